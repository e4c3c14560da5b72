// kanegen models/plate_hub: a 0.4 x 0.04 m plate (the link of plate_hub.json)
// of 20 x 2 four-node plane-stress quadrilaterals, in the body frame's x-y
// plane; the root edge (x = 0) is node set ROOT. Meshed with
//   gmsh -2 -format inp -setnumber Mesh.SaveGroupsOfNodes 1 plate_hub.geo -o plate_hub.inp
Point(1) = {0, -0.02, 0};
Point(2) = {0.4, -0.02, 0};
Point(3) = {0.4, 0.02, 0};
Point(4) = {0, 0.02, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 21;
Transfinite Curve{2, 4} = 3;
Transfinite Surface{1};
Recombine Surface{1};
Physical Surface("PLATE") = {1};
Physical Curve("ROOT") = {4};
Physical Curve("TIP") = {2};
