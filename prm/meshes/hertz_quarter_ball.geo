// A quarter of the lower half of a ball of radius R (prm/hertz_sphere_gmsh.prm):
// centre (0, 0, R), south pole at the origin where the ball touches the rigid
// plane z = 0, flat top z = R (the loaded face), symmetry planes x = 0 and
// y = 0. Physical groups: "contact" (the spherical surface), "top", "x min",
// "y min" and the volume "ball".
//
// Hexahedra as a general-purpose mesher gives them: tetrahedra, each
// subdivided into four hexahedra (Mesh.SubdivisionAlgorithm = 2), so the
// faces on the contact surface are general quadrilaterals (thirds of
// triangles), not parallelograms. Size field: h_contact within r_fine of the
// south pole, growing linearly to h_far at r_coarse.
//
// Refinement: every size is multiplied by size_factor (1 unless the including
// file sets it first, as contrib/benchmark_hertz_gmsh.py does), and the mesh
// is made anew; a uniform refinement of the coarse hexahedra would keep the
// facets of the coarse sphere.
If (!Exists(size_factor))
  size_factor = 1;
EndIf
R = 50;
h_contact = 0.6 * size_factor;  // size near the south pole (before subdivision)
h_far = 16 * size_factor;       // size far from it (before subdivision)
r_fine = 2.5;                   // radius of the fine zone (Hertz: a ~ 1.5 mm at P = 20 kN)
r_coarse = 40;                  // distance at which the size reaches h_far

Point(1) = {0, 0, R};   // centre
Point(2) = {0, 0, 0};   // south pole, the contact point
Point(3) = {R, 0, R};
Point(4) = {0, R, R};
Circle(1) = {2, 1, 3};  // meridian in y = 0
Circle(2) = {3, 1, 4};  // equator quarter at z = R
Circle(3) = {4, 1, 2};  // meridian in x = 0
Line(4) = {1, 2};       // axis
Line(5) = {1, 3};
Line(6) = {1, 4};

Curve Loop(1) = {1, 2, 3};
Surface(1) = {1} In Sphere {1};     // spherical surface
Curve Loop(2) = {5, 2, -6};
Plane Surface(2) = {2};             // top z = R
Curve Loop(3) = {4, 1, -5};
Plane Surface(3) = {3};             // y = 0
Curve Loop(4) = {6, 3, -4};
Plane Surface(4) = {4};             // x = 0
Surface Loop(1) = {1, 2, 3, 4};
Volume(1) = {1};

Field[1] = Distance;
Field[1].NodesList = {2};
Field[2] = Threshold;
Field[2].IField = 1;
Field[2].LcMin = h_contact;
Field[2].LcMax = h_far;
Field[2].DistMin = r_fine;
Field[2].DistMax = r_coarse;
Background Field = 2;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthFromCurvature = 0;
Mesh.SubdivisionAlgorithm = 2;

Physical Surface("contact") = {1};
Physical Surface("top") = {2};
Physical Surface("y min") = {3};
Physical Surface("x min") = {4};
Physical Volume("ball") = {1};
