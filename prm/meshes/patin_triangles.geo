// The patin of the seed paper (§3, Fig. 2), 100 x 50 mm, meshed with
// unstructured triangles as in the paper ("des éléments triangulaires").
// The element size h gives about the nodes of the 32 x 16 quadrilaterals of
// prm/patin_elastic.prm. Physical groups name the boundaries and the body.
length = 100;
height = 50;
h = 3.125;  // element size (mm)

Point(1) = {-length/2, 0, 0, h};
Point(2) = { length/2, 0, 0, h};
Point(3) = { length/2, height, 0, h};
Point(4) = {-length/2, height, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("patin") = {1};
