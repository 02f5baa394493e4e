// Cook's membrane (Cook 1974; the standard locking benchmark, e.g. Simo &
// Rifai 1990): a tapered panel with the corners (0, 0), (48, 44), (48, 60),
// (0, 44) mm, clamped on its left edge and sheared on its right edge, meshed
// with n x n quadrilaterals (transfinite, recombined). A file that sets `n`
// and includes this one changes the mesh.
If (!Exists(n))
  n = 8;
EndIf
Point(1) = {0, 0, 0};
Point(2) = {48, 44, 0};
Point(3) = {48, 60, 0};
Point(4) = {0, 44, 0};
Line(1) = {1, 2};  // lower edge
Line(2) = {2, 3};  // right edge: the shear load
Line(3) = {3, 4};  // upper edge
Line(4) = {4, 1};  // left edge: clamped
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n + 1;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("lower") = {1};
Physical Curve("right") = {2};
Physical Curve("upper") = {3};
Physical Curve("left") = {4};
Physical Surface("membrane") = {1};
