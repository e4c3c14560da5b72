// kanegen tests/flexible: Kane, Ryan and Banerjee's spin-up beam
// (models/spin_up_beam.json: L 10 m, A 4e-4 m^2, I 2e-7 m^4) as a plane-stress
// strip, 10 x 0.0774597 m (h = sqrt(12 I / A); the thickness b = A / h =
// 0.00516398 m is in the model), of 20 x 1 eight-node quadrilaterals. Root
// edge x = 0: node set ROOT; tip edge x = 10: TIP. Meshed with
//   gmsh -2 -format inp -setnumber Mesh.SaveGroupsOfNodes 1 -setnumber Mesh.SecondOrderIncomplete 1 -order 2 spin_up_cps8.geo -o spin_up_cps8.inp
h = 0.0774597;
Point(1) = {0, -h / 2, 0};
Point(2) = {10, -h / 2, 0};
Point(3) = {10, h / 2, 0};
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
