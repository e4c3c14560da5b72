// kanegen tests/fem: the connecting rod of models/solid_slider_crank.geo (the
// same geometry, node sets BIG_END and SMALL_END, element set ROD) in ten-node
// tetrahedra (C3D10): its faces are meshed in triangles and extruded by one
// layer, so each wedge splits into three tetrahedra. Meshed by
// tests/fem/ccx/make_solid_reference.py with
//   gmsh -3 -order 2 -format inp -setnumber Mesh.SaveGroupsOfNodes 1
//        solid_slider_crank_c3d10.geo -o solid_slider_crank_c3d10.inp
L = 0.3;   // pin centres apart
h = 0.004; // half the shank's height and half the rod's thickness
rb = 0.006; Rb = 0.014; // big end: bore and eye radius
rs = 0.004; Rs = 0.008; // small end: bore and eye radius
tb = Asin(h / Rb); // half the angle the shank takes of each eye
ts = Asin(h / Rs);
nShank = 15;     // nodes along the shank (14 elements)
nSide = 4;       // nodes on the big eye's side sectors (3 elements), 3 on the small eye's

// Big end: centre 1; sector corners at +-tb and 180 -+ tb, on the bore (b) and the eye (B).
Point(1) = {0, 0, -h};
Point(2) = {rb * Cos(tb), rb * Sin(tb), -h};
Point(3) = {-rb * Cos(tb), rb * Sin(tb), -h};
Point(4) = {-rb * Cos(tb), -rb * Sin(tb), -h};
Point(5) = {rb * Cos(tb), -rb * Sin(tb), -h};
Point(6) = {Rb * Cos(tb), h, -h};
Point(7) = {-Rb * Cos(tb), h, -h};
Point(8) = {-Rb * Cos(tb), -h, -h};
Point(9) = {Rb * Cos(tb), -h, -h};
// Small end: centre 11; sector corners at 180 -+ ts and +-ts.
Point(11) = {L, 0, -h};
Point(12) = {L - rs * Cos(ts), rs * Sin(ts), -h};
Point(13) = {L + rs * Cos(ts), rs * Sin(ts), -h};
Point(14) = {L + rs * Cos(ts), -rs * Sin(ts), -h};
Point(15) = {L - rs * Cos(ts), -rs * Sin(ts), -h};
Point(16) = {L - Rs * Cos(ts), h, -h};
Point(17) = {L + Rs * Cos(ts), h, -h};
Point(18) = {L + Rs * Cos(ts), -h, -h};
Point(19) = {L - Rs * Cos(ts), -h, -h};

// Big end arcs (bore 1-4, eye 5-8, counter-clockwise from the shank sector) and radial lines 9-12.
Circle(1) = {5, 1, 2};
Circle(2) = {2, 1, 3};
Circle(3) = {3, 1, 4};
Circle(4) = {4, 1, 5};
Circle(5) = {9, 1, 6};
Circle(6) = {6, 1, 7};
Circle(7) = {7, 1, 8};
Circle(8) = {8, 1, 9};
Line(9) = {2, 6};
Line(10) = {3, 7};
Line(11) = {4, 8};
Line(12) = {5, 9};
// Small end arcs (bore 21-24, eye 25-28, counter-clockwise from the shank sector) and radial lines 29-32.
Circle(21) = {12, 11, 15};
Circle(22) = {15, 11, 14};
Circle(23) = {14, 11, 13};
Circle(24) = {13, 11, 12};
Circle(25) = {16, 11, 19};
Circle(26) = {19, 11, 18};
Circle(27) = {18, 11, 17};
Circle(28) = {17, 11, 16};
Line(29) = {12, 16};
Line(30) = {15, 19};
Line(31) = {14, 18};
Line(32) = {13, 17};
// Shank: the bottom 42, the small eye's arc 25, the top 41 and the big eye's arc 5, reversed.
// Every curve loop runs counter-clockwise seen from +z, so that the hexahedra are not inverted.
Line(41) = {6, 16};
Line(42) = {19, 9};

Curve Loop(1) = {12, 5, -9, -1};  // big end, shank sector
Curve Loop(2) = {9, 6, -10, -2};
Curve Loop(3) = {10, 7, -11, -3};
Curve Loop(4) = {11, 8, -12, -4};
Curve Loop(5) = {29, 25, -30, -21};  // small end, shank sector
Curve Loop(6) = {30, 26, -31, -22};
Curve Loop(7) = {31, 27, -32, -23};
Curve Loop(8) = {32, 28, -29, -24};
Curve Loop(9) = {-42, -25, -41, -5};  // shank
For s In {1:9}
  Plane Surface(s) = {s};
EndFor

Transfinite Curve{9, 10, 11, 12, 29, 30, 31, 32} = 2;  // one element through each eye's wall
Transfinite Curve{1, 3, 5, 7, 21, 23, 25, 27} = 2;     // the shank's height, and the sectors opposite it
Transfinite Curve{2, 4, 6, 8} = nSide;
Transfinite Curve{22, 24, 26, 28} = 3;
Transfinite Curve{41, 42} = nShank;
Transfinite Surface{1:9};

out[] = Extrude {0, 0, 2 * h} { Surface{1:9}; Layers{1}; };
// out[] holds, per extruded surface, the top face, the volume, then the side faces in the
// order of its curve loop: the bore faces are the sides on curves 1-4 and 21-24.
Physical Volume("ROD") = {out[1], out[7], out[13], out[19], out[25], out[31], out[37], out[43], out[49]};
Physical Surface("BIG_END") = {out[5], out[11], out[17], out[23]};
Physical Surface("SMALL_END") = {out[29], out[35], out[41], out[47]};
