// hertz_sphere.geo: the solid sphere of tests/verification/test_hertz.c (docs/theory/hertz.md),
// R = 20 mm, all hexahedra, graded toward the south pole (0, 0, -R), where it meets the
// half-space. The topology is sphere.geo's cube-sphere (a central cube and six outer blocks,
// every block transfinite, every surface node on the sphere), with fewer elements away from
// the contact: the four arcs around the bottom block are refined toward their middle (gmsh's
// Bump 5: end cells about 3.5 times the middle ones) and the radial lines toward the sphere
// (Progression 0.85). Element size h: the deck's mesh.element_size (Mesh.MeshSizeMax), else
// the default below. With n divisions per arc (even, so that a node sits at the pole) and
// m radial ones, the mesh has n^3 + 6 n^2 m hexahedra; the faces at the pole are 1.3 to 1.4 h
// across. h = 1.425 mm (the test): n = 10, m = 5, 4000 hexahedra, pole faces 2.0 mm, faces
// up to 4.3 mm elsewhere, smallest V / A_max 1.06 mm (sphere.geo scaled to the same radius,
// with the same pole faces: 25272 hexahedra, 0.52 mm). h = 0.95 mm: n = 16, m = 7, 14848.
// Physical groups: volume "sphere"; surface "surface" (the sphere). Units: metres.
R = 20e-3;         // radius
a = 0.35 * R;      // half edge of the central cube
h = R / 10;
If (Mesh.MeshSizeMax < 1e21)
  h = Mesh.MeshSizeMax;
EndIf
n = 2 * Max(1, Ceil(0.28 * R * Acos(1 / 3) / h - 1e-6));
m = Max(1, Ceil(0.5 * (R - a) / h - 1e-6));
s = R / Sqrt(3);   // outer corners (+-s, +-s, +-s) are on the sphere

Point(100) = {0, 0, 0, h}; // centre
// corners of the central cube: 1..8; of the sphere: 11..18 (same signs)
Point(1) = {-a, -a, -a, h};
Point(2) = { a, -a, -a, h};
Point(3) = {-a,  a, -a, h};
Point(4) = { a,  a, -a, h};
Point(5) = {-a, -a,  a, h};
Point(6) = { a, -a,  a, h};
Point(7) = {-a,  a,  a, h};
Point(8) = { a,  a,  a, h};
Point(11) = {-s, -s, -s, h};
Point(12) = { s, -s, -s, h};
Point(13) = {-s,  s, -s, h};
Point(14) = { s,  s, -s, h};
Point(15) = {-s, -s,  s, h};
Point(16) = { s, -s,  s, h};
Point(17) = {-s,  s,  s, h};
Point(18) = { s,  s,  s, h};

// edges of the central cube: lines 1..12; arcs of the sphere above them: 21..32;
// radial lines from cube corner k to sphere corner 10 + k: 40 + k
Line(1) = {1, 2};
Line(2) = {5, 6};
Line(3) = {3, 4};
Line(4) = {7, 8};
Line(5) = {1, 3};
Line(6) = {5, 7};
Line(7) = {2, 4};
Line(8) = {6, 8};
Line(9) = {1, 5};
Line(10) = {3, 7};
Line(11) = {2, 6};
Line(12) = {4, 8};
Circle(21) = {11, 100, 12};
Circle(22) = {15, 100, 16};
Circle(23) = {13, 100, 14};
Circle(24) = {17, 100, 18};
Circle(25) = {11, 100, 13};
Circle(26) = {15, 100, 17};
Circle(27) = {12, 100, 14};
Circle(28) = {16, 100, 18};
Circle(29) = {11, 100, 15};
Circle(30) = {13, 100, 17};
Circle(31) = {12, 100, 16};
Circle(32) = {14, 100, 18};
Line(41) = {1, 11};
Line(42) = {2, 12};
Line(43) = {3, 13};
Line(44) = {4, 14};
Line(45) = {5, 15};
Line(46) = {6, 16};
Line(47) = {7, 17};
Line(48) = {8, 18};

