// cylinder.geo: a solid cylinder (a projectile or a plug) of radius R = 6.35 mm and length
// L = 25.4 mm along z (z = 0 is the impact face), all hexahedra. Units: metres.
// Cross-section: an O-grid ("butterfly"): a square core |x|, |y| <= a and four outer blocks
// between the square's sides and quarter arcs of the circle, each transfinite; the section is
// extruded along z in layers. Element size h: the deck's mesh.element_size (perifem sets
// Mesh.MeshSizeMax before opening this file; `gmsh -3 -clmax 8e-4 cylinder.geo` does the
// same), else the default below. Divisions: n along each side of the square and each quarter
// arc, m across each outer block, nz layers, so the mesh has (n^2 + 4 n m) nz hexahedra and the
// circle is replaced by the inscribed regular polygon of 4 n sides (the nodes on a gmsh circle
// arc are evenly spaced in angle).
// Physical groups: volume "cylinder"; surfaces "impact_face" (z = 0), "rear_face" (z = L),
// "lateral" (r = R).
R = 6.35e-3;
L = 25.4e-3;
a = 0.5 * R;     // half side of the square core (its corners sit at r = 0.71 R)
h = 0.8e-3;
If (Mesh.MeshSizeMax < 1e21)
  h = Mesh.MeshSizeMax;
EndIf
n = Max(1, Ceil(Pi * R / 2 / h - 1e-6));
m = Max(1, Ceil((R - a) / h - 1e-6));
nz = Max(1, Ceil(L / h - 1e-6));
c = R / Sqrt(2);

Point(1) = {0, 0, 0, h};                                   // centre
Point(2) = {a, a, 0, h};   Point(3) = {-a, a, 0, h};       // corners of the core,
Point(4) = {-a, -a, 0, h}; Point(5) = {a, -a, 0, h};       //   counter-clockwise
Point(6) = {c, c, 0, h};   Point(7) = {-c, c, 0, h};       // the circle at 45, 135,
Point(8) = {-c, -c, 0, h}; Point(9) = {c, -c, 0, h};       //   225 and 315 degrees

Line(1) = {2, 3}; Line(2) = {3, 4}; Line(3) = {4, 5}; Line(4) = {5, 2};         // core
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};
Line(9) = {2, 6}; Line(10) = {3, 7}; Line(11) = {4, 8}; Line(12) = {5, 9};      // radial

Curve Loop(1) = {1, 2, 3, 4};      Plane Surface(1) = {1}; // core
Curve Loop(2) = {9, 5, -10, -1};   Plane Surface(2) = {2}; // +y block
Curve Loop(3) = {10, 6, -11, -2};  Plane Surface(3) = {3}; // -x block
Curve Loop(4) = {11, 7, -12, -3};  Plane Surface(4) = {4}; // -y block
Curve Loop(5) = {12, 8, -9, -4};   Plane Surface(5) = {5}; // +x block

Transfinite Curve {1:8} = n + 1;
Transfinite Curve {9:12} = m + 1;
Transfinite Surface {1:5};
Recombine Surface {1:5};

// Each extrusion returns [top, volume, one lateral surface per bounding curve in loop order]:
// the arc of outer block k is its loop's second curve, so its lateral surface is entry 3.
core[] = Extrude {0, 0, L} { Surface{1}; Layers{nz}; Recombine; };
b1[] = Extrude {0, 0, L} { Surface{2}; Layers{nz}; Recombine; };
b2[] = Extrude {0, 0, L} { Surface{3}; Layers{nz}; Recombine; };
b3[] = Extrude {0, 0, L} { Surface{4}; Layers{nz}; Recombine; };
b4[] = Extrude {0, 0, L} { Surface{5}; Layers{nz}; Recombine; };

Physical Volume("cylinder") = {core[1], b1[1], b2[1], b3[1], b4[1]};
Physical Surface("impact_face") = {1:5};
Physical Surface("rear_face") = {core[0], b1[0], b2[0], b3[0], b4[0]};
Physical Surface("lateral") = {b1[3], b2[3], b3[3], b4[3]};
