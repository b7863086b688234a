// A .geo that stops gmsh half-way with `Exit;` (gmsh's Msg::Exit calls exit(0)): perifem must
// refuse it (tests/data/bad/81_gmsh_exit.yaml), not end with status 0 and nothing run.
Point(1) = {0, 0, 0, 1e-3};
Point(2) = {1e-3, 0, 0, 1e-3};
Line(1) = {1, 2};
Exit;
Extrude {0, 1e-3, 0} { Line{1}; Layers{1}; Recombine; }
