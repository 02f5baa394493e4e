// Two equal elastic cylinders of radius R touching at the origin, plane strain
// (prm/two_cylinders.prm). The upper body is the lower half disc of the upper
// cylinder (centre (0, R), flat top y = R), the lower body the upper half disc
// of the lower cylinder (centre (0, -R), flat bottom y = -R). Each curved
// boundary is split at the origin (a node there on both bodies); the bodies
// share no point or curve, so their nodes are distinct.
//
// Quadrilaterals: frontal-Delaunay for quads, recombined, then every cell
// subdivided once (Mesh.SubdivisionAlgorithm = 1: quads into 4, any triangle
// left into 3), which guarantees an all-quad mesh and halves the sizes set
// below. Size fields: fine within r_fine of the contact point, growing
// linearly to coarse at r_coarse; the fine sizes of the two bodies differ, so
// the meshes do not match on the contact zone. Final sizes (after the
// subdivision): h_upper = 0.25 mm, h_lower = 0.3 mm near the contact,
// about 5 mm far from it.
R = 50;
h_upper = 0.25;   // final cell size near the contact, upper body
h_lower = 0.3;    // final cell size near the contact, lower body
h_far = 5;        // final cell size far from the contact
r_fine = 6;       // radius of the fine zone around the origin
r_coarse = 40;    // distance at which the size reaches h_far

// upper body: lower half disc of the cylinder centred at (0, R)
Point(1) = {0, R, 0};      // centre
Point(2) = {-R, R, 0};
Point(3) = {0, 0, 0};      // contact point
Point(4) = {R, R, 0};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 2};          // flat top
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

// lower body: upper half disc of the cylinder centred at (0, -R)
Point(11) = {0, -R, 0};    // centre
Point(12) = {R, -R, 0};
Point(13) = {0, 0, 0};     // contact point, a point of its own
Point(14) = {-R, -R, 0};
Circle(11) = {12, 11, 13};
Circle(12) = {13, 11, 14};
Line(13) = {14, 12};       // flat bottom
Curve Loop(11) = {11, 12, 13};
Plane Surface(11) = {11};

// size fields (sizes before the subdivision: twice the final ones)
Field[1] = Distance;
Field[1].NodesList = {3};
Field[2] = Threshold;
Field[2].IField = 1;
Field[2].LcMin = 2 * h_upper;
Field[2].LcMax = 2 * h_far;
Field[2].DistMin = r_fine;
Field[2].DistMax = r_coarse;
Field[3] = Restrict;
Field[3].IField = 2;
Field[3].FacesList = {1};
Field[3].EdgesList = {1, 2, 3};

Field[11] = Distance;
Field[11].NodesList = {13};
Field[12] = Threshold;
Field[12].IField = 11;
Field[12].LcMin = 2 * h_lower;
Field[12].LcMax = 2 * h_far;
Field[12].DistMin = r_fine;
Field[12].DistMax = r_coarse;
Field[13] = Restrict;
Field[13].IField = 12;
Field[13].FacesList = {11};
Field[13].EdgesList = {11, 12, 13};

Field[20] = Min;
Field[20].FieldsList = {3, 13};
Background Field = 20;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

Mesh.Algorithm = 6;               // frontal-Delaunay (8, the quad variant, crashes Gmsh 4.8.4 here)
Mesh.RecombinationAlgorithm = 1;  // blossom
Mesh.RecombineAll = 1;
Mesh.SubdivisionAlgorithm = 1;    // all quadrilaterals

Physical Curve("upper_contact") = {1, 2};
Physical Curve("upper_top") = {3};
Physical Curve("lower_contact") = {11, 12};
Physical Curve("lower_bottom") = {13};
Physical Surface("upper") = {1};
Physical Surface("lower") = {11};
