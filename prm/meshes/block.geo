// A 100 x 50 mm block resting on y = 0, meshed with quadrilaterals
// (transfinite, recombined). Physical groups name the boundaries and the body
// so that a scene refers to them by name (prm/gmsh_block.prm).
length = 100;
height = 50;
nx = 16;   // cells along x
ny = 8;    // cells along y

Point(1) = {-length/2, 0, 0};
Point(2) = { length/2, 0, 0};
Point(3) = { length/2, height, 0};
Point(4) = {-length/2, height, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};
Recombine Surface{1};

Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("block") = {1};
