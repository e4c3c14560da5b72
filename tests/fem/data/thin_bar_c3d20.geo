// kanegen tests/fem: the spin-up beam's section (models/spin_up_beam.json:
// A 4e-4 m^2, Iz 2e-7 m^4) as a solid rectangle, 77.5 mm in y and 5.16 mm in
// z, 10 m along x, of 20 x 1 x 1 twenty-node hexahedra: a thin, properly
// held solid (element aspect ratio 97) whose K has a condition number near
// 1e13. Root face x = 0: node set ROOT; tip face x = 10: TIP. Meshed with
//   gmsh -3 -order 2 -setnumber Mesh.SecondOrderIncomplete 1 -format inp
//        -setnumber Mesh.SaveGroupsOfNodes 1 thin_bar_c3d20.geo -o thin_bar_c3d20.inp
h = 0.0775;  // in-plane depth (Iz = t h^3 / 12)
t = 4e-4 / h;  // thickness, 5.16 mm
Point(1) = {0, -h / 2, -t / 2};
Point(2) = {0, h / 2, -t / 2};
Point(3) = {0, h / 2, t / 2};
Point(4) = {0, -h / 2, t / 2};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1:4} = 2;
Transfinite Surface{1};
Recombine Surface{1};
out[] = Extrude {10, 0, 0} { Surface{1}; Layers{20}; Recombine; };
Physical Volume("BAR") = {out[1]};
Physical Surface("ROOT") = {1};
Physical Surface("TIP") = {out[0]};
