// kanegen tests/flexible: issue 12's free flexible pendulum
// (free_strip_modal.json: an aluminium strip 1 m long, 25 x 4 mm, bending in
// the plane of its motion) as a plane-stress strip 1 x 0.004 m (thickness
// 0.025 m in the model) of 20 x 1 eight-node quadrilaterals. Root edge x = 0:
// node set ROOT; tip edge x = 1: TIP. Meshed with
//   gmsh -2 -format inp -setnumber Mesh.SaveGroupsOfNodes 1 -setnumber Mesh.SecondOrderIncomplete 1 -order 2 free_strip_cps8.geo -o free_strip_cps8.inp
h = 0.004;
Point(1) = {0, -h / 2, 0};
Point(2) = {1, -h / 2, 0};
Point(3) = {1, h / 2, 0};
Point(4) = {0, h / 2, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 21;
Transfinite Curve{2, 4} = 2;
Transfinite Surface{1};
Recombine Surface{1};
Physical Surface("STRIP") = {1};
Physical Curve("ROOT") = {4};
Physical Curve("TIP") = {2};
