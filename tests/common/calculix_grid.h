/* CalculiX (ccx) as an independent reference for the tests: a linear static solution on a
 * structured grid of 8-node hexahedra with two materials, each face held or moved along its
 * normal (a roller), the reaction on the far faces read back. */
#ifndef PF_TEST_CALCULIX_GRID_H
#define PF_TEST_CALCULIX_GRID_H

/* The grid [0, n[0] h[0]] x [0, n[1] h[1]] x [0, n[2] h[2]], element (i, j, k) of material
 * in_b[i + n[0] (j + n[1] k)] ? b : a (isotropic linear elastic: E, nu). The faces x = 0, y = 0,
 * z = 0 are held along their normal; the far faces x, y, z = max move along theirs by disp[0..2]
 * (0: held); tangential motion is free everywhere. The elements are ccx's `type` (C3D8: full
 * 2x2x2 integration). */
typedef struct {
  int n[3];
  double h[3];
  const unsigned char *in_b;
  double E_a, nu_a, E_b, nu_b;
  double disp[3];
  const char *type;
} pf_test_ccx_grid;

/* The ccx executable: $CCX, else ccx on the PATH; NULL when there is none. */
const char *pf_test_ccx_path(void);
/* Write <dir>/<name>.inp for g, run ccx there (one thread) and read the total reaction on each
 * far face along its normal into F[0..2] (N). Returns 0, or -1 after printing why not. */
int pf_test_ccx_grid_solve(const pf_test_ccx_grid *g, const char *dir, const char *name, double F[3]);
/* The fibre of a square cell [0, a]^2 around one fibre of radius r at its centre, on an n x n grid:
 * [n^2] 1 where element (point) i + n j has its centroid inside the circle (free() it); its
 * fibre fraction, the count over n^2, into *vf. */
unsigned char *pf_test_fibre_map(int n, double a, double r, double *vf);
#endif
