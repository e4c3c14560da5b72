// kanegen tests/fem: a slender 0.4 x 0.01 m plane-stress bar of 40 x 2
// eight-node quadrilaterals (test_mesh_body_model.cpp compares it with the
// beam of the same section); root edge x = 0 as node set ROOT. Meshed with
//   gmsh -2 -format inp -setnumber Mesh.SaveGroupsOfNodes 1 -setnumber Mesh.SecondOrderIncomplete 1 -order 2 slender_cps8.geo -o slender_cps8.inp
Point(1) = {0, -0.005, 0};
Point(2) = {0.4, -0.005, 0};
Point(3) = {0.4, 0.005, 0};
Point(4) = {0, 0.005, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 41;
Transfinite Curve{2, 4} = 3;
Transfinite Surface{1};
Recombine Surface{1};
Physical Surface("BAR") = {1};
Physical Curve("ROOT") = {4};
Physical Curve("TIP") = {2};
