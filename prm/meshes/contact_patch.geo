// Taylor-Papadopoulos contact patch test (prm/contact_patch_test.prm): two
// stacked 10 x 5 mm blocks, the lower one in -5 < y < 0, the upper one in
// 0 < y < 5, meshed with quadrilaterals (transfinite, recombined). The two
// blocks share no point or curve: their nodes on the interface y = 0 are
// distinct, and the meshes there do not match: 4 cells along x below, graded
// (each 1.3 times the previous one from the left face), 5 equal cells above;
// with one global refinement 8 and 10, and no interior node of the interface
// coincides with one of the other body.
length = 10;
height = 5;
nx_lower = 4;   // cells along x, lower block, graded
grading = 1.3;  // ratio of consecutive cells along x, lower block
nx_upper = 5;   // cells along x, upper block
ny = 2;         // cells along y, each block

// lower block
Point(1) = {0, -height, 0};
Point(2) = {length, -height, 0};
Point(3) = {length, 0, 0};
Point(4) = {0, 0, 0};
Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // right
Line(3) = {3, 4};   // top (the interface)
Line(4) = {4, 1};   // left
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1} = nx_lower + 1 Using Progression grading;       // left to right
Transfinite Curve{3} = nx_lower + 1 Using Progression 1 / grading;   // right to left
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};
Recombine Surface{1};

// upper block: its own points on y = 0
Point(11) = {0, 0, 0};
Point(12) = {length, 0, 0};
Point(13) = {length, height, 0};
Point(14) = {0, height, 0};
Line(11) = {11, 12};   // bottom (the interface)
Line(12) = {12, 13};   // right
Line(13) = {13, 14};   // top
Line(14) = {14, 11};   // left
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
Transfinite Curve{11, 13} = nx_upper + 1;
Transfinite Curve{12, 14} = ny + 1;
Transfinite Surface{11};
Recombine Surface{11};

Physical Curve("lower_bottom") = {1};
Physical Curve("lower_right") = {2};
Physical Curve("lower_top") = {3};
Physical Curve("lower_left") = {4};
Physical Curve("upper_bottom") = {11};
Physical Curve("upper_right") = {12};
Physical Curve("upper_top") = {13};
Physical Curve("upper_left") = {14};
Physical Surface("lower") = {1};
Physical Surface("upper") = {11};
