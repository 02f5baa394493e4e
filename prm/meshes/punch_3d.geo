// A filleted half-cylinder punch on an elastic block, 3D (prm/punch_3d_friction.prm).
// Gmsh OpenCASCADE kernel; all hexahedra.
//
// Punch: the lower half of a cylinder of radius R = 5 mm, axis along y
// (0 < y < L = 10 mm) at height z = R, with its two end circles rounded by
// fillets of radius f = 1 mm (a straight-ended cylinder would put an edge of
// the punch into the contact zone at y = 0 and y = L). Its flat top, z = R,
// is the surface "punch_top"; the rest of its boundary (the curved side and
// the filleted ends) is "punch_contact" (the slave surface). It touches the
// block along the line x = 0, z = 0 (initial gap zero there).
// Block: -W < x < W, -B < y < L + B, -H < z < 0 (W = 8, B = 2, H = 4 mm),
// wider than the punch and its 0.2 mm of sliding; its top z = 0 is
// "block_top" (the master surface), its bottom z = -H "block_bottom".
// Volumes "punch" and "block". The bodies share no point or surface
// (Geometry.AutoCoherence = 0), so their nodes are distinct.
//
// Hexahedra: each tetrahedron of the Delaunay mesh split into four hexahedra
// (Mesh.SubdivisionAlgorithm = 2), which halves the sizes set below. The size
// is hc (about 1 mm after the split) in a box around the contact line,
// |x| < 2.5, |z| < 1.5, growing to hf outside it. This is the coarsest mesh
// that still shows the sliding of the punch: 1580 cells, 4 contact nodes
// along the contact line (with hc = 2.5, 1240 cells, no node of the punch
// touches the block). Halve hc and hf for a finer one.
SetFactory("OpenCASCADE");
Geometry.AutoCoherence = 0;
R = 5;      // punch radius
L = 10;     // punch length (along y)
f = 1;      // fillet radius of the punch's ends
W = 8;      // block half-width (x)
B = 2;      // block overhang beyond the punch's ends (y)
H = 4;      // block height (z)
hc = 2;     // size near the contact line (before the subdivision)
hf = 5;     // size elsewhere (before the subdivision)
e = 1e-6;   // tolerance of the bounding-box selections

// punch: a full cylinder with filleted end circles, cut to its lower half
Cylinder(1) = {0, 0, R, 0, L, 0, R};
c() = Curve In BoundingBox{-R-e, -e, -e, R+e, e, 2*R+e};
c() += Curve In BoundingBox{-R-e, L-e, -e, R+e, L+e, 2*R+e};
fl() = Fillet{1}{c()}{f};
Box(3) = {-R-1, -1, R, 2*R+2, L+2, R+1};
punch() = BooleanDifference{Volume{fl(0)}; Delete;}{Volume{3}; Delete;};

// block
Box(10) = {-W, -B, -H, 2*W, L+2*B, H};

ptop() = Surface In BoundingBox{-R-e, -e, R-e, R+e, L+e, R+e};
pall() = Boundary{Volume{punch(0)};};
btop() = Surface In BoundingBox{-W-e, -B-e, -e, W+e, L+B+e, e};
bbot() = Surface In BoundingBox{-W-e, -B-e, -H-e, W+e, L+B+e, -H+e};
Physical Surface("punch_top") = {ptop()};
pc() = pall();
pc() -= ptop();
Physical Surface("punch_contact") = {pc()};
Physical Surface("block_top") = {btop()};
Physical Surface("block_bottom") = {bbot()};
Physical Volume("punch") = {punch(0)};
Physical Volume("block") = {10};

// sizes: hc in a box around the contact line, hf elsewhere
Field[1] = Box;
Field[1].VIn = hc; Field[1].VOut = hf;
Field[1].XMin = -2.5; Field[1].XMax = 2.5; Field[1].YMin = -1; Field[1].YMax = L+1;
Field[1].ZMin = -1.5; Field[1].ZMax = 1.5; Field[1].Thickness = 3;
Background Field = 1;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.SubdivisionAlgorithm = 2;
Mesh.MshFileVersion = 2.2;
