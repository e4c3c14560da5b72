// kanegen tests/fem: the 0.2 x 0.02 x 0.012 m bar of bar_c3d8.geo in six-node
// wedges (C3D6): a structured triangle mesh of the x-y face extruded in z, the
// root face (x = 0) as node set ROOT. Meshed by tests/fem/ccx/make_solid_reference.py with
//   gmsh -3 -format inp -setnumber Mesh.SaveGroupsOfNodes 1 bar_c3d6.geo -o bar_c3d6.inp
Point(1) = {0, 0, 0};
Point(2) = {0.2, 0, 0};
Point(3) = {0.2, 0.02, 0};
Point(4) = {0, 0.02, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 17;
Transfinite Curve{2, 4} = 4;
Transfinite Surface{1};
out[] = Extrude {0, 0, 0.012} { Surface{1}; Layers{2}; Recombine; };
Physical Volume("BAR") = {out[1]};
Physical Surface("ROOT") = {out[5]};
