// A half cylinder (R = 10 mm, flat top y = 10) touching a block 30 x 10 mm at one point;
// the bodies are kept apart (AutoCoherence = 0), non-matching quadrilaterals. @ARC@ nodes
// on each quarter arc, @TOP@ along the block's top, @SIDE@ along its sides, cells at most
// @H@ mm: tests/sltest.py cylinder_on_block_geo() replaces them.
Geometry.AutoCoherence = 0;
R = 10;
Point(1) = {0, R, 0};
Point(2) = {-R, R, 0};
Point(3) = {0, 0, 0};
Point(4) = {R, R, 0};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Transfinite Curve{1, 2} = @ARC@;
Point(11) = {-15, -10, 0};
Point(12) = {15, -10, 0};
Point(13) = {15, 0, 0};
Point(14) = {-15, 0, 0};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
Transfinite Curve{11, 13} = @TOP@;
Transfinite Curve{12, 14} = @SIDE@;
Transfinite Surface{11};
Mesh.CharacteristicLengthMax = @H@;
Recombine Surface{1, 11};
Mesh.SubdivisionAlgorithm = 1;
Physical Curve("cyl_contact") = {1, 2};
Physical Curve("cyl_top") = {3};
Physical Curve("blk_contact") = {13};
Physical Curve("blk_bottom") = {11};
Physical Surface("cylinder") = {1};
Physical Surface("block") = {11};
