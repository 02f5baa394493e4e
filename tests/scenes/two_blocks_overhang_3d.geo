// tests/scenes/two_blocks_3d.geo with the upper block moved by (3, 2) mm: it
// overhangs the lower block along x and y, and the closest points of its
// contact points there are held at the master's edges and corner
// (tests/contact_jacobian.cc). Two stacked 10 x 10 x 5 mm blocks of
// hexahedra touching along z = 0, with
// non-matching meshes (3 x 3 and 4 x 4 faces on the interface)
// (tests/two_body_sliding.py).
Geometry.AutoCoherence = 0;
Point(1) = {0, 0, -5}; Point(2) = {10, 0, -5}; Point(3) = {10, 10, -5}; Point(4) = {0, 10, -5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 4; Transfinite Surface{1}; Recombine Surface{1};
lower[] = Extrude{0, 0, 5}{Surface{1}; Layers{2}; Recombine;};
Point(101) = {3, 2, 0}; Point(102) = {13, 2, 0}; Point(103) = {13, 12, 0}; Point(104) = {3, 12, 0};
Line(101) = {101, 102}; Line(102) = {102, 103}; Line(103) = {103, 104}; Line(104) = {104, 101};
Curve Loop(101) = {101, 102, 103, 104}; Plane Surface(101) = {101};
Transfinite Curve{101, 102, 103, 104} = 5; Transfinite Surface{101}; Recombine Surface{101};
upper[] = Extrude{0, 0, 5}{Surface{101}; Layers{2}; Recombine;};
Physical Surface("lower_bottom") = {1};
Physical Surface("lower_top") = {lower[0]};
Physical Surface("lower_x0") = {lower[5]};
Physical Surface("lower_y0") = {lower[2]};
Physical Surface("upper_bottom") = {101};
Physical Surface("upper_top") = {upper[0]};
Physical Surface("upper_x0") = {upper[5]};
Physical Surface("upper_y0") = {upper[2]};
Physical Volume("lower") = {lower[1]};
Physical Volume("upper") = {upper[1]};
