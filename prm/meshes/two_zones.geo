// A 100 x 50 mm block resting on y = 0 whose bottom is two contact zones:
// "bottom_left" (x < 0) and "bottom_right" (x > 0), quadrilaterals
// (transfinite, recombined); prm/two_zones.prm gives each its own friction law.
length = 100;
height = 50;
nx = 8;    // cells along x in each half
ny = 8;    // cells along y

Point(1) = {-length/2, 0, 0};
Point(2) = {0, 0, 0};
Point(3) = { length/2, 0, 0};
Point(4) = { length/2, height, 0};
Point(5) = {0, height, 0};
Point(6) = {-length/2, height, 0};
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
Transfinite Curve{1, 2, 4, 5} = nx + 1;
Transfinite Curve{3, 6, 7} = ny + 1;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};

Physical Curve("bottom_left") = {1};
Physical Curve("bottom_right") = {2};
Physical Curve("right") = {3};
Physical Curve("top") = {4, 5};
Physical Curve("left") = {6};
Physical Surface("block") = {1, 2};
