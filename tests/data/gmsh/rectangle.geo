// A 2 x 1 rectangle meshed with 8 x 4 structured quadrilaterals: the same
// grid as a [mesh] type = "box" with cells = [8, 4] (tests/mesh/gmsh_reader_test.cpp).
//   gmsh -2 rectangle.geo -format msh41 -o rectangle.msh
//   gmsh -2 rectangle.geo -format msh22 -o rectangle_v22.msh
Point(1) = {0, 0, 0};
Point(2) = {2, 0, 0};
Point(3) = {2, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 9;
Transfinite Curve{2, 4} = 5;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("left") = {4};
Physical Curve("right") = {2};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Point("origin") = {1};
Physical Surface("body") = {1};
