// A unit square of quadrilaterals whose surface runs clockwise (normal -z):
// its elements are inverted for a 2D code; refused with advice.
//   gmsh -2 clockwise.geo -format msh41 -o clockwise.msh
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 4};
Line(2) = {4, 3};
Line(3) = {3, 2};
Line(4) = {2, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 3;
Transfinite Surface{1};
Recombine Surface{1};
Physical Surface("body") = {1};
