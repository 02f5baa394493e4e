// tests/scenes/two_blocks.geo with the upper block 3 mm to the right: its last
// 3 mm overhang the lower block, and the closest points of its contact points
// there are held at the master's end (tests/contact_jacobian.cc). Two stacked
// 10 x 5 mm blocks touching along y = 0, with non-matching meshes
// (4 and 5 cells along the interface); the bodies share no Gmsh entity, so
// their nodes on the interface are distinct (tests/two_body_sliding.py).
Geometry.AutoCoherence = 0;
Point(1) = {0, -5, 0}; Point(2) = {10, -5, 0}; Point(3) = {10, 0, 0}; Point(4) = {0, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 5; Transfinite Curve{2, 4} = 3;
Transfinite Surface{1}; Recombine Surface{1};
Point(5) = {3, 0, 0}; Point(6) = {13, 0, 0}; Point(7) = {13, 5, 0}; Point(8) = {3, 5, 0};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Transfinite Curve{5, 7} = 6; Transfinite Curve{6, 8} = 3;
Transfinite Surface{2}; Recombine Surface{2};
Physical Curve("lower_bottom") = {1};
Physical Curve("lower_top") = {3};
Physical Curve("lower_left") = {4};
Physical Curve("upper_bottom") = {5};
Physical Curve("upper_top") = {7};
Physical Curve("upper_left") = {8};
Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
