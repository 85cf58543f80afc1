// Single-edge U-notched tension specimen, 4 x 6 x 0.5 mm (x, y, z): a notch 0.3 mm wide with a
// semicircular root of radius 0.15 mm enters from the edge x = 0 at mid-height (y = 3) to a depth of
// 1.2 mm. The outline is meshed with unstructured quadrilaterals (0.2 mm, 0.1 mm at the notch root)
// and extruded through the thickness in 2 layers of hexahedra.
//   gmsh -3 specimen.geo -format msh41 -o specimen.msh
h = 0.2;
hr = 0.1;
Point(1) = {0, 0, 0, h};
Point(2) = {4, 0, 0, h};
Point(3) = {4, 6, 0, h};
Point(4) = {0, 6, 0, h};
Point(5) = {0, 3.15, 0, hr * 2};
Point(6) = {1.05, 3.15, 0, hr};
Point(7) = {1.05, 3.0, 0, hr};  // centre of the notch root
Point(8) = {1.2, 3.0, 0, hr};
Point(9) = {1.05, 2.85, 0, hr};
Point(10) = {0, 2.85, 0, hr * 2};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Circle(6) = {6, 7, 8};
Circle(7) = {8, 7, 9};
Line(8) = {9, 10};
Line(9) = {10, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8, 9};
Plane Surface(1) = {1};
Mesh.Algorithm = 6;               // frontal-Delaunay (8, its quadrilateral variant, crashes Gmsh 4.8.4)
Mesh.RecombinationAlgorithm = 1;  // blossom
Recombine Surface{1};
out[] = Extrude {0, 0, 0.5} { Surface{1}; Layers{2}; Recombine; };
// out[0]: the top face (z = 0.5), out[1]: the volume, out[2 ...]: the faces swept by curves 1 ... 9.
Physical Volume("specimen") = {out[1]};
Physical Surface("bottom") = {out[2]};       // y = 0
Physical Surface("top") = {out[4]};          // y = 6
Physical Surface("notch") = {out[6], out[7], out[8], out[9]};
Physical Curve("pin_line") = {1};            // y = 0, z = 0: the bottom edge of the back face
Physical Point("pin") = {1};                 // (0, 0, 0)
