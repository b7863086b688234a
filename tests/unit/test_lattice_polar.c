/* The polar lattice (core/lattice_polar.c) of the expanding tube's wall (inner radius 6.35 mm,
 * outer 9.35 mm, length 50.8 mm, h = 0.75 mm) and of a solid cylinder along x, against their
 * closed forms: the points' volumes sum to pi (R^2 - r0^2) H (the cells tile the shape); the
 * count is sum_i round(2 pi r_i / h) per layer over the rings r_i = r0 + (i + 1/2) dr
 * (4 rings: 56 + 63 + 69 + 75 = 263 per layer, 68 layers: 17,884 points); every point lies
 * dr/2 inside the curved surfaces and dz/2 inside the ends; each volume is r dr dtheta dz with
 * the ring's own dtheta. A deck asking a polar lattice of a box is refused. */
#include "test_common.h"

#include <math.h>

static void check(const pf_region *r, double h, pf_int want_n) {
  pf_point_cloud pc;
  PF_TEST_OK(pf_polar_fill(r, h, &pc));
  PF_TEST_TRUE(pc.n == want_n);
  const int a = r->axis, u = (a + 1) % 3, v = (a + 2) % 3;
  const double r0 = r->inner_radius, R = r->radius, H = r->height;
  const double dr = (R - r0) / lround((R - r0) / h), dz = H / lround(H / h);
  double vol = 0, rmin = INFINITY, rmax = 0, zmin = INFINITY, zmax = -INFINITY, err = 0;
  for (pf_int i = 0; i < pc.n; i++) {
    const double *x = &pc.X[3 * i];
    const double rr = hypot(x[u] - r->center[u], x[v] - r->center[v]), z = x[a] - r->center[a];
    const double nt = round(2 * PF_PI * rr / h);
    err = fmax(err, fabs(pc.vol[i] - rr * dr * (2 * PF_PI / nt) * dz) / pc.vol[i]);
    vol += pc.vol[i];
    rmin = fmin(rmin, rr), rmax = fmax(rmax, rr), zmin = fmin(zmin, z), zmax = fmax(zmax, z);
  }
  PF_TEST_CLOSE(vol, PF_PI * (R * R - r0 * r0) * H, 1e-12, 0);
  PF_TEST_CLOSE(err, 0.0, 0, 1e-12);
  PF_TEST_CLOSE(rmin, r0 + 0.5 * dr, 1e-12, 0);
  PF_TEST_CLOSE(rmax, R - 0.5 * dr, 1e-12, 0);
  PF_TEST_CLOSE(zmin, 0.5 * dz, 1e-9, 0);
  PF_TEST_CLOSE(zmax, H - 0.5 * dz, 1e-12, 0);
  pf_point_cloud_free(&pc);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  pf_region tube = {.kind = PF_REGION_CYLINDER, .axis = 2, .radius = 9.35e-3, .inner_radius = 6.35e-3,
                    .height = 50.8e-3};
  check(&tube, 0.75e-3, (56 + 63 + 69 + 75) * 68);
  /* a solid cylinder along x: rings at 0.5, 1.5, 2.5 mm of round(2 pi r) = 3, 9, 16 sectors, 4 layers */
  pf_region rod = {.kind = PF_REGION_CYLINDER, .axis = 0, .center = {1, 2, 3}, .radius = 3e-3, .height = 4e-3};
  check(&rod, 1e-3, (3 + 9 + 16) * 4);
  const char *path = pf_test_write_file(0, "polar_box",
                                        "materials: {g: {model: pmb, density: 2200, bulk_modulus: 14.9e9}}\n"
                                        "bodies:\n  - {name: b, material: g, horizon: 0.003,\n"
                                        "     geometry: {shape: box, lo: [0, 0, 0], hi: [0.01, 0.01, 0.01], spacing: 0.001, lattice: polar}}\n"
                                        "time: {steps: 0}\n");
  pf_sim *sim = NULL;
  PF_TEST_TRUE(pf_sim_create(path, &(pf_sim_options){.no_output = 1}, &sim) != 0 && sim == NULL);
  remove(path);
  return pf_test_finish();
}
