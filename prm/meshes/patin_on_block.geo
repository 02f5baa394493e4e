// The elastic patin of prm/gmsh_block.prm on a deformable lower block
// (prm/patin_deformable_block.prm). The patin is the mesh of
// prm/meshes/block.geo, point for point: 100 x 50 mm, -50 < x < 50,
// 0 < y < 50, 16 x 8 quadrilaterals. The lower block is 120 x 30 mm,
// -60 < x < 60, -30 < y < 0, 20 x 5 quadrilaterals: its top (6 mm cells) and
// the patin's bottom (6.25 mm cells) do not match. The bodies share no point
// or curve, so their nodes on y = 0 are distinct.
length = 100;
height = 50;
nx = 16;   // cells along x, patin
ny = 8;    // cells along y, patin
lower_length = 120;
lower_height = 30;
lower_nx = 20;   // cells along x, lower block
lower_ny = 5;    // cells along y, lower block

// the patin (as prm/meshes/block.geo)
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

// the lower block
Point(11) = {-lower_length/2, -lower_height, 0};
Point(12) = { lower_length/2, -lower_height, 0};
Point(13) = { lower_length/2, 0, 0};
Point(14) = {-lower_length/2, 0, 0};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
Transfinite Curve{11, 13} = lower_nx + 1;
Transfinite Curve{12, 14} = lower_ny + 1;
Transfinite Surface{11};
Recombine Surface{11};

Physical Curve("patin_bottom") = {1};
Physical Curve("patin_right") = {2};
Physical Curve("patin_top") = {3};
Physical Curve("patin_left") = {4};
Physical Curve("lower_bottom") = {11};
Physical Curve("lower_right") = {12};
Physical Curve("lower_top") = {13};
Physical Curve("lower_left") = {14};
Physical Surface("patin") = {1};
Physical Surface("lower") = {11};
