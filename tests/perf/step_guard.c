/* The whole-step instruction-count guard's driver (tests/perf/step_guard.sh runs it under
 * valgrind's callgrind): builds the simulation of a deck, takes a few warm-up steps, then
 * counts the instructions of `steps` whole time steps (pf_sim_step: forces, contact, damage,
 * integration, halo exchange, per-step records) and, in the same process and build, those of a
 * fixed reference workload written here: a plain bond-based step (velocity Verlet, PMB forces
 * of Silling & Askari 2005 eq. 7 with a critical stretch) on a 10^3 lattice, horizon 3.0001
 * spacings (84,288 directed bonds), one bond at a time. The script divides the first count by
 * the second.
 *
 *   step_guard DECK WARMUP STEPS
 *
 * Each count is a callgrind dump (CALLGRIND_DUMP_STATS_AT "step", then "reference"); the
 * driver also prints the work of the deck (points, directed bonds, elements) for the table.
 * Outside valgrind the client requests do nothing and the program only runs. */
#include "core/core.h"
#include "fem/fem.h"
#include "sim/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <valgrind/callgrind.h>

enum { REF_N = 10, REF_STEPS = 4 };

typedef struct {
  int n;               /* points */
  double *x, *u, *v, *f; /* reference positions, displacements, velocities, forces [3n] */
  int *off, *nb;       /* bonds of point i: nb[off[i] .. off[i+1]) */
  unsigned char *cut;  /* 1 once the bond has failed */
  double c, s0, vol, mass, dt;
} ref_lattice;

/* The lattice, its bonds (|xi| <= 3.0001 h, all pairs tested: 84,288) and a slow expansion (no
 * bond reaches the critical stretch in the REF_STEPS steps); set up outside the counted part. */
static void ref_build(ref_lattice *L) {
  const double h = 1e-3, delta = 3.0001 * h, K = 14.9e9, rho = 2200;
  const int n = REF_N * REF_N * REF_N;
  L->n = n, L->nb = NULL, L->cut = NULL;
  L->x = calloc(3 * (size_t)n, sizeof *L->x), L->u = calloc(3 * (size_t)n, sizeof *L->u);
  L->v = calloc(3 * (size_t)n, sizeof *L->v), L->f = calloc(3 * (size_t)n, sizeof *L->f);
  L->off = calloc((size_t)n + 1, sizeof *L->off);
  for (int i = 0; i < n; i++) {
    L->x[3 * i] = h * (i % REF_N), L->x[3 * i + 1] = h * (i / REF_N % REF_N), L->x[3 * i + 2] = h * (i / (REF_N * REF_N));
    for (int a = 0; a < 3; a++) L->v[3 * i + a] = 2.0 * (L->x[3 * i + a] - 4.5 * h) / (4.5 * h);
  }
  int cap = 0;
  for (int pass = 0; pass < 2; pass++) {
    int k = 0;
    for (int i = 0; i < n; i++) {
      L->off[i] = k;
      for (int j = 0; j < n; j++) {
        double d2 = 0;
        for (int a = 0; a < 3; a++) d2 += (L->x[3 * j + a] - L->x[3 * i + a]) * (L->x[3 * j + a] - L->x[3 * i + a]);
        if (j != i && d2 <= delta * delta) {
          if (pass) L->nb[k] = j;
          k++;
        }
      }
    }
    L->off[n] = k;
    if (!pass) cap = k, L->nb = calloc((size_t)cap, sizeof *L->nb), L->cut = calloc((size_t)cap, 1);
  }
  L->c = 18 * K / (PF_PI * delta * delta * delta * delta);
  L->s0 = 1e-3, L->vol = h * h * h, L->mass = rho * L->vol;
  L->dt = 0.5 * h / sqrt(K / rho) * 0.5;
}

