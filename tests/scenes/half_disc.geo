// A half disc of radius 10 mm (the cylinder of a 2D Hertz problem): centre
// (0, 10), the arc below it touching y = 0 at the origin, the flat side y = 10
// on top. Coarse quadrilaterals, so that refinement shows whether the new
// vertices follow the arc. Physical groups: "contact" (the arc), "top", the
// surface "disc".
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
Mesh.CharacteristicLengthMax = 4;
Recombine Surface{1};
Mesh.SubdivisionAlgorithm = 1;  // quadrilaterals only
Physical Curve("contact") = {1, 2};
Physical Curve("top") = {3};
Physical Surface("disc") = {1};
