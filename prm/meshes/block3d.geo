// A 100 x 50 x 50 mm block resting on z = 0, meshed with hexahedra (a
// transfinite, recombined bottom extruded in layers). Physical groups name
// the boundaries and the body.
length = 100;
width = 50;
height = 50;
nx = 8;   // cells along x
ny = 4;   // cells along y
nz = 4;   // cell layers along z

Point(1) = {-length/2, 0, 0};
Point(2) = { length/2, 0, 0};
Point(3) = { length/2, width, 0};
Point(4) = {-length/2, width, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};
Recombine Surface{1};
// out[0]: the top, out[1]: the volume, out[2..5]: the sides swept by lines 1..4
out[] = Extrude {0, 0, height} { Surface{1}; Layers{nz}; Recombine; };

Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
Physical Surface("y min") = {out[2]};
Physical Surface("x max") = {out[3]};
Physical Surface("y max") = {out[4]};
Physical Surface("x min") = {out[5]};
Physical Volume("block") = {out[1]};
