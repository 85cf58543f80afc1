// Plate 8 x 8 mm with a circular hole of radius 1 mm at its centre: the true circle of
// examples/hole_plate_2d (which removes the cells of a box grid, a stair-stepped hole), meshed with
// unstructured quadrilaterals of size 1/6 mm (the box grid's h). The mid-edge points (4, 0) and
// (4, 8) are mesh nodes, for the symmetric minimal constraint u_x = 0.
//   gmsh -2 plate.geo -format msh41 -o plate.msh
h = 0.19;
Point(1) = {0, 0, 0, h};
Point(2) = {4, 0, 0, h};
Point(3) = {8, 0, 0, h};
Point(4) = {8, 8, 0, h};
Point(5) = {4, 8, 0, h};
Point(6) = {0, 8, 0, h};
Point(7) = {4, 4, 0, h};  // hole centre
Point(8) = {5, 4, 0, h};
Point(9) = {4, 5, 0, h};
Point(10) = {3, 4, 0, h};
Point(11) = {4, 3, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Circle(7) = {8, 7, 9};
Circle(8) = {9, 7, 10};
Circle(9) = {10, 7, 11};
Circle(10) = {11, 7, 8};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Curve Loop(2) = {7, 8, 9, 10};
Plane Surface(1) = {1, 2};
Mesh.Algorithm = 6;               // frontal-Delaunay (8, its quadrilateral variant, crashes Gmsh 4.8.4)
Mesh.RecombinationAlgorithm = 1;  // blossom
Recombine Surface{1};
Physical Curve("bottom") = {1, 2};
Physical Curve("top") = {4, 5};
Physical Curve("hole") = {7, 8, 9, 10};
Physical Point("mid_bottom") = {2};
Physical Point("mid_top") = {5};
Physical Surface("plate") = {1};
