#include "test_common.h"

#include <sys/stat.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sim/sim.h"
#include "fem/fem.h"

int pf_test_failures = 0;

/* $PF_MEASURE_DIR/<test>.tsv, or "" when measurements are not recorded. */
static char measure_path[1024];

/* Both variables must be set: a shell test that runs test programs (mpi_verify on 2 and 3 ranks)
 * passes on PF_MEASURE_DIR alone, and those runs must not overwrite the 1-rank measurements. */
static void measure_file_start(void) {
  const char *dir = getenv("PF_MEASURE_DIR"), *test = getenv("PF_MEASURE_TEST");
  if (!dir || !*dir || !test || !*test) return;
  snprintf(measure_path, sizeof measure_path, "%s/%s.tsv", dir, test);
  if (pf_comm_rank() == 0) mkdir(dir, 0777); /* (made at configure time; again if removed since) */
  FILE *f = pf_comm_rank() == 0 ? fopen(measure_path, "w") : NULL; /* emptied: this run's only */
  if (f) fclose(f);
}

void pf_test_init(int *argc, char ***argv) {
  MPI_Init(argc, argv);
  pf_log_set_quiet(1);
  const char *path = getenv("PF_TEST_DIGEST_FILE"); /* emptied here, appended to below */
  FILE *f = path && pf_comm_rank() == 0 ? fopen(path, "w") : NULL;
  if (f) fclose(f);
  measure_file_start();
}

void pf_test_measure(const char *key, double value, const char *unit) {
  if (!measure_path[0] || pf_comm_rank() != 0) return;
  FILE *f = fopen(measure_path, "a");
  if (!f) {
    fprintf(stderr, "cannot append to %s\n", measure_path);
    pf_test_failures++;
    return;
  }
  fprintf(f, "%s\t%.17g\t%s\n", key, value, unit ? unit : "");
  fclose(f);
}

