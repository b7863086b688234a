// bar.geo: a rectangular bar Lx x Ly x Lz = 10 x 1 x 1 mm, all hexahedra (transfinite).
// Units: metres. Element size h: the deck's mesh.element_size (perifem sets
// Mesh.MeshSizeMax before opening this file; `gmsh -3 -clmax 2e-4 bar.geo` does the same),
// else the default below. Divisions: n = Max(1, Ceil(L/h - 1e-6)) along each edge, so the
// mesh has nx * ny * nz elements of edge <= h.
// Physical groups: volume "bar"; surfaces "x0" (x = 0, the impact face), "x1" (x = Lx),
// "y0", "y1", "z0", "z1" (side sets and node sets in perifem).
Lx = 10e-3; Ly = 1e-3; Lz = 1e-3;
h = 0.25e-3;
If (Mesh.MeshSizeMax < 1e21)
  h = Mesh.MeshSizeMax;
EndIf
nx = Max(1, Ceil(Lx / h - 1e-6));
ny = Max(1, Ceil(Ly / h - 1e-6));
nz = Max(1, Ceil(Lz / h - 1e-6));

Point(1) = {0, 0, 0, h};   Point(2) = {Lx, 0, 0, h};
Point(3) = {Lx, Ly, 0, h}; Point(4) = {0, Ly, 0, h};
Point(5) = {0, 0, Lz, h};  Point(6) = {Lx, 0, Lz, h};
Point(7) = {Lx, Ly, Lz, h}; Point(8) = {0, Ly, Lz, h};

Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {4, 3}; Line(4) = {1, 4};    // z = 0
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {8, 7}; Line(8) = {5, 8};    // z = Lz
Line(9) = {1, 5}; Line(10) = {2, 6}; Line(11) = {3, 7}; Line(12) = {4, 8}; // along z

Curve Loop(1) = {1, 2, -3, -4};   Plane Surface(1) = {1}; // z = 0
Curve Loop(2) = {5, 6, -7, -8};   Plane Surface(2) = {2}; // z = Lz
Curve Loop(3) = {1, 10, -5, -9};  Plane Surface(3) = {3}; // y = 0
Curve Loop(4) = {3, 11, -7, -12}; Plane Surface(4) = {4}; // y = Ly
Curve Loop(5) = {4, 12, -8, -9};  Plane Surface(5) = {5}; // x = 0
Curve Loop(6) = {2, 11, -6, -10}; Plane Surface(6) = {6}; // x = Lx
Surface Loop(1) = {1, 2, 3, 4, 5, 6};
Volume(1) = {1};

Transfinite Curve {1, 3, 5, 7} = nx + 1;
Transfinite Curve {2, 4, 6, 8} = ny + 1;
Transfinite Curve {9, 10, 11, 12} = nz + 1;
Transfinite Surface {1:6};
Recombine Surface {1:6};
Transfinite Volume {1};

Physical Volume("bar") = {1};
Physical Surface("x0") = {5};
Physical Surface("x1") = {6};
Physical Surface("y0") = {3};
Physical Surface("y1") = {4};
Physical Surface("z0") = {1};
Physical Surface("z1") = {2};