// faces of the central cube: surfaces 1..6; sixths of the sphere above them: 11..16;
// radial faces through cube edge i: 20 + i
Curve Loop(1) = {5, 10, -6, -9}; Plane Surface(1) = {1}; // x = -a
Curve Loop(2) = {7, 12, -8, -11}; Plane Surface(2) = {2}; // x = +a
Curve Loop(3) = {9, 2, -11, -1}; Plane Surface(3) = {3}; // y = -a
Curve Loop(4) = {10, 4, -12, -3}; Plane Surface(4) = {4}; // y = +a
Curve Loop(5) = {1, 7, -3, -5}; Plane Surface(5) = {5}; // z = -a
Curve Loop(6) = {2, 8, -4, -6}; Plane Surface(6) = {6}; // z = +a
Curve Loop(11) = {25, 30, -26, -29}; Surface(11) = {11} In Sphere {100};
Curve Loop(12) = {27, 32, -28, -31}; Surface(12) = {12} In Sphere {100};
Curve Loop(13) = {29, 22, -31, -21}; Surface(13) = {13} In Sphere {100};
Curve Loop(14) = {30, 24, -32, -23}; Surface(14) = {14} In Sphere {100};
Curve Loop(15) = {21, 27, -23, -25}; Surface(15) = {15} In Sphere {100};
Curve Loop(16) = {22, 28, -24, -26}; Surface(16) = {16} In Sphere {100};
Curve Loop(21) = {1, 42, -21, -41}; Surface(21) = {21};
Curve Loop(22) = {2, 46, -22, -45}; Surface(22) = {22};
Curve Loop(23) = {3, 44, -23, -43}; Surface(23) = {23};
Curve Loop(24) = {4, 48, -24, -47}; Surface(24) = {24};
Curve Loop(25) = {5, 43, -25, -41}; Surface(25) = {25};
Curve Loop(26) = {6, 47, -26, -45}; Surface(26) = {26};
Curve Loop(27) = {7, 44, -27, -42}; Surface(27) = {27};
Curve Loop(28) = {8, 48, -28, -46}; Surface(28) = {28};
Curve Loop(29) = {9, 45, -29, -41}; Surface(29) = {29};
Curve Loop(30) = {10, 47, -30, -43}; Surface(30) = {30};
Curve Loop(31) = {11, 46, -31, -42}; Surface(31) = {31};
Curve Loop(32) = {12, 48, -32, -44}; Surface(32) = {32};

// the central cube: volume 1; the block above cube face i: volume 1 + i
Surface Loop(1) = {1, 2, 3, 4, 5, 6}; Volume(1) = {1};
Surface Loop(2) = {1, 11, 25, 30, 26, 29}; Volume(2) = {2};
Surface Loop(3) = {2, 12, 27, 32, 28, 31}; Volume(3) = {3};
Surface Loop(4) = {3, 13, 29, 22, 31, 21}; Volume(4) = {4};
Surface Loop(5) = {4, 14, 30, 24, 32, 23}; Volume(5) = {5};
Surface Loop(6) = {5, 15, 21, 27, 23, 25}; Volume(6) = {6};
Surface Loop(7) = {6, 16, 22, 28, 24, 26}; Volume(7) = {7};

// the arcs around the bottom face (z = -R side) are refined toward their middle, the radial
// lines toward the sphere: fine elements at the south pole, coarse ones elsewhere
Transfinite Curve {1:12, 22, 24, 26, 28:32} = n + 1;
Transfinite Curve {21, 23, 25, 27} = n + 1 Using Bump 5;
Transfinite Curve {41:48} = m + 1 Using Progression 0.85;
Transfinite Surface {1:6, 11:16, 21:32};
Recombine Surface {1:6, 11:16, 21:32};
Transfinite Volume {1:7};

Physical Volume("sphere") = {1:7};
Physical Surface("surface") = {11:16};
