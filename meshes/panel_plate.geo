// panel_plate.geo: the monolithic variant of panel_sandwich.geo -- a solid aluminium plate of the
// same footprint and the same mass per area as the sandwich (issue 8; docs/examples/panel_impact.md).
// The sandwich carries two 3 mm face sheets and four webs of cross-section th x hc = 2.5 x 15 mm
// in every 60 mm of width: (2 tf W + 4 th hc) / W = (360 + 150) / 60 = 8.5 mm of aluminium.
//   W = 60 mm (x in [-W/2, W/2], clamped on x = +-W/2), L = 80 mm (y in [-L/2, L/2]),
//   t = 8.5 mm thick, top surface z = 0 (impact from +z), bottom z = -t.
// Units: metres. Element size h: the deck's mesh.element_size (perifem sets Mesh.MeshSizeMax
// before opening this file), else the default below; every edge gets Ceil(length / h) divisions,
// all hexahedra. Physical groups: volume "panel"; surfaces "top" (z = 0) and "bottom".
SetFactory("OpenCASCADE");
W = 60e-3; L = 80e-3; t = 8.5e-3;
h = 1e-3;
If (Mesh.MeshSizeMax < 1e21)
  h = Mesh.MeshSizeMax;
EndIf
Rectangle(1) = {-W / 2, -t, 0, W, t}; // the cross-section in the plane's (x, y) = (x, z)
Rotate {{1, 0, 0}, {0, 0, 0}, Pi / 2} { Surface{1}; }
Translate {0, L / 2, 0} { Surface{1}; }
allc() = Curve{:};
For i In {0 : #allc() - 1}
  ends() = PointsOf{ Curve{allc(i)}; };
  pa() = Point{ends(0)};
  pb() = Point{ends(1)};
  len = Sqrt((pb(0) - pa(0))^2 + (pb(1) - pa(1))^2 + (pb(2) - pa(2))^2);
  Transfinite Curve{allc(i)} = Max(1, Ceil(len / h - 1e-6)) + 1;
EndFor
Transfinite Surface{1};
Recombine Surface{1};
Extrude {0, -L, 0} { Surface{1}; Layers{ Max(1, Ceil(L / h - 1e-6)) }; Recombine; }
Physical Volume("panel") = Volume{:};
top() = Surface In BoundingBox{-W, -L, -1e-6, W, L, 1e-6};
bot() = Surface In BoundingBox{-W, -L, -t - 1e-6, W, L, -t + 1e-6};
Physical Surface("top") = {top()};
Physical Surface("bottom") = {bot()};
