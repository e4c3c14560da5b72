// kanegen tests/data/models: a 0.2 x 0.02 x 0.02 m bar of ten-node tetrahedra
// (C3D10) for kanegen verify of a tetrahedral mesh body (tip_bar_c3d10.json):
// 4 x 1 boxes of two triangles in x-y, extruded by one layer in z, each prism
// split into three tetrahedra (24 elements). The root face (x = 0) is node set
// ROOT, the tip face (x = 0.2) TIP. Meshed with
//   gmsh -3 -order 2 -format inp -setnumber Mesh.SaveGroupsOfNodes 1 tip_bar_c3d10.geo -o tip_bar_c3d10.inp
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
Transfinite Curve{1, 3} = 5;
Transfinite Curve{2, 4} = 2;
Transfinite Surface{1};
out[] = Extrude {0, 0, 0.02} { Surface{1}; Layers{1}; };
Physical Volume("BAR") = {out[1]};
Physical Surface("ROOT") = {out[5]};
Physical Surface("TIP") = {out[3]};
