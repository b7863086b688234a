// laminate_hole.geo: a [0/90]s laminate plate with a central circular hole, all hexahedra
// (docs/examples/laminate_hole.md); meshes/plate_hole.geo with the thickness of four plies.
//   x in [-L/2, L/2] (the load's direction), y in [-W/2, W/2], z in [-t/2, t/2];
//   W = 50 mm, L = 150 mm, t = 0.5 mm (four plies of 0.125 mm), hole radius a = 5 mm at the origin (2a/W = 0.2).
// Units: metres. Element size h: the deck's mesh.element_size (perifem sets Mesh.MeshSizeMax
// before opening this file), else the default below; h is the spacing along the hole's edge.
// Blocks (all transfinite, 4-sided): an O-grid of four blocks between the hole and the square
// |x|, |y| <= b = 2.5 a (nc divisions along the hole's quarter and the square's side, nr radial
// divisions growing outward by the ratio q), two blocks above and below it (|x| <= b), and three
// blocks at each end (|x| >= b) of uniform spacing 2b/nc along x; 4 layers through the
// thickness, one per ply, so the mid-plane z = 0 and the ply interfaces z = +-t/4 carry nodes. nc is a multiple of 2, so the ligament x = 0
// and the axis y = 0 are lines of nodes. Physical group: volume "plate".
W = 50e-3; L = 150e-3; t = 0.5e-3; a = 5e-3; b = 2.5 * a;
h = 0.5e-3;
If (Mesh.MeshSizeMax < 1e21)
  h = Mesh.MeshSizeMax;
EndIf
nc = 2 * Ceil(Pi * a / (4 * h) - 1e-6);           // divisions along a quarter of the hole
q = 1.12;                                          // radial growth ratio along the diagonals
s = 2 * b / nc;                                    // spacing along the square's sides
lr = b * Sqrt(2) - a;                              // diagonal from the hole to the square
nr = Ceil(Log(1 + lr * (q - 1) / (1.3 * h)) / Log(q));   // first diagonal size about 1.3 h
ny = Ceil((W / 2 - b) / s - 1e-6);                 // above and below the square
nx = Ceil((L / 2 - b) / s - 1e-6);                 // each end, uniform spacing
nt = 4;                                            // one layer per ply

c = a / Sqrt(2);
Point(1) = {0, 0, -t / 2};
// the hole's points at 45, 135, 225, 315 degrees and the square's corners
Point(2) = {c, c, -t / 2};   Point(3) = {-c, c, -t / 2};
Point(4) = {-c, -c, -t / 2}; Point(5) = {c, -c, -t / 2};
Point(6) = {b, b, -t / 2};   Point(7) = {-b, b, -t / 2};
Point(8) = {-b, -b, -t / 2}; Point(9) = {b, -b, -t / 2};
// the plate's edges at x = +-b and the corners
Point(10) = {b, W / 2, -t / 2};  Point(11) = {-b, W / 2, -t / 2};
Point(12) = {-b, -W / 2, -t / 2}; Point(13) = {b, -W / 2, -t / 2};
Point(14) = {L / 2, W / 2, -t / 2}; Point(15) = {L / 2, b, -t / 2};
Point(16) = {L / 2, -b, -t / 2};    Point(17) = {L / 2, -W / 2, -t / 2};
Point(18) = {-L / 2, W / 2, -t / 2}; Point(19) = {-L / 2, b, -t / 2};
Point(20) = {-L / 2, -b, -t / 2};    Point(21) = {-L / 2, -W / 2, -t / 2};

Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Line(5) = {6, 7}; Line(6) = {7, 8}; Line(7) = {8, 9}; Line(8) = {9, 6};      // the square
Line(9) = {2, 6}; Line(10) = {3, 7}; Line(11) = {4, 8}; Line(12) = {5, 9};  // diagonals
Line(13) = {6, 10}; Line(14) = {10, 11}; Line(15) = {11, 7};                // above
Line(16) = {8, 12}; Line(17) = {12, 13}; Line(18) = {13, 9};                // below
Line(19) = {10, 14}; Line(20) = {6, 15}; Line(21) = {9, 16}; Line(22) = {13, 17}; // right end
Line(23) = {14, 15}; Line(24) = {15, 16}; Line(25) = {16, 17};
Line(26) = {11, 18}; Line(27) = {7, 19}; Line(28) = {8, 20}; Line(29) = {12, 21}; // left end
Line(30) = {18, 19}; Line(31) = {19, 20}; Line(32) = {20, 21};

Transfinite Curve{1, 2, 3, 4, 5, 6, 7, 8, 14, 17, 24, 31} = nc + 1;
Transfinite Curve{9, 10, 11, 12} = nr + 1 Using Progression q;
Transfinite Curve{13, 15, 16, 18, 23, 25, 30, 32} = ny + 1;
Transfinite Curve{19, 20, 21, 22, 26, 27, 28, 29} = nx + 1;

Curve Loop(1) = {1, 10, -5, -9};   Plane Surface(1) = {1};   // O-grid: above the hole
Curve Loop(2) = {2, 11, -6, -10};  Plane Surface(2) = {2};   // left of it
Curve Loop(3) = {3, 12, -7, -11};  Plane Surface(3) = {3};   // below
Curve Loop(4) = {4, 9, -8, -12};   Plane Surface(4) = {4};   // right
Curve Loop(5) = {13, 14, 15, -5};  Plane Surface(5) = {5};   // above the square
Curve Loop(6) = {-7, 16, 17, 18};  Plane Surface(6) = {6};   // below the square
Curve Loop(7) = {20, -23, -19, -13}; Plane Surface(7) = {7}; // right end, top
Curve Loop(8) = {21, -24, -20, -8};  Plane Surface(8) = {8}; // right end, middle
Curve Loop(9) = {22, -25, -21, -18}; Plane Surface(9) = {9}; // right end, bottom
Curve Loop(10) = {15, 27, -30, -26}; Plane Surface(10) = {10}; // left end, top
Curve Loop(11) = {6, 28, -31, -27};  Plane Surface(11) = {11}; // left end, middle
Curve Loop(12) = {-16, 28, 32, -29}; Plane Surface(12) = {12}; // left end, bottom
Transfinite Surface{1 : 12};
Recombine Surface{1 : 12};
Extrude {0, 0, t} { Surface{1 : 12}; Layers{nt}; Recombine; }
Physical Volume("plate") = Volume{:};
