// The quarter ball of hertz_quarter_ball.geo with its tetrahedra kept (not
// subdivided into hexahedra), every size multiplied by 0.35: the contact
// faces are triangles of about 0.2 mm at the south pole (a ~ 1.5 mm).
size_factor = 0.35;
Include "hertz_quarter_ball.geo";
Mesh.SubdivisionAlgorithm = 0;
