// expanding_tube_lexan.geo: the Lexan of the expanding tube (Vogler et al. 2003), a projectile
// and a plug of radius R = 6.35 mm and length 25.4 mm each, end to end along z: projectile
// z = 0 .. 25.4 mm, plug z = 25.4 .. 50.8 mm, all hexahedra, one conforming mesh (the two
// share the nodes of the impact plane z = 25.4 mm). Units: metres.
// Cross-section: the O-grid of cylinder.geo (a square core and four transfinite outer blocks;
// the circle becomes the inscribed regular polygon of 4 n sides), extruded twice along z.
// Element size h: the deck's mesh.element_size (perifem sets Mesh.MeshSizeMax before opening
// this file; `gmsh -3 -clmax 1e-3 expanding_tube_lexan.geo` does the same), else the default.
// Physical groups (blocks): volumes "projectile" and "plug"; surfaces "rear_face" (z = 0),
// "far_face" (z = 50.8 mm), "lateral" (r = R, both parts).
R = 6.35e-3;
L = 25.4e-3;     // length of each part
a = 0.5 * R;     // half side of the square core
h = 1.0e-3;
If (Mesh.MeshSizeMax < 1e21)
  h = Mesh.MeshSizeMax;
EndIf
n = Max(1, Ceil(Pi * R / 2 / h - 1e-6));
m = Max(1, Ceil((R - a) / h - 1e-6));
nz = Max(1, Ceil(L / h - 1e-6));
c = R / Sqrt(2);

Point(1) = {0, 0, 0, h};
Point(2) = {a, a, 0, h};   Point(3) = {-a, a, 0, h};
Point(4) = {-a, -a, 0, h}; Point(5) = {a, -a, 0, h};
Point(6) = {c, c, 0, h};   Point(7) = {-c, c, 0, h};
Point(8) = {-c, -c, 0, h}; Point(9) = {c, -c, 0, h};
Line(1) = {2, 3}; Line(2) = {3, 4}; Line(3) = {4, 5}; Line(4) = {5, 2};
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};
Line(9) = {2, 6}; Line(10) = {3, 7}; Line(11) = {4, 8}; Line(12) = {5, 9};
Curve Loop(1) = {1, 2, 3, 4};      Plane Surface(1) = {1};
Curve Loop(2) = {9, 5, -10, -1};   Plane Surface(2) = {2};
Curve Loop(3) = {10, 6, -11, -2};  Plane Surface(3) = {3};
Curve Loop(4) = {11, 7, -12, -3};  Plane Surface(4) = {4};
Curve Loop(5) = {12, 8, -9, -4};   Plane Surface(5) = {5};
Transfinite Curve {1:8} = n + 1;
Transfinite Curve {9:12} = m + 1;
Transfinite Surface {1:5};
Recombine Surface {1:5};

// First the projectile, then the plug extruded from the projectile's top faces. Each extrusion
// returns [top, volume, lateral surfaces in loop order]; an outer block's arc is its loop's
// second curve, so its lateral surface is entry 3.
For k In {1:5}
  p[] = Extrude {0, 0, L} { Surface{k}; Layers{nz}; Recombine; };
  q[] = Extrude {0, 0, L} { Surface{p[0]}; Layers{nz}; Recombine; };
  projectile[k - 1] = p[1];
  plug[k - 1] = q[1];
  far[k - 1] = q[0];
  If (k > 1)
    lateral[] += {p[3], q[3]};
  EndIf
EndFor
Physical Volume("projectile") = {projectile[]};
Physical Volume("plug") = {plug[]};
Physical Surface("rear_face") = {1:5};
Physical Surface("far_face") = {far[]};
Physical Surface("lateral") = {lateral[]};
