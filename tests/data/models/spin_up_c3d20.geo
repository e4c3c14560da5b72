// kanegen tests/flexible: Kane, Ryan and Banerjee's spin-up beam
// (models/spin_up_beam.json: L 10 m, A 4e-4 m^2, Iz 2e-7 m^4) as a solid bar
// of twenty-node hexahedra (C3D20), 10 m along x: a square tube of outer side
// a and inner side c with a^2 - c^2 = A and (a^4 - c^4) / 12 = Iz, i.e.
// a^2 = 3.2e-3 and c^2 = 2.8e-3 m^2 (walls 1.83 mm). A solid rectangle with
// the beam's A and Iz would be 77.5 x 5.16 mm, so thin that its stiffness
// spans 15 orders of magnitude (tests/fem/data/thin_bar_c3d20.geo); the
// tube bends alike across and in the plane of rotation.
// Each wall is one element across its width and thickness, 20 along x (one
// quadratic brick across bends without locking). Root face x = 0: node set
// ROOT; tip face x = 10: TIP; element set BAR. Meshed with
//   gmsh -3 -order 2 -setnumber Mesh.SecondOrderIncomplete 1 -format inp
//        -setnumber Mesh.SaveGroupsOfNodes 1 spin_up_c3d20.geo -o spin_up_c3d20.inp
a = Sqrt(3.2e-3) / 2; // half the outer side
c = Sqrt(2.8e-3) / 2; // half the inner side
Point(1) = {0, -a, -a};
Point(2) = {0, a, -a};
Point(3) = {0, a, a};
Point(4) = {0, -a, a};
Point(5) = {0, -c, -c};
Point(6) = {0, c, -c};
Point(7) = {0, c, c};
Point(8) = {0, -c, c};
For i In {0:3}
  Line(1 + i) = {1 + i, 1 + (i + 1) % 4};     // outer edges
  Line(5 + i) = {5 + i, 5 + (i + 1) % 4};     // inner edges
  Line(9 + i) = {1 + i, 5 + i};               // corners, across the wall
EndFor
For i In {0:3}
  Curve Loop(1 + i) = {1 + i, 9 + (i + 1) % 4, -(5 + i), -(9 + i)};
  Plane Surface(1 + i) = {1 + i};
EndFor
Transfinite Curve{1:12} = 2;
Transfinite Surface{1:4};
Recombine Surface{1:4};
out[] = Extrude {10, 0, 0} { Surface{1:4}; Layers{20}; Recombine; };
Physical Volume("BAR") = {out[1], out[7], out[13], out[19]};
Physical Surface("ROOT") = {1:4};
Physical Surface("TIP") = {out[0], out[6], out[12], out[18]};
