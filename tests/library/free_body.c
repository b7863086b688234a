/* tests/library/free_body.c DECK: a user program of the installed library (include/perifem.h,
 * libperifem.so, built with pkg-config). On tests/library/free_body.yaml:
 *  1. run in parts (0, 7, 13 steps, then to the end): the body's momentum in the history stays at
 *     its initial value (internal forces come in equal and opposite pairs) and equals sum m v of
 *     the fields read back; prints the state digest, which the test compares with perifem's;
 *  2. the same deck as YAML text with a uniform velocity override: u = v t at every point;
 *  3. bad input is a status and a message (a YAML error naming the deck and line, an unknown
 *     field listing the known ones), not an exit.
 * Prints only on failure, besides the digest line; exit status 0 when every check passes. */
#include <math.h>
#include <perifem.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;
#define CHECK(cond, ...)                                                                           \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);                                         \
      fprintf(stderr, __VA_ARGS__);                                                                \
      fprintf(stderr, "\n");                                                                       \
      failures++;                                                                                  \
    }                                                                                              \
  } while (0)
#define CALL(expr)                                                                                 \
  do {                                                                                             \
    if ((expr) != PERIFEM_OK) {                                                                    \
      fprintf(stderr, "FAIL %s:%d: %s: %s\n", __FILE__, __LINE__, #expr, perifem_last_error());    \
      exit(1);                                                                                     \
    }                                                                                              \
  } while (0)

static double history(perifem_sim *sim, const char *name) {
  double v = NAN;
  CALL(perifem_history_value(sim, name, &v));
  return v;
}

/* sum m v over the block's points (one rank: all of them) */
static void field_momentum(perifem_sim *sim, double p[3]) {
  const long n = perifem_body_points(sim, 0);
  double *m = malloc(sizeof(double) * (size_t)n), *v = malloc(sizeof(double) * 3 * (size_t)n);
  CALL(perifem_field_read(sim, 0, "mass", m, n));
  CALL(perifem_field_read(sim, 0, "velocity", v, 3 * n));
  p[0] = p[1] = p[2] = 0;
  for (long i = 0; i < n; i++)
    for (int c = 0; c < 3; c++) p[c] += m[i] * v[3 * i + c];
  free(m), free(v);
}

static void momentum_run(const char *deck) {
  perifem_options opt = {0};
  opt.quiet = 1;
  opt.output_dir = "out_c";
  perifem_sim *sim = NULL;
  CALL(perifem_create(deck, &opt, &sim));
  CHECK(perifem_body_count(sim) == 1 && !strcmp(perifem_body_name(sim, 0), "block"), "bodies");
  CHECK(perifem_body_points(sim, 0) == 7 * 6 * 9, "points %ld, expected 7 x 6 x 9", perifem_body_points(sim, 0));
  CALL(perifem_step(sim, 0));
  const double p0[3] = {history(sim, "momentum_x"), history(sim, "momentum_y"), history(sim, "momentum_z")};
  double scale = 0; /* sum m |v|: the size of the momenta that cancel */
  {
    const long n = perifem_body_points(sim, 0);
    const double *m, *v;
    int nc;
    CALL(perifem_field_view(sim, 0, "mass", &m, &nc));
    CHECK(nc == 1, "mass has %d components", nc);
    CALL(perifem_field_view(sim, 0, "velocity", &v, &nc));
    CHECK(nc == 3, "velocity has %d components", nc);
    for (long i = 0; i < n; i++) scale += m[i] * sqrt(v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]);
  }
  CALL(perifem_step(sim, 7));
  CALL(perifem_step(sim, 13));
  CHECK(perifem_step_count(sim) == 20 && !perifem_finished(sim), "after 20 steps: step %ld", perifem_step_count(sim));
  CALL(perifem_run(sim));
  CHECK(perifem_finished(sim) && perifem_step_count(sim) == 60, "finished at step %ld", perifem_step_count(sim));
  CHECK(fabs(perifem_time(sim) - 60 * perifem_dt(sim)) <= 1e-12 * perifem_time(sim), "time %g", perifem_time(sim));
  double p[3];
  field_momentum(sim, p);
  const char *axis[3] = {"momentum_x", "momentum_y", "momentum_z"};
  for (int c = 0; c < 3; c++) {
    const double h = history(sim, axis[c]);
    CHECK(fabs(h - p0[c]) <= 1e-12 * scale, "%s: %.17g at the end, %.17g at the start (scale %g)", axis[c], h, p0[c], scale);
    CHECK(fabs(h - p[c]) <= 1e-12 * scale, "%s: history %.17g, fields %.17g", axis[c], h, p[c]);
  }
  CHECK(history(sim, "step") == 60 && history(sim, "kinetic_energy") > 0, "history's last row");
  CHECK(history(sim, "damage_fraction") == 0, "damage");
  uint64_t digest;
  CALL(perifem_digest(sim, &digest));
  printf("state digest: %016llx\n", (unsigned long long)digest);
  CALL(perifem_destroy(&sim));
  CHECK(sim == NULL, "destroy nulls the handle");
}

