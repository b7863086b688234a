/* A polar lattice for cylinders and tubes (`geometry: {shape: cylinder, lattice: polar}`): the
 * shape is cut into nz layers, nr rings and, on ring i, n_i sectors, each as near to a cube of
 * edge h as whole divisions allow (nz = round(H / h), nr = round((R - r_0) / h),
 * n_i = round(2 pi r_i / h)), and a point sits at each cell's centre radius r_i = r_0 + (i + 1/2)
 * dr with the cell's exact volume r_i dr dtheta dz. The cells tile the shape: the points' volumes
 * sum to pi (R^2 - r_0^2) H to round-off, and the outermost points lie dr/2 inside the curved
 * surfaces, as a cubic lattice's cells cannot for a curved wall (the expanding tube's wall is 4
 * cells thick; a cubic lattice fitting inside it misses a quarter of its mass). */
#include "core/core.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int pf_polar_fill(const pf_region *r, double h, pf_point_cloud *pc) {
  PF_CHECK(h > 0, PF_ERR_INPUT, "lattice spacing must be positive (got %g)", h);
  PF_CHECK(r->kind == PF_REGION_CYLINDER, PF_ERR_INPUT, "a polar lattice needs a cylinder");
  const double r0 = r->inner_radius, wall = r->radius - r0;
  const long nz = lround(fmax(1, r->height / h)), nr = lround(fmax(1, wall / h));
  const double dz = r->height / nz, dr = wall / nr;
  double cells = 0;
  for (long i = 0; i < nr; i++) cells += fmax(1, round(2 * PF_PI * (r0 + (i + 0.5) * dr) / h));
  PF_CHECK(cells * nz < 2e9, PF_ERR_INPUT, "polar lattice of %.3g cells is too large (spacing %g m)", cells * nz, h);
  memset(pc, 0, sizeof *pc);
  pc->n = (pf_int)(cells * nz);
  PF_MALLOC(pc->X, 3 * (size_t)pc->n);
  PF_MALLOC(pc->vol, pc->n);
  PF_MALLOC(pc->cell, pc->n);
  PF_MALLOC(pc->block, pc->n);
  const int a = r->axis, u = (a + 1) % 3, v = (a + 2) % 3;
  pf_int n = 0;
  for (long k = 0; k < nz; k++)
    for (long i = 0; i < nr; i++) {
      const double ri = r0 + (i + 0.5) * dr;
      const long nt = (long)fmax(1, round(2 * PF_PI * ri / h));
      const double dth = 2 * PF_PI / nt;
      for (long j = 0; j < nt; j++, n++) {
        double *x = &pc->X[3 * (size_t)n];
        x[a] = r->center[a] + (k + 0.5) * dz;
        x[u] = r->center[u] + ri * cos(j * dth);
        x[v] = r->center[v] + ri * sin(j * dth);
        pc->vol[n] = ri * dr * dth * dz;
        pc->cell[n] = cbrt(pc->vol[n]);
      }
    }
  return 0;
}