static void ref_forces(ref_lattice *L) {
  for (int i = 0; i < L->n; i++) {
    double fi[3] = {0, 0, 0};
    for (int k = L->off[i]; k < L->off[i + 1]; k++) {
      if (L->cut[k]) continue;
      const int j = L->nb[k];
      double xi[3], eta[3], r0 = 0, r = 0;
      for (int a = 0; a < 3; a++) {
        xi[a] = L->x[3 * j + a] - L->x[3 * i + a];
        eta[a] = xi[a] + L->u[3 * j + a] - L->u[3 * i + a];
        r0 += xi[a] * xi[a], r += eta[a] * eta[a];
      }
      r0 = sqrt(r0), r = sqrt(r);
      const double s = (r - r0) / r0;
      if (s > L->s0) {
        L->cut[k] = 1;
        continue;
      }
      for (int a = 0; a < 3; a++) fi[a] += L->c * s * L->vol * eta[a] / r;
    }
    for (int a = 0; a < 3; a++) L->f[3 * i + a] = L->vol * fi[a];
  }
}

/* REF_STEPS velocity Verlet steps: half kick, drift, forces, half kick. */
static void ref_steps(ref_lattice *L) {
  for (int s = 0; s < REF_STEPS; s++) {
    for (int k = 0; k < 3 * L->n; k++) L->v[k] += 0.5 * L->dt * L->f[k] / L->mass, L->u[k] += L->dt * L->v[k];
    ref_forces(L);
    for (int k = 0; k < 3 * L->n; k++) L->v[k] += 0.5 * L->dt * L->f[k] / L->mass;
  }
}

static void ref_free(ref_lattice *L) {
  free(L->x), free(L->u), free(L->v), free(L->f), free(L->off), free(L->nb), free(L->cut);
}

/* Points, directed bonds and elements of the simulation (this rank). */
static void work_of(pf_sim *sim, double *points, double *bonds, double *elements) {
  *points = (double)pf_sim_points(sim)->n_owned, *bonds = 0, *elements = 0;
  for (int b = 0; b < pf_sim_nbodies(sim); b++) {
    pf_pd_body *pd = pf_sim_body(sim, b);
    struct pf_fem_body *fe = pf_sim_fem_body(sim, b);
    if (pd) *bonds += (double)pf_pd_body_nbonds(pd);
    if (fe) *elements += (double)pf_fem_body_mesh(fe)->nelem;
  }
}

int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  if (argc != 4) {
    fprintf(stderr, "usage: step_guard DECK WARMUP STEPS\n");
    MPI_Finalize();
    return 2;
  }
  pf_log_set_quiet(1);
  const long warm = atol(argv[2]), steps = atol(argv[3]);
  pf_sim_options opt = {.no_output = 1};
  pf_sim *sim = NULL;
  if (pf_sim_create(argv[1], &opt, &sim)) {
    fprintf(stderr, "step_guard: cannot build the simulation of %s\n", argv[1]);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  ref_lattice L;
  ref_build(&L);
  int ierr = pf_sim_step(sim, warm);
  CALLGRIND_START_INSTRUMENTATION;
  CALLGRIND_ZERO_STATS;
  if (!ierr) ierr = pf_sim_step(sim, steps);
  CALLGRIND_DUMP_STATS_AT("step");
  ref_steps(&L);
  CALLGRIND_DUMP_STATS_AT("reference");
  CALLGRIND_STOP_INSTRUMENTATION;
  if (ierr) {
    fprintf(stderr, "step_guard: the step failed on %s\n", argv[1]);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  double points, bonds, elements, broken = 0;
  work_of(sim, &points, &bonds, &elements);
  for (int k = 0; k < L.off[L.n]; k++) broken += L.cut[k];
  printf("steps %ld points %.0f bonds %.0f elements %.0f reference_bonds %d reference_steps %d reference_broken %.0f\n",
         steps, points, bonds, elements, L.off[L.n], REF_STEPS, broken);
  ref_free(&L);
  pf_sim_destroy(&sim);
  MPI_Finalize();
  return 0;
}
