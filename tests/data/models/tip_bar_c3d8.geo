// kanegen tests/data/models: a 0.2 x 0.02 x 0.02 m bar of 8 x 2 x 2 eight-node
// hexahedra for the loops, forces and outputs on node sets of a solid mesh body
// (tip_bar_loops.json): the root face (x = 0) is node set ROOT, the tip face
// (x = 0.2) TIP, one edge of the tip face TIPEDGE, one corner of it TIPCORNER.
// Meshed with
//   gmsh -3 -format inp -setnumber Mesh.SaveGroupsOfNodes 1 tip_bar_c3d8.geo -o tip_bar_c3d8.inp
Point(1) = {0, -0.01, -0.01};
Point(2) = {0.2, -0.01, -0.01};
Point(3) = {0.2, 0.01, -0.01};
Point(4) = {0, 0.01, -0.01};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 9;
Transfinite Curve{2, 4} = 3;
Transfinite Surface{1};
Recombine Surface{1};
out[] = Extrude {0, 0, 0.02} { Surface{1}; Layers{2}; Recombine; };
Physical Volume("BAR") = {out[1]};
Physical Surface("ROOT") = {out[5]};
Physical Surface("TIP") = {out[3]};
Physical Curve("TIPEDGE") = {2};
Physical Point("TIPCORNER") = {2};
