// A 1 mm cube of tetrahedra (test data for tests/unit/test_fem_mesh.c: tetrahedra.msh is
// `gmsh -3 tetrahedra.geo -format msh41 -o tetrahedra.msh`; read as .geo it exercises the
// all-hexahedra subdivision fallback). Units: metres.
Point(1) = {0, 0, 0, 1e-3};
Extrude {1e-3, 0, 0} { Point{1}; }
Extrude {0, 1e-3, 0} { Curve{1}; }
Extrude {0, 0, 1e-3} { Surface{5}; }
Physical Volume("cube") = {1};
