// panel_sandwich.geo: an extruded aluminium sandwich panel with a triangular corrugated core,
// resembling the extruded 6061-T6 panels of Tupek et al. 2013 (sec. 3.2; Wetzel 2009):
// two face sheets joined by inclined webs. The cross-section is drawn in the x-z plane as
// quadrilateral blocks (face-sheet segments and parallelogram webs sharing their edges), meshed
// transfinite, and extruded along y (the extrusion direction) in layers: all hexahedra.
// Dimensions are this project's choice (the paper does not give them), documented in
// docs/examples/panel_impact.md:
//   W  = 60 mm   width across the corrugation (x in [-W/2, W/2]; the panel is clamped on x = +-W/2)
//   L  = 80 mm   length along the extrusion (y in [-L/2, L/2]; the long sides are x = +-W/2)
//   tf = 3 mm    face-sheet thickness; the top face's top surface is z = 0 (impact from +z)
//   hc = 15 mm   core height between the face sheets
//   th = 2.5 mm  width of a web's foot on a face sheet (webs 1.92 mm thick, normal to the web)
//   p  = 30 mm   corrugation pitch: the webs leave the top face side by side at x = +-p/2 and
//                meet the bottom face side by side at x = 0 (and alone at x = +-W/2), so a
//                projectile at x = 0 goes through the top face into a core cell and meets the
//                apex of two webs on the bottom face.
// Units: metres. Element size h: the deck's mesh.element_size (perifem sets Mesh.MeshSizeMax
// before opening this file; `gmsh -3 -clmax 1e-3 panel_sandwich.geo` does the same), else the
// default below; every block edge of length l gets Ceil(l / h) divisions.
// Physical groups: volume "panel"; surfaces "top" (z = 0) and "bottom".
SetFactory("OpenCASCADE");
W = 60e-3; L = 80e-3; tf = 3e-3; hc = 15e-3; th = 2.5e-3; p = 30e-3;
h = 1e-3;
If (Mesh.MeshSizeMax < 1e21)
  h = Mesh.MeshSizeMax;
EndIf
zt = -tf; zc = -tf - hc; zb = -2 * tf - hc; // core top, core bottom, panel bottom

// face-sheet segments, split where the web feet meet them
xtop[] = {-W / 2, -p / 2 - th, -p / 2, -p / 2 + th, p / 2 - th, p / 2, p / 2 + th, W / 2};
xbot[] = {-W / 2, -W / 2 + th, -th, 0, th, W / 2 - th, W / 2};
For k In {0 : #xtop[] - 2}
  Rectangle(newv) = {xtop[k], zt, 0, xtop[k + 1] - xtop[k], tf};
EndFor
For k In {0 : #xbot[] - 2}
  Rectangle(newv) = {xbot[k], zb, 0, xbot[k + 1] - xbot[k], tf};
EndFor
// webs: parallelograms from a top foot [a, a + th] at z = zt to a bottom foot [b, b + th] at zc
atop[] = {-p / 2 - th, -p / 2, p / 2 - th, p / 2};
abot[] = {-W / 2, -th, 0, W / 2 - th};
For k In {0 : 3}
  p1 = newp; Point(p1) = {atop[k], zt, 0};
  p2 = newp; Point(p2) = {atop[k] + th, zt, 0};
  p3 = newp; Point(p3) = {abot[k] + th, zc, 0};
  p4 = newp; Point(p4) = {abot[k], zc, 0};
  l1 = newl; Line(l1) = {p1, p2};
  l2 = newl; Line(l2) = {p2, p3};
  l3 = newl; Line(l3) = {p3, p4};
  l4 = newl; Line(l4) = {p4, p1};
  cl = newll; Curve Loop(cl) = {l1, l2, l3, l4};
  Plane Surface(news) = {cl};
EndFor
// one conforming cross-section (blocks share their common edges), drawn as (x, z) in the
// plane's (x, y): turn it up into the x-z plane, at y = L/2
cs() = BooleanFragments{ Surface{:}; Delete; }{};
Rotate {{1, 0, 0}, {0, 0, 0}, Pi / 2} { Surface{cs()}; }
Translate {0, L / 2, 0} { Surface{cs()}; }
// transfinite blocks: every straight edge gets Ceil(length / h) divisions (opposite edges of a
// block have equal lengths, so equal divisions)
allc() = Curve{:};
For i In {0 : #allc() - 1}
  ends() = PointsOf{ Curve{allc(i)}; };
  pa() = Point{ends(0)};
  pb() = Point{ends(1)};
  len = Sqrt((pb(0) - pa(0))^2 + (pb(1) - pa(1))^2 + (pb(2) - pa(2))^2);
  Transfinite Curve{allc(i)} = Max(1, Ceil(len / h - 1e-6)) + 1;
EndFor
Transfinite Surface{cs()};
Recombine Surface{cs()};
Extrude {0, -L, 0} { Surface{cs()}; Layers{ Max(1, Ceil(L / h - 1e-6)) }; Recombine; }
Physical Volume("panel") = Volume{:};
top() = Surface In BoundingBox{-W, -L, -1e-6, W, L, 1e-6};
bot() = Surface In BoundingBox{-W, -L, zb - 1e-6, W, L, zb + 1e-6};
Physical Surface("top") = {top()};
Physical Surface("bottom") = {bot()};