static char *read_text(const char *path) {
  FILE *fp = fopen(path, "rb");
  if (!fp) fprintf(stderr, "FAIL: cannot read %s\n", path), exit(1);
  static char text[1 << 16];
  size_t n = fread(text, 1, sizeof text - 1, fp);
  fclose(fp);
  text[n] = '\0';
  return text;
}

static void translation_run(const char *deck) {
  const char *sets[] = {"bodies.block.initial_velocity=[10, -5, 2]", "time.steps=30"};
  perifem_options opt = {0};
  opt.quiet = 1;
  opt.no_output = 1;
  opt.overrides = sets;
  opt.noverrides = 2;
  perifem_sim *sim = NULL;
  CALL(perifem_create_from_string(read_text(deck), "text_deck.yaml", &opt, &sim));
  CALL(perifem_run(sim));
  CHECK(perifem_step_count(sim) == 30, "steps %ld", perifem_step_count(sim));
  const long n = perifem_body_points(sim, 0);
  double *u = malloc(sizeof(double) * 3 * (size_t)n);
  CALL(perifem_field_read(sim, 0, "displacement", u, 3 * n));
  const double t = perifem_time(sim), v[3] = {10, -5, 2};
  double worst = 0;
  for (long i = 0; i < n; i++)
    for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(u[3 * i + c] - v[c] * t));
  CHECK(worst <= 1e-9 * 10 * t, "rigid translation: |u - v t| up to %g m (v t = %g m)", worst, 10 * t);
  free(u);
  CALL(perifem_destroy(&sim));
}

static void bad_input(void) {
  perifem_options opt = {0};
  opt.silent_errors = 1;
  perifem_sim *sim = (perifem_sim *)&opt; /* must come back NULL */
  int ierr = perifem_create_from_string("bodies: [\n  - name: x\n    : : :\n", "broken.yaml", &opt, &sim);
  CHECK(ierr == PERIFEM_ERR_INPUT && sim == NULL, "a YAML error: status %d", ierr);
  CHECK(strstr(perifem_last_error(), "broken.yaml:") != NULL, "the message names the deck: '%s'", perifem_last_error());
  ierr = perifem_create("no/such/deck.yaml", &opt, &sim);
  CHECK(ierr == PERIFEM_ERR_INPUT && strstr(perifem_last_error(), "no/such/deck.yaml"), "a missing deck: %d '%s'", ierr,
        perifem_last_error());
  CHECK(perifem_step(NULL, 1) == PERIFEM_ERR_INPUT, "a NULL simulation");
  CHECK(perifem_history_count(NULL) == 0 && perifem_body_name(NULL, 0) == NULL, "queries on NULL");
}

static void bad_field(const char *deck) {
  perifem_options opt = {0};
  opt.silent_errors = 1;
  opt.quiet = 1;
  opt.no_output = 1;
  perifem_sim *sim = NULL;
  CALL(perifem_create(deck, &opt, &sim));
  double x;
  CHECK(perifem_history_value(sim, "time", &x) == PERIFEM_ERR_INPUT, "history before the run starts");
  CHECK(perifem_field_read(sim, 0, "pressure", &x, 1) == PERIFEM_ERR_INPUT &&
            strstr(perifem_last_error(), "known: reference_position"),
        "an unknown field: '%s'", perifem_last_error());
  CHECK(perifem_field_read(sim, 0, "mass", &x, 1) == PERIFEM_ERR_INPUT, "an array too short");
  CHECK(perifem_field_read(sim, 3, "mass", &x, 1) == PERIFEM_ERR_INPUT, "a bad body index");
  CHECK(perifem_field_components(sim, "damage") == 1, "damage is a registered field");
  CALL(perifem_destroy(&sim));
}

int main(int argc, char **argv) {
  if (argc != 2) return fprintf(stderr, "usage: free_body DECK\n"), 2;
  int major;
  perifem_version_numbers(&major, NULL, NULL);
  CHECK(major == PERIFEM_VERSION_MAJOR, "the library's major version %d, the header's %d", major, PERIFEM_VERSION_MAJOR);
  momentum_run(argv[1]);
  translation_run(argv[1]);
  bad_input();
  bad_field(argv[1]);
  CALL(perifem_finalize());
  return failures ? 1 : 0;
}
