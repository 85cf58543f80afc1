// A 2 x 2 square with an edge crack from (0, 1) to (1, 1): two surfaces meet
// along y = 1; the segment x < 1 is the physical curve "crack" (a pre-crack,
// [mesh] precrack = "crack"), the segment x > 1 the ligament. 4 x 4 quads.
//   gmsh -2 edge_crack.geo -format msh41 -o edge_crack.msh
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
Physical Curve("crack") = {7};
Physical Curve("bottom") = {1};
Physical Curve("top") = {4};
Physical Surface("plate") = {1, 2};
