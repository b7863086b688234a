/* Lattice bookkeeping: LAMMPS's examples/peri target (a cylinder of radius 5 mm along y,
 * y in [-5, 0] mm, on a 0.5 mm simple cubic lattice) has 3487 points (11 layers of the 317
 * lattice points of a disk of radius 10 spacings) and 335,966 directed bonds with
 * delta = 1.5001 mm (LAMMPS's log of examples/peri). */
#include "test_common.h"

#include "sim/sim.h"

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  pf_sim *sim = pf_test_sim("lattice_count",
                            "materials: {g: {model: pmb, density: 2200, bulk_modulus: 14.9e9}}\n"
                            "bodies:\n  - {name: target, material: g, horizon: 0.0015001,\n"
                            "     geometry: {shape: cylinder, center: [0, -0.005, 0], axis: y,\n"
                            "                radius: 0.005, height: 0.005, spacing: 0.0005}}\n"
                            "time: {steps: 0}\n");
  PF_TEST_TRUE(pf_sim_points(sim)->n_owned == 3487);
  PF_TEST_TRUE(pf_pd_body_nbonds(pf_sim_body(sim, 0)) == 335966);
  pf_sim_destroy(&sim);
  return pf_test_finish();
}
