/* Helpers for perifem's C tests: they print only on failure and exit non-zero. */
#ifndef PF_TEST_COMMON_H
#define PF_TEST_COMMON_H
#include "core/core.h"
#include "sim/sim.h"
#include "fem/fem.h"

extern int pf_test_failures;
/* Start MPI and silence logging. */
void pf_test_init(int *argc, char ***argv);
/* Finalize MPI; returns the process exit status (0 when every check passed). */
int pf_test_finish(void);

/* |got - want| <= tol_rel * |want| + tol_abs, else print both and count a failure. */
#define PF_TEST_CLOSE(got, want, tol_rel, tol_abs)                                                 \
  pf_test_close((got), (want), (tol_rel), (tol_abs), #got, __FILE__, __LINE__)
#define PF_TEST_TRUE(cond) pf_test_true((cond), #cond, __FILE__, __LINE__)
#define PF_TEST_OK(expr) pf_test_true((expr) == 0, #expr " returned 0", __FILE__, __LINE__)
void pf_test_close(double got, double want, double tol_rel, double tol_abs, const char *what,
                   const char *file, int line);
void pf_test_true(int cond, const char *what, const char *file, int line);
/* Write text to a fresh file under /tmp named after tag and the process id; returns its path
 * (static storage, valid until the next call with the same slot 0..7). */
const char *pf_test_write_file(int slot, const char *tag, const char *text);
/* Write an FE mesh as an Exodus file on rank 0, under a /tmp name every rank shares (rank 0's
 * process id); returns the path (static storage). Remove it with pf_test_remove_shared. */
const char *pf_test_write_mesh(const char *tag, const void *mesh); /* mesh: a pf_mesh */
/* A copy of the deck file beside it (same folder, so relative paths still hold) in which every
 * line containing keys[k] is replaced by lines[k]; returns its path (static storage). Rank 0
 * writes it, every rank may read it. Remove it with pf_test_remove_shared. Collective. */
const char *pf_test_deck_variant(const char *deck, int n, const char *const *keys, const char *const *lines);
/* Rank 0 removes path once every rank is past this point. Collective. */
void pf_test_remove_shared(const char *path);
/* Build a simulation from deck text (no output files); aborts the test on failure. */
struct pf_sim *pf_test_sim(const char *tag, const char *deck_text);
/* The bond-loop benchmark lattice: a 30^3 box of 1 mm spacing, horizon 3 spacings (113 bonds a
 * point inside), K = 1 GPa, G = 0.6 GPa, critical stretch 0.5, of the given PD model, with
 * reproducible random displacements of up to 0.5e-6 m (test_bond_loop_speed,
 * bench/bond_variants.c). */
struct pf_sim *pf_test_bond_lattice(const char *model);
/* The materials and the body of the bi-material bars (test_bimaterial_wave, _static): a PD bar
 * `bar` on a lattice of spacing h over [0, L] x [0, W]^2, horizon delta, its points of x < xI of
 * material `soft` (aluminium-like, rho 2700 kg/m^3, K 70 GPa), the others (material_regions) of
 * `stiff` (steel-like, 7800 kg/m^3, 160 GPa), model "pmb" or "lps" (then G = 0.6 K: Poisson's
 * ratio 1/4 in both); deck text ending in a newline, static storage. */
enum { PF_TEST_RHO_SOFT = 2700, PF_TEST_RHO_STIFF = 7800 };
#define PF_TEST_K_SOFT 70e9
#define PF_TEST_K_STIFF 160e9
const char *pf_test_bimaterial_bar(const char *model, double h, double delta, double xI, double L, double W);
/* The static pull of a bi-material bar by its series-spring field (a static text): x held in a
 * layer delta at each end to u = eps1 x (x < delta) and u = eps1 xI + eps2 (x - xI) (x > xend - delta),
 * the other points free along x; one Newton-Krylov load step to tolerance 1e-10, final time 1. */
const char *pf_test_series_pull(double delta, double xI, double xend, double eps1, double eps2);
/* The mean x displacement of the points of the layer of spacing h nearest to x, over the ranks. */
double pf_test_layer_u(const pf_points *p, double x, double h);
/* Deck text written to a scratch file and loaded, its root validated against keys (`where` names
 * the section in messages) when keys is not NULL. *d is the deck (pf_deck_destroy it), NULL on
 * an error; returns the first error. */
int pf_test_deck_text(const char *tag, const char *text, const pf_key *keys, const char *where, pf_deck **d);
/* The outcome of a deck that must be refused: ierr must be PF_ERR_INPUT, nothing made, and the
 * error message must mention must_mention (when not NULL); a failure is counted and the deck
 * printed otherwise. */
void pf_test_refused(int ierr, int made, const char *text, const char *must_mention);
/* n points at y (also their reference X), each of volume vol (cell size cbrt(vol)) and mass m,
 * body 0, at rest, no force; exits on failure. For unit tests of contact/ on hand-placed points. */
pf_points *pf_test_points(pf_int n, const double (*y)[3], double vol, double m);
/* One material point of the constitutive library, for the unit tests of fem/ models. */
typedef struct {
  double F[9], D[6], sig[6], st[8], c; /* deformation gradient, rate, stress, history, wave speed */
} pf_test_point;
/* Load a material from deck text whose root mapping is the material (checked against the
 * material keys when validate), named name; returns the error code (0 on success). */
int pf_test_material_load(const char *text, const char *name, int validate, pf_material **m);
/* The same, validated; a failure is a test failure (the deck is printed) and gives NULL. */
pf_material *pf_test_material_must_load(const char *text, const char *name);
/* A bad material deck must be refused with an input error whose message mentions
 * must_mention (when given); otherwise a test failure. */
void pf_test_material_bad(const char *text, const char *name, int validate, const char *must_mention);
/* F = I, the rest zero, the model's initial history. */
void pf_test_point_init(const pf_material *m, pf_test_point *p);
/* Advance the point over dt with its F and D. */
void pf_test_point_step(const pf_material *m, double dt, pf_test_point *p);
/* Rotation by angle t about the unit axis a (Rodrigues): R = cos t I + sin t [a]x +
 * (1 - cos t) a a^T, row-major. */
void pf_test_rotation(const double a[3], double t, double R[9]);

/* The `mesh:` entry of an FE body (at the indentation of a block-style body's keys): a Pamgen
 * rectilinear box of nx x ny x nz elements from lo to hi (static storage, valid until the next
 * call). */
const char *pf_test_pamgen_box(int nx, int ny, int nz, const double lo[3], const double hi[3]);
/* Take the initial step of sim and run it to its end, each step checked; the globals before
 * (g0) and after (g) when not NULL. Returns the steps taken. Collective. */
long pf_test_run_to_end(pf_sim *sim, pf_sim_globals *g0, pf_sim_globals *g);
/* With PF_TEST_DIGESTS set, rank 0 prints "state digest (tag): <hex>" (tests/regression/mpi_verify.sh
 * compares them over rank counts); with PF_TEST_DIGEST_FILE set it appends the same line to that
 * file, which pf_test_init empties (ctest sets it for the verification tests: mpi_verify takes
 * their 1-rank digests from there instead of running them again). Collective. */
void pf_test_print_digest(const char *tag, struct pf_sim *sim);
/* Record a measured value for docs/verification.md (scripts/verification_report.py): with
 * PF_MEASURE_DIR and PF_MEASURE_TEST set (ctest sets them: the test's name, e.g. test_wave),
 * rank 0 appends "key<TAB>value<TAB>unit" to $PF_MEASURE_DIR/$PF_MEASURE_TEST.tsv, which
 * pf_test_init empties. Nothing happens without both variables. The document
 * quotes the value as <!--m <test>.<key> FORMAT-->value<!--/m-->. */
void pf_test_measure(const char *key, double value, const char *unit);
#endif
