// A 10 x 10 x 5 mm block of hexahedra (4 x 4 faces on its bottom, the slave
// upper_bottom) resting at z = 0 on a body whose top (the master lower_top,
// 3 x 3 faces) is a cylinder of radius R = 30 mm about an axis along y, its
// crest at x = 5, z = 0 (tests/contact_jacobian.cc: the linearised pairing
// on a curved deformable master, whose faces' normals differ by 0.11 rad).
Geometry.AutoCoherence = 0;
R = 30;
zt = -R + Sqrt(R * R - 25);
Point(1) = {0, 0, -5}; Point(2) = {10, 0, -5}; Point(3) = {10, 10, -5}; Point(4) = {0, 10, -5};
Point(5) = {0, 0, zt}; Point(6) = {10, 0, zt}; Point(7) = {10, 10, zt}; Point(8) = {0, 10, zt};
Point(9) = {5, 0, -R}; Point(10) = {5, 10, -R};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Circle(5) = {5, 9, 6}; Line(6) = {6, 7}; Circle(7) = {7, 10, 8}; Line(8) = {8, 5};
Line(9) = {1, 5}; Line(10) = {2, 6}; Line(11) = {3, 7}; Line(12) = {4, 8};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Surface(2) = {2};
Curve Loop(3) = {1, 10, -5, -9}; Plane Surface(3) = {3};
Curve Loop(4) = {2, 11, -6, -10}; Plane Surface(4) = {4};
Curve Loop(5) = {3, 12, -7, -11}; Plane Surface(5) = {5};
Curve Loop(6) = {4, 9, -8, -12}; Plane Surface(6) = {6};
Surface Loop(1) = {1, 2, 3, 4, 5, 6}; Volume(1) = {1};
Transfinite Curve{1, 2, 3, 4, 5, 6, 7, 8} = 4; Transfinite Curve{9, 10, 11, 12} = 3;
Transfinite Surface{1, 2, 3, 4, 5, 6}; Recombine Surface{1, 2, 3, 4, 5, 6};
Transfinite Volume{1};
Point(101) = {0, 0, 0}; Point(102) = {10, 0, 0}; Point(103) = {10, 10, 0}; Point(104) = {0, 10, 0};
Line(101) = {101, 102}; Line(102) = {102, 103}; Line(103) = {103, 104}; Line(104) = {104, 101};
Curve Loop(101) = {101, 102, 103, 104}; Plane Surface(101) = {101};
Transfinite Curve{101, 102, 103, 104} = 5; Transfinite Surface{101}; Recombine Surface{101};
upper[] = Extrude{0, 0, 5}{Surface{101}; Layers{2}; Recombine;};
Physical Surface("lower_bottom") = {1};
Physical Surface("lower_top") = {2};
Physical Surface("upper_bottom") = {101};
Physical Surface("upper_top") = {upper[0]};
Physical Volume("lower") = {1};
Physical Volume("upper") = {upper[1]};
