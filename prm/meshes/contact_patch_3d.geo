// Contact patch test in 3D (prm/contact_patch_test_3d.prm): two stacked
// 10 x 10 x 5 mm blocks, the lower one in -5 < z < 0, the upper one in
// 0 < z < 5, meshed with hexahedra (transfinite, recombined bottoms extruded
// in layers). The blocks share no point: their nodes on the interface z = 0
// are distinct and the meshes there do not match: below 4 x 3 cells graded
// along x and y (ratios 1.3 and 1.2), above 5 x 5 equal cells; with one global
// refinement 8 x 6 and 10 x 10, and no interior node of the interface
// coincides with one of the other body.
Geometry.AutoCoherence = 0;  // keep the blocks' interface nodes distinct
length = 10;
height = 5;
nx_lower = 4;    // cells along x, lower block, graded
ny_lower = 3;    // cells along y, lower block, graded
grading_x = 1.3;
grading_y = 1.2;
n_upper = 5;     // cells along x and y, upper block
nz = 2;          // cell layers along z, each block

// lower block: its bottom at z = -height, extruded up to the interface
Point(1) = {0, 0, -height};
Point(2) = {length, 0, -height};
Point(3) = {length, length, -height};
Point(4) = {0, length, -height};
Line(1) = {1, 2};   // y = 0
Line(2) = {2, 3};   // x = length
Line(3) = {3, 4};   // y = length
Line(4) = {4, 1};   // x = 0
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1} = nx_lower + 1 Using Progression grading_x;
Transfinite Curve{3} = nx_lower + 1 Using Progression 1 / grading_x;
Transfinite Curve{2} = ny_lower + 1 Using Progression grading_y;
Transfinite Curve{4} = ny_lower + 1 Using Progression 1 / grading_y;
Transfinite Surface{1};
Recombine Surface{1};
// lower[0]: the top (the interface), lower[1]: the volume, lower[2..5]: the sides swept by lines 1..4
lower[] = Extrude {0, 0, height} { Surface{1}; Layers{nz}; Recombine; };

// upper block: its own points on z = 0
Point(101) = {0, 0, 0};
Point(102) = {length, 0, 0};
Point(103) = {length, length, 0};
Point(104) = {0, length, 0};
Line(101) = {101, 102};
Line(102) = {102, 103};
Line(103) = {103, 104};
Line(104) = {104, 101};
Curve Loop(101) = {101, 102, 103, 104};
Plane Surface(101) = {101};
Transfinite Curve{101, 102, 103, 104} = n_upper + 1;
Transfinite Surface{101};
Recombine Surface{101};
upper[] = Extrude {0, 0, height} { Surface{101}; Layers{nz}; Recombine; };

Physical Surface("lower_bottom") = {1};
Physical Surface("lower_top") = {lower[0]};
Physical Surface("lower_front") = {lower[2]};
Physical Surface("lower_right") = {lower[3]};
Physical Surface("lower_back") = {lower[4]};
Physical Surface("lower_left") = {lower[5]};
Physical Surface("upper_bottom") = {101};
Physical Surface("upper_top") = {upper[0]};
Physical Surface("upper_front") = {upper[2]};
Physical Surface("upper_right") = {upper[3]};
Physical Surface("upper_back") = {upper[4]};
Physical Surface("upper_left") = {upper[5]};
Physical Volume("lower") = {lower[1]};
Physical Volume("upper") = {upper[1]};
