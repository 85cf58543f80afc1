// A 2 x 1 x 1 block of 4 x 2 x 2 hexahedra (a recombined transfinite square
// extruded in layers), with two physical volumes (x < 1 and x > 1).
//   gmsh -3 block.geo -format msh41 -o block.msh
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {2, 0, 0};
Point(4) = {2, 1, 0};
Point(5) = {1, 1, 0};
Point(6) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Transfinite Curve{1, 2, 3, 4, 5, 6, 7} = 3;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};
left[] = Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; };
right[] = Extrude {0, 0, 1} { Surface{2}; Layers{2}; Recombine; };
Physical Volume("soft") = {left[1]};
Physical Volume("hard") = {right[1]};
Physical Surface("xmin_face") = {left[5]};
Physical Surface("top_face") = {left[0], right[0]};
Physical Curve("edge") = {1};
