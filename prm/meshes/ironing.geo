// Ironing (prm/ironing.prm): a stiff rounded die pressed into a soft block and
// dragged along it, plane strain. The die is the lower half disc of a circle
// of radius R centred at (x0, R), with a flat top y = R; it touches the block
// at (x0, 0). The block is 40 x 10 mm, -20 < x < 20, -10 < y < 0. The bodies
// share no point or curve.
//
// Every cell of both bodies is subdivided once at the end
// (Mesh.SubdivisionAlgorithm = 1, needed for an all-quadrilateral die: quads
// into 4, any triangle into 3), which halves the sizes set below.
// Block: 40 x 6 transfinite quadrilaterals, graded along y (finer at the
// top), hence 80 x 12 cells, 0.5 mm along x. Die: frontal-Delaunay triangles
// recombined, then subdivided: about 0.15 mm on the arc near the bottom of the
// die, 0.5 mm at its top corners.
R = 4;
x0 = -5;
block_length = 40;
block_height = 10;
block_nx = 40;   // 80 after the subdivision
block_ny = 6;    // 12 after the subdivision
h_die_bottom = 0.15;   // final cell size at the die's bottom
h_die_top = 0.5;       // final cell size at the die's top corners

// the block
Point(1) = {-block_length/2, -block_height, 0};
Point(2) = { block_length/2, -block_height, 0};
Point(3) = { block_length/2, 0, 0};
Point(4) = {-block_length/2, 0, 0};
Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // right, upwards
Line(3) = {3, 4};   // top
Line(4) = {4, 1};   // left, downwards
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = block_nx + 1;
Transfinite Curve{2} = block_ny + 1 Using Progression 0.7;     // cells shrink upwards
Transfinite Curve{4} = block_ny + 1 Using Progression 1/0.7;   // the same, downwards
Transfinite Surface{1};
Recombine Surface{1};

// the die (sizes at its points: twice the final ones, halved by the subdivision)
Point(11) = {x0, R, 0};                    // centre
Point(12) = {x0 - R, R, 0, 2 * h_die_top};
Point(13) = {x0, 0, 0, 2 * h_die_bottom}; // bottom, a point of its own
Point(14) = {x0 + R, R, 0, 2 * h_die_top};
Circle(11) = {12, 11, 13};
Circle(12) = {13, 11, 14};
Line(13) = {14, 12};                       // flat top
Curve Loop(11) = {11, 12, 13};
Plane Surface(11) = {11};
Recombine Surface{11};

Mesh.Algorithm = 6;              // frontal-Delaunay
Mesh.RecombinationAlgorithm = 1; // blossom
Mesh.SubdivisionAlgorithm = 1;   // all quadrilaterals

Physical Curve("block_bottom") = {1};
Physical Curve("block_right") = {2};
Physical Curve("block_top") = {3};
Physical Curve("block_left") = {4};
Physical Curve("die_contact") = {11, 12};
Physical Curve("die_top") = {13};
Physical Surface("block") = {1};
Physical Surface("die") = {11};