int pf_test_finish(void) {
  int fails = pf_test_failures, total = 0;
  MPI_Allreduce(&fails, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  MPI_Finalize();
  return total ? 1 : 0;
}

void pf_test_close(double got, double want, double tol_rel, double tol_abs, const char *what,
                   const char *file, int line) {
  double err = fabs(got - want);
  if (!(err <= tol_rel * fabs(want) + tol_abs)) {
    fprintf(stderr, "%s:%d: %s = %.15g, expected %.15g (error %.3g, tolerance rel %.3g abs %.3g)\n",
            file, line, what, got, want, err, tol_rel, tol_abs);
    pf_test_failures++;
  }
}

void pf_test_true(int cond, const char *what, const char *file, int line) {
  if (!cond) {
    fprintf(stderr, "%s:%d: check failed: %s\n", file, line, what);
    pf_test_failures++;
  }
}

const char *pf_test_write_file(int slot, const char *tag, const char *text) {
  static char paths[8][256];
  snprintf(paths[slot], sizeof paths[slot], "/tmp/pf_test_%s_%d_%d.txt", tag, (int)getpid(), slot);
  FILE *fp = fopen(paths[slot], "w");
  if (!fp || fputs(text, fp) < 0) {
    fprintf(stderr, "cannot write %s\n", paths[slot]);
    exit(1);
  }
  fclose(fp);
  return paths[slot];
}

struct pf_sim *pf_test_sim(const char *tag, const char *deck_text) {
  const char *path = pf_test_write_file(7, tag, deck_text);
  pf_sim_options opt = {.no_output = 1};
  pf_sim *sim = NULL;
  if (pf_sim_create(path, &opt, &sim)) {
    fprintf(stderr, "%s: cannot build the simulation from deck %s\n", tag, path);
    exit(1);
  }
  remove(path);
  return sim;
}

const char *pf_test_bimaterial_bar(const char *model, double h, double delta, double xI, double L, double W) {
  static char text[1024];
  const double K1 = PF_TEST_K_SOFT, K2 = PF_TEST_K_STIFF;
  const double r1 = PF_TEST_RHO_SOFT, r2 = PF_TEST_RHO_STIFF;
  char mats[512];
  if (!strcmp(model, "pmb"))
    snprintf(mats, sizeof mats, "{soft: {model: pmb, density: %g, bulk_modulus: %g}, "
             "stiff: {model: pmb, density: %g, bulk_modulus: %g}}", r1, K1, r2, K2);
  else /* (elastic_plastic: yield stresses of their own, far above the tests' stresses, 0.2 GPa) */
    snprintf(mats, sizeof mats, "{soft: {model: %s, density: %g, bulk_modulus: %g, shear_modulus: %g%s}, "
             "stiff: {model: %s, density: %g, bulk_modulus: %g, shear_modulus: %g%s}}",
             model, r1, K1, 0.6 * K1, strcmp(model, "elastic_plastic") ? "" : ", yield_stress: 1.0e9", model, r2, K2,
             0.6 * K2, strcmp(model, "elastic_plastic") ? "" : ", yield_stress: 2.0e9");
  snprintf(text, sizeof text,
           "materials: %s\n"
           "bodies:\n  - {name: bar, material: soft, horizon: %.17g,\n"
           "     material_regions: [{material: stiff, region: {shape: box, lo: [%.17g, -1, -1], hi: [1, 1, 1]}}],\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], spacing: %.17g}}\n",
           mats, delta, xI, L, W, W, h);
  return text;
}

const char *pf_test_series_pull(double delta, double xI, double xend, double eps1, double eps2) {
  static char text[1024];
  snprintf(text, sizeof text,
           "boundary_conditions:\n"
           "  - {displacement: [free, \"0\", \"0\"]}\n"
           "  - {region: {shape: box, lo: [-1, -1, -1], hi: [%.17g, 1, 1]}, displacement: [\"%.17g * x * t\", \"0\", \"0\"]}\n"
           "  - {region: {shape: box, lo: [%.17g, -1, -1], hi: [1, 1, 1]},\n"
           "     displacement: [\"(%.17g + %.17g * (x - %.17g)) * t\", \"0\", \"0\"]}\n"
           "solver: {type: quasi_static, method: newton_krylov, load_steps: 1, tolerance: 1.0e-10, max_iterations: 200000}\n"
           "time: {final_time: 1}\n",
           delta, eps1, xend - delta, eps1 * xI, eps2, xI);
  return text;
}

double pf_test_layer_u(const pf_points *p, double x, double h) {
  double s[2] = {0, 0};
  for (pf_int i = 0; i < p->n_owned; i++)
    if (fabs(p->X[3 * i] - x) < 0.5 * h) s[0] += p->y[3 * i] - p->X[3 * i], s[1] += 1;
  MPI_Allreduce(MPI_IN_PLACE, s, 2, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return s[0] / s[1];
}

struct pf_sim *pf_test_bond_lattice(const char *model) {
  char deck[1024];
  snprintf(deck, sizeof deck,
           "materials: {m: {model: %s, density: 1000, bulk_modulus: 1.0e9, shear_modulus: 0.6e9}}\n"
           "bodies:\n  - {name: b, material: m, horizon: 3.0001e-3,\n"
           "     geometry: {shape: box, lo: [0, 0, 0], hi: [29e-3, 29e-3, 29e-3], spacing: 1e-3},\n"
           "     damage: {law: critical_stretch, critical_stretch: 0.5}}\n"
           "time: {steps: 0, dt: 1e-9}\n",
           model);
  pf_sim *sim = pf_test_sim("bond_loop_speed", deck);
  pf_points *p = pf_sim_points(sim);
  unsigned seed = 5;
  for (pf_int k = 0; k < 3 * p->n_owned; k++) {
    seed = seed * 1103515245u + 12345u;
    p->u[k] = 1e-6 * ((double)((seed >> 8) & 0xffff) / 65536.0 - 0.5);
    p->y[k] = p->X[k] + p->u[k];
  }
  return sim;
}

void pf_test_print_digest(const char *tag, struct pf_sim *sim) {
  uint64_t h = pf_sim_digest(sim);
  if (getenv("PF_TEST_DIGESTS") && pf_comm_rank() == 0) printf("state digest (%s): %016" PRIx64 "\n", tag, h);
  const char *path = getenv("PF_TEST_DIGEST_FILE");
  FILE *f = path && pf_comm_rank() == 0 ? fopen(path, "a") : NULL;
  if (f) fprintf(f, "state digest (%s): %016" PRIx64 "\n", tag, h), fclose(f);
}

const char *pf_test_write_mesh(const char *tag, const void *mesh) {
  static char path[256];
  int id = (int)getpid();
  MPI_Bcast(&id, 1, MPI_INT, 0, MPI_COMM_WORLD);
  snprintf(path, sizeof path, "/tmp/pf_test_%s_%d.e", tag, id);
  int ok = pf_comm_rank() != 0 || pf_mesh_write_exodus(path, (const pf_mesh *)mesh) == 0;
  pf_test_true(ok, "pf_mesh_write_exodus", __FILE__, __LINE__);
  MPI_Barrier(MPI_COMM_WORLD);
  return path;
}

const char *pf_test_deck_variant(const char *deck, int n, const char *const *keys, const char *const *lines) {
  static char path[512];
  int id = (int)getpid(); /* rank 0's: every rank reads the file rank 0 writes */
  MPI_Bcast(&id, 1, MPI_INT, 0, MPI_COMM_WORLD);
  const char *slash = strrchr(deck, '/');
  const int dir = slash ? (int)(slash - deck + 1) : 0;
  snprintf(path, sizeof path, "%.*s.variant_%d_%s", dir, deck, id, deck + dir);
  if (pf_comm_rank() == 0) {
    FILE *in = fopen(deck, "r"), *out = fopen(path, "w");
    if (!in || !out) {
      fprintf(stderr, "cannot copy %s to %s\n", deck, path);
      exit(1);
    }
    char line[1024];
    while (fgets(line, sizeof line, in)) {
      int k = 0;
      while (k < n && !strstr(line, keys[k])) k++;
      if (k < n) fprintf(out, "%s\n", lines[k]);
      else fputs(line, out);
    }
    fclose(in), fclose(out);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return path;
}

void pf_test_remove_shared(const char *path) {
  MPI_Barrier(MPI_COMM_WORLD);
  if (pf_comm_rank() == 0) remove(path);
}

long pf_test_run_to_end(pf_sim *sim, pf_sim_globals *g0, pf_sim_globals *g) {
  long steps = 0;
  PF_TEST_OK(pf_sim_step(sim, 0));
  if (g0) PF_TEST_OK(pf_sim_globals_get(sim, g0));
  for (; !pf_sim_finished(sim); steps++) PF_TEST_OK(pf_sim_step(sim, 1));
  if (g) PF_TEST_OK(pf_sim_globals_get(sim, g));
  return steps;
}

const char *pf_test_pamgen_box(int nx, int ny, int nz, const double lo[3], const double hi[3]) {
  static char text[512];
  snprintf(text, sizeof text,
           "    mesh:\n      pamgen: |\n        mesh\n          rectilinear\n"
           "            nx = %d\n            ny = %d\n            nz = %d\n"
           "            bx = 1\n            by = 1\n            bz = 1\n"
           "            gmin = %.17g %.17g %.17g\n            gmax = %.17g %.17g %.17g\n"
           "          end\n        end\n",
           nx, ny, nz, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  return text;
}

pf_points *pf_test_points(pf_int n, const double (*y)[3], double vol, double m) {
  pf_points *p = NULL;
  if (pf_points_create(n, &p)) {
    fprintf(stderr, "pf_points_create failed\n");
    exit(1);
  }
  for (pf_int i = 0; i < n; i++) {
    for (int a = 0; a < 3; a++) p->X[3 * i + a] = p->y[3 * i + a] = y[i][a];
    p->vol[i] = vol, p->cell[i] = cbrt(vol), p->m[i] = m;
  }
  return p;
}

int pf_test_material_load(const char *text, const char *name, int validate, pf_material **m) {
  *m = NULL;
  pf_deck *d = NULL;
  int ierr = pf_test_deck_text("fem_mat", text, validate ? pf_material_keys : NULL, "materials.test", &d);
  if (!ierr) ierr = pf_material_create(d, pf_deck_root(d), name, m);
  pf_deck_destroy(&d);
  return ierr;
}

pf_material *pf_test_material_must_load(const char *text, const char *name) {
  pf_material *m = NULL;
  if (pf_test_material_load(text, name, 1, &m)) {
    fprintf(stderr, "cannot load material deck:\n%s\n", text);
    pf_test_failures++;
  }
  return m;
}

int pf_test_deck_text(const char *tag, const char *text, const pf_key *keys, const char *where, pf_deck **d) {
  *d = NULL;
  const char *path = pf_test_write_file(0, tag, text);
  int ierr = pf_deck_load(path, d);
  if (!ierr && keys) ierr = pf_deck_validate(*d, pf_deck_root(*d), keys, where);
  remove(path);
  if (ierr) pf_deck_destroy(d);
  return ierr;
}

void pf_test_refused(int ierr, int made, const char *text, const char *must_mention) {
  if (ierr != PF_ERR_INPUT || made) {
    fprintf(stderr, "bad deck accepted (ierr %d):\n%s\n", ierr, text);
    pf_test_failures++;
  } else if (must_mention && !strstr(pf_error_message(), must_mention)) {
    fprintf(stderr, "error message '%s' does not mention '%s'\n", pf_error_message(), must_mention);
    pf_test_failures++;
  }
}

void pf_test_material_bad(const char *text, const char *name, int validate, const char *must_mention) {
  pf_material *m = NULL;
  pf_error_clear();
  const int ierr = pf_test_material_load(text, name, validate, &m);
  pf_test_refused(ierr, m != NULL, text, must_mention);
  pf_material_destroy(&m);
}

void pf_test_point_init(const pf_material *m, pf_test_point *p) {
  memset(p, 0, sizeof *p);
  p->F[0] = p->F[4] = p->F[8] = 1.0;
  pf_material_init(m, 1, p->st);
}

void pf_test_point_step(const pf_material *m, double dt, pf_test_point *p) {
  pf_material_update(m, 1, dt, p->F, p->D, p->sig, p->st, &p->c);
}

void pf_test_rotation(const double a[3], double t, double R[9]) {
  const double c = cos(t), s = sin(t);
  const double W[9] = {0, -a[2], a[1], a[2], 0, -a[0], -a[1], a[0], 0};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) R[3 * i + j] = (i == j ? c : 0.0) + s * W[3 * i + j] + (1 - c) * a[i] * a[j];
}
