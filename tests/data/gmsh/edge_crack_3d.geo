// The square of edge_crack.geo extruded to a 2 x 2 x 1 block of 4 x 4 x 2 hexahedra: the edge crack
// becomes the physical surface "crack" (x < 1, y = 1, all z), a pre-crack ([mesh] precrack = "crack")
// that tests/setup/gmsh_case_test.cpp compares with the box's [[mesh.cut]] parallelogram.
//   gmsh -3 edge_crack_3d.geo -format msh41 -o edge_crack_3d.msh
Point(1) = {0, 0, 0};
Point(2) = {2, 0, 0};
Point(3) = {2, 1, 0};
Point(4) = {2, 2, 0};
Point(5) = {0, 2, 0};
Point(6) = {0, 1, 0};
Point(7) = {1, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {6, 7};
Line(8) = {7, 3};
Curve Loop(1) = {1, 2, -8, -7, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {7, 8, 3, 4, 5};
Plane Surface(2) = {2};
Transfinite Curve{1, 4} = 5;
Transfinite Curve{7, 8} = 3;
Transfinite Curve{2, 3, 5, 6} = 3;
Transfinite Surface{1} = {1, 2, 3, 6};
Transfinite Surface{2} = {6, 3, 4, 5};
Recombine Surface{1, 2};
lower[] = Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; };
upper[] = Extrude {0, 0, 1} { Surface{2}; Layers{2}; Recombine; };
// lower[]: top face, volume, then the faces swept by curves 1, 2, -8, -7, 6 of loop 1.
Physical Surface("crack") = {lower[5]};
Physical Surface("bottom") = {lower[2]};
Physical Surface("top") = {upper[5]};
Physical Volume("block") = {lower[1], upper[1]};
