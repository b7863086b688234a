/* Non-ordinary state-based correspondence: any continuum model of the constitutive library
 * (fem/: elastic, neo-Hookean, J2, Johnson-Cook + EOS, modified Johnson-Cook with damage) as a
 * peridynamic material. Theory: docs/theory/materials.md §2.
 *
 * Kinematics (Silling, Epton, Weckner, Xu & Askari 2007, J. Elast. 88:151, sec. 15; discrete form
 * of Tupek, Rimoli & Radovitzky 2013, CMAME 263:20, eqs. 3-4 and sec. 2.4):
 *   K_i    = sum_j w V_j xi (x) xi                           shape tensor, xi = x_j - x_i
 *   Fbar_i = [sum_j w V_j Y (x) xi] K_i^-1                   Y = y_j - y_i
 *   Fdot_i = [sum_j w V_j Ydot (x) xi] K_i^-1                Ydot = v_j - v_i
 * Stress: as in an FE element (fem/element_force.c), L = Fdot Fm^-1 on the mid-step
 * Fm = Fbar - dt/2 Fdot, D = sym L, the previous Cauchy stress rotated by the Hughes & Winget
 * (1980) increment of W = skew L; the continuum model then advances it (pf_material_update).
 * Force state (Silling et al. 2007, eq. 140; Tupek et al. eq. 5): T_i<xi> = w P_i K_i^-1 xi with
 * P = J sigma Fbar^-T, so with full neighbour lists
 *   f_i = V_i sum_j w V_j (P_i K_i^-1 + P_j K_j^-1) xi.
 * Damage correspondence (Tupek et al. 2013, eqs. 6-7): w = w_xi(|xi|) w_D(D_i, D_j), w_D = 0 once
 * either end's damage (the model's state "damage") exceeds D_c: the bond fails for good, so both
 * Fbar (from the next step) and the force use the degraded w.
 * Zero-energy-mode control (Littlewood 2012, IMECE2012-87977; Littlewood 2014 "Suppression of
 * Low-Energy Modes"): each end predicts the neighbour at x_i + Fbar_i xi; the deviation
 * Gamma_i = Fbar_i xi - Y projected on the bond direction M = Y/|Y| gives the pair force
 *   f_i += -C_hg c w V_i V_j [(Gamma_i + Gamma_j) . M] / |xi| M,  c = 18 K / (4 pi int w r^3 dr),
 * equal and opposite and along the bond (momentum and angular momentum conserved), zero under
 * any homogeneous deformation. The viscous variant (the analogue of Flanagan & Belytschko's
 * viscous hourglass control of hex8) penalises the deviation of the relative velocity from
 * Fdot xi instead, with c scaled by tau = delta / c_L (the wave transit of the horizon, so that
 * C_hg ~ 1 damps a mode of wavelength ~ delta critically): it damps zero-energy modes without
 * resisting the slow, non-affine flow of plastic deformation.
 * Cost (bench/measurements.md, "Correspondence and modified Johnson-Cook"): K is reference geometry,
 * formed again only when a point's intact own bonds change; each pass is one walk over the row
 * (the bond failures of the step are tested in the first); the 3x3 products are lane-wise
 * vector multiply-adds in the order of the scalar sums, so the results are those of the formulas
 * term by term; the common case (one horizon, influence 1, no partial volumes, stiffness control,
 * no blended or consistent terms) is a specialised copy of each loop. */
#include "pd/pd_impl.h"
#include "material/material.h"

#include <stdlib.h>
#include <string.h>

/* Four doubles in one vector register (GCC/Clang vector extension; two SSE2 halves where the
 * target has no AVX): a 3-vector or a column of a 3x3 matrix in lanes 0-2, lane 3 unused. */
typedef double v4d __attribute__((vector_size(4 * sizeof(double))));
static inline v4d v4d_load(const double *q) {
  v4d v;
  memcpy(&v, q, sizeof v);
  return v;
}


/* Ghosted per-point record, one exchange per step: P K^-1, Fbar, Fdot (each by columns: M_rc at
 * r + 3 c, for the lane-wise products of pair_sums), detached,
 * damage, the hourglass micromodulus of the point's horizon, and P itself (the partial stress
 * nu = sum_j w P K^-1 xi (x) xi V_j = P, for the partial-stress form; docs/theory/coupling.md
 * §2). */
enum { G_PK = 0, G_F = 9, G_FDOT = 18, G_DETACHED = 27, G_DAMAGE = 28, G_C = 29, G_NU = 30, GX = 39 };

/* The cached shape of each point's intact own bonds (kshape): the entries step_rates reads. */
enum { KS_LMIN = 0, KS_LEN = 1, KS_INV = 2, KS_SPANS = 3, KS_SPREAD = 4, KS = 5 };

typedef struct {
  pf_material *cm; /* the continuum model (of the body's material: part 0) */
  /* several materials (docs/theory/interfaces.md §3a): part q's continuum model, of the body's
   * model with its own constants (cms[0] = cm), and its initial P-wave speed */
  pf_material *cms[PF_PD_MAX_PARTS];
  double cls[PF_PD_MAX_PARTS];
  char model[32]; /* the body's `model:` */
  int nstate, idamage; /* history variables; index of the one named "damage", or -1 */
  int viscous;         /* hourglass control on the velocity deviation instead of the position's */
  int keep_stress;     /* bond_loss: keep_stress (1) or jump (0) */
  double hg, dcrit;    /* C_hg, D_c */
  double cl;           /* the initial P-wave speed: the viscous form's tau = delta / c_L, the time
                          a wave takes to cross the horizon */
  double gamma;        /* max_k |b(k)| / (sum w V |xi| / lambda_min K) in the continuum (step) */
  double *sigma;       /* field "stress" [6]: Cauchy stress, Pa */
  double *state;       /* field "material_state_<nstate>" */
  double *work;        /* field "stress_work": stress work per reference volume, J/m^3 */
  double *hgwork;      /* field "hourglass_work": work of the hourglass forces, J */
  double *hgforce;     /* field "hourglass_force" [3]: last step's, for the trapezoidal work */
  double *gx;          /* field "correspondence" [GX] */
  double *step;        /* field "stable_step": each point's stable step at its last evaluation */
  double **out;        /* [nstate] output fields named by the model's state names */
  double *F, *D, *s_old, *saved, *Jm; /* scratch: [9n], [6n], [6n], [nstate n], [n] */
  double *Ki;                         /* scratch [9n]: K^-1, for the partial-stress force */
  double *K0;                         /* [9n] the whole family's shape tensor (broken bonds too) */
  int *nfam;                          /* [n] the number of bonds in the point's own family */
  unsigned char *lost;                /* [n] the point lost a bond this step (rereference) */
  double *jump; /* [n] scratch: the step's unbooked work at a point whose bonds failed or that
                   detached (failure_work; docs/theory/pd.md §5.1), J; NAN elsewhere */
  double *ghost;                      /* field "ghost_correction" [3]: the corrected form's d_i */
  double *lm;                         /* field "consistent_weights": the consistent form's multipliers */
  double *rate, *whg2, *cw; /* scratch [n]: beta / sigma_min(Fbar), omega_hg^2, wave speed */
  double *mrow, *crow; /* [n] several materials: the largest P-wave modulus over the point's row over
                          its own, and the largest hourglass micromodulus there (row_bounds) */
  /* The shape tensor of each owned point's intact own bonds, kept between steps (it depends only
   * on the reference positions and on which bonds are intact, and bonds only ever fail): valid
   * while the point's count of intact own bonds is kcount (-1: to compute). */
  int *kcount;       /* [n] */
  double *kinv;      /* [9n] K^-1 */
  double *kshape;    /* [KS n] lambda_min(K), sum_j w V_j |xi|, sum_j w V_j / |xi|, 1 if K spans,
                        sum_j w V_j |K^-1 xi| */
  uint8_t *fails;    /* [store] last step's record of each point, for the bond failures:
                        bit 0 detached, bit 1 damage above D_c, bit 2 in the PD region */
  uint8_t *nearz;    /* [n] the point or one in its row takes the consistent form */
  pf_int cap, fcap;
} corr;

const pf_key pf_pd_hourglass_keys[] = {
    {"type", PF_KEY_STRING, 0, "stiffness", "", "stiffness (Littlewood) | viscous | none", NULL},
    {"coefficient", PF_KEY_REAL, 0, "0.05", "", "C_hg >= 0", NULL},
    PF_KEY_END};

static int read_hourglass(const pf_deck *d, const pf_node *h, corr *p) {
  const char *type = "stiffness";
  p->hg = 0.05;
  if (!h) return 0;
  PF_CALL(pf_deck_string(d, h, "type", &type));
  PF_CALL(pf_deck_real(d, h, "coefficient", &p->hg));
  if (!(p->hg >= 0)) return pf_deck_error(d, pf_node_get(h, "coefficient"), "coefficient", "must be >= 0 (got %g)", p->hg);
  if (!strcmp(type, "none")) p->hg = 0;
  else if (!strcmp(type, "viscous")) p->viscous = 1;
  else if (strcmp(type, "stiffness"))
    return pf_deck_error(d, pf_node_get(h, "type"), "type", "unknown hourglass control '%s' (known: stiffness, viscous, none)", type);
  return 0;
}

/* int_0^delta w r^3 j1(kappa r) dr, or int w r^3 dr when kappa = 0; Simpson's rule on 200
 * intervals (the r = 0 end contributes nothing). */
static double r3_moment(const pf_influence *w, double delta, double kappa) {
  const int n = 200;
  double sum = 0;
  for (int q = 1; q <= n; q++) {
    const double r = delta * q / n, x = kappa * r, wq = q == n ? 1 : (q % 2 ? 4 : 2);
    const double j1 = x < 1e-3 ? x / 3.0 : sin(x) / (x * x) - cos(x) / x;
    sum += wq * pf_pd_omega(w, r) * r * r * r * (kappa > 0 ? j1 : 1.0);
  }
  return sum * delta / (3.0 * n);
}

/* The wave factor of the stable step (docs/theory/materials.md §2.6): in the continuum,
 * sum_j w V_j xi sin(k.xi) = 4 pi khat int w r^3 j1(|k| r) dr and K = (4 pi / 3) int w r^4 dr I, so
 * max_k |b(k)| = gamma beta with gamma = max_kappa int w r^3 j1(kappa r) dr / int w r^3 dr, j1 the
 * spherical Bessel function (0.416 for w = 1, 0.391 for the Gaussian of sigma = delta/2),
 * searched over kappa delta on a 0.01 grid up to 30. */
static double wave_factor(const pf_influence *w, double delta) {
  const double den = r3_moment(w, delta, 0.0);
  double best = 0;
  for (int m = 1; m <= 3000; m++) best = fmax(best, r3_moment(w, delta, 0.01 * m / delta) / den);
  return best;
}

static int corr_create(const pf_deck *d, const pf_node *mat, pf_pd_body *b) {
  const char *mname = b->material;
  corr *p;
  PF_MALLOC(p, 1);
  b->mat = p;
  PF_CALL(pf_material_create(d, mat, mname, &p->cm));
  p->cms[0] = p->cm;
  const char *model = "";
  PF_CALL(pf_deck_string(d, mat, "model", &model));
  snprintf(p->model, sizeof p->model, "%s", model);
  b->bulk_modulus = pf_material_bulk_modulus(p->cm);
  b->shear_modulus = pf_material_shear_modulus(p->cm);
  b->density = pf_material_density(p->cm);
  p->nstate = pf_material_nstate(p->cm);
  p->idamage = -1;
  for (int k = 0; k < p->nstate; k++)
    if (!strcmp(pf_material_state_name(p->cm, k), "damage")) p->idamage = k;
  PF_CALL(read_hourglass(d, pf_node_get(b->node, "hourglass"), p));
  p->dcrit = 0.99;
  PF_CALL(pf_deck_real(d, b->node, "critical_damage", &p->dcrit));
  const pf_node *dc = pf_node_get(b->node, "critical_damage");
  if (dc && p->idamage < 0)
    return pf_deck_error(d, dc, "critical_damage", "the model of material '%s' has no damage variable "
                         "(modified_johnson_cook has one)", mname);
  if (!(p->dcrit > 0 && p->dcrit <= 1))
    return pf_deck_error(d, dc, "critical_damage", "must satisfy 0 < D_c <= 1 (got %g)", p->dcrit);
  const char *loss = "keep_stress";
  PF_CALL(pf_deck_string(d, b->node, "bond_loss", &loss));
  p->keep_stress = !strcmp(loss, "keep_stress");
  if (!p->keep_stress && strcmp(loss, "jump"))
    return pf_deck_error(d, pf_node_get(b->node, "bond_loss"), "bond_loss", "unknown '%s' (known: keep_stress, jump)", loss);
  p->cl = sqrt((b->bulk_modulus + 4.0 * b->shear_modulus / 3.0) / b->density);
  p->cls[0] = p->cl;
  return 0;
}

/* Part q's material (several materials): a continuum model of the body's model, with its own
 * constants (an orthotropic part its own axes), created with the part; its density and small-strain
 * K, G into the part (pf_pd_material_ops.read_part). */
static int corr_read_part(const pf_deck *d, const pf_node *mat, const char *name, pf_pd_body *b, int q,
                          pf_pd_part *part) {
  corr *p = b->mat;
  const char *model = "";
  PF_CALL(pf_deck_string(d, mat, "model", &model));
  if (strcmp(model, p->model))
    return pf_deck_error(d, pf_node_get(part->node, "material"), "material", "material '%s' is model '%s', body "
                         "'%s''s material '%s' is '%s': the materials of one correspondence body%s share a continuum "
                         "model (their constants may differ)", name, model, b->name, b->material, p->model,
                         b->coupled ? " (the peridynamic: operator of a finite_element body)" : "");
  PF_CALL(pf_material_create(d, mat, name, &p->cms[q]));
  part->density = pf_material_density(p->cms[q]);
  part->K = pf_material_bulk_modulus(p->cms[q]);
  part->G = pf_material_shear_modulus(p->cms[q]);
  p->cls[q] = sqrt((part->K + 4.0 * part->G / 3.0) / part->density);
  return 0;
}

/* Point i's continuum model and initial P-wave speed: its part's. */
static inline const pf_material *model_at(const pf_pd_body *b, pf_int i) {
  const corr *p = b->mat;
  return b->part ? p->cms[(int)b->part[i]] : p->cm;
}
static inline double cl_at(const pf_pd_body *b, pf_int i) {
  const corr *p = b->mat;
  return b->part ? p->cls[(int)b->part[i]] : p->cl;
}

/* Register a field that a step advances: it is history, committed and restored by the
 * quasi-static solver (pd/history.c). */
static int history_field(pf_pd_body *b, pf_points *pts, const char *name, int ncomp, int flags, double **data) {
  int idx;
  PF_CALL(pf_points_field_register(pts, name, ncomp, flags | PF_FIELD_RESTART, &idx));
  *data = pts->fields[idx].data;
  return pf_pd_body_keep_history(b, idx);
}

static int register_fields(pf_pd_body *b, pf_points *pts) {
  corr *p = b->mat;
  int idx;
  PF_CALL(history_field(b, pts, "stress", 6, PF_FIELD_OUTPUT, &p->sigma));
  PF_CALL(history_field(b, pts, "stress_work", 1, 0, &p->work));
  PF_CALL(history_field(b, pts, "hourglass_work", 1, 0, &p->hgwork));
  PF_CALL(history_field(b, pts, "hourglass_force", 3, 0, &p->hgforce));
  PF_CALL(history_field(b, pts, "correspondence", GX, PF_FIELD_GHOST, &p->gx));
  PF_CALL(history_field(b, pts, "stable_step", 1, 0, &p->step));
  if (!p->nstate) return 0;
  char name[32];
  snprintf(name, sizeof name, "material_state_%d", p->nstate); /* bodies own disjoint ranges */
  PF_CALL(history_field(b, pts, name, p->nstate, 0, &p->state));
  if (!p->out) PF_MALLOC(p->out, p->nstate);
  for (int k = 0; k < p->nstate; k++) { /* the model's damage D is not the bond damage phi */
    const char *sname = pf_material_state_name(p->cm, k);
    PF_CALL(pf_points_field_register(pts, k == p->idamage ? "material_damage" : sname, 1, PF_FIELD_OUTPUT, &idx));
    p->out[k] = pts->fields[idx].data;
  }
  return 0;
}

/* The stable step of a point (docs/theory/materials.md §2.6). Linearised about a homogeneous
 * state, a plane wave u = U exp(i k.X) gives Fbar' = i U (x) b, b = K^-1 sum_j w V_j xi sin(k.xi),
 * and the force density -(c:(U (x) b')) b' with b' = Fbar^-T b, so omega <= c |b'| <= c gamma
 * beta / sigma_min(Fbar), where beta = sum_j w V_j |xi| / lambda_min(K) would bound |b| if every
 * sin(k.xi) could be 1 at once, gamma (wave_factor) is the largest fraction of it a wave reaches
 * in the continuum, and c is the model's current P-wave speed. |b| <= sum_j w V_j |K^-1 xi|
 * (spread, spread_of) holds for any family, without gamma, and is the smaller where K is nearly
 * flat. The stiffness-form hourglass force adds at most omega_hg^2 = 4 C_hg c_hg sum_j w V_j /
 * |xi| / rho (the PMB bound of Silling & Askari 2005, eq. 16, doubled: both ends' deviations act
 * on a bond); eigenvalues of a sum add, so omega^2 sums. Computes rate = min(gamma beta, spread) /
 * sigma_min (0 for a point without stiffness) and omega_hg^2; the step is 2 / sqrt((c rate)^2 +
 * omega_hg^2). */
static void step_rates(const pf_pd_body *b, pf_int i, double lk, double Fb[3][3],
                       const double sums[2], double spread, double *rate, double *whg2) {
  const corr *p = b->mat;
  double C[3][3];
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) C[r][c] = Fb[0][r] * Fb[0][c] + Fb[1][r] * Fb[1][c] + Fb[2][r] * Fb[2][c];
  const double lc = pf_sym3_min_eigenvalue(C); /* lk = lambda_min(K) */
  *rate = lk > 0 && lc > 0 ? fmin(p->gamma * sums[0] / (lk * sqrt(lc)), spread / sqrt(lc)) : 0.0;
  const double chg = b->part ? p->crow[i - b->first] : p->gx[GX * i + G_C];
  if (b->part) *rate *= sqrt(p->mrow[i - b->first]); /* (the row's stiffest neighbour: an upper bound) */
  *whg2 = p->viscous ? 0.0 : 4.0 * p->hg * chg * sums[1] / pf_pd_density(b, i);
}

/* Several materials (docs/theory/interfaces.md §7): the force on point i takes its neighbours'
 * force states and hourglass stiffnesses as well as its own, so its step is bounded with the
 * largest of them over its row: the P-wave modulus M = K + 4G/3 relative to its own (the wave
 * speed's factor sqrt(mrow)) and the hourglass micromodulus crow. */
static void row_bounds(pf_pd_body *b) {
  corr *p = b->mat;
  for (pf_int li = 0; li < b->n; li++) {
    const pf_int i = b->first + li;
    const double Mi = pf_pd_K(b, i) + 4.0 * pf_pd_G(b, i) / 3.0;
    double Kmax = pf_pd_K(b, i), Mmax = Mi;
    for (int64_t k = b->fam.offset[li]; k < b->fam.offset[li + 1]; k++) {
      const pf_int j = b->fam.neighbor[k];
      Kmax = fmax(Kmax, pf_pd_K(b, j)), Mmax = fmax(Mmax, pf_pd_K(b, j) + 4.0 * pf_pd_G(b, j) / 3.0);
    }
    p->mrow[li] = Mmax / Mi;
    p->crow[li] = pf_pd_pmb_micromodulus(Kmax, &b->influence, b->hz[i]);
  }
}

/* sum_j w V_j |K^-1 xi| over the intact own bonds of point i, K^-1 = Ki (step_rates): on a
 * complete family, where K is isotropic, sum_j w V_j |xi| / lambda(K); where bonds are missing
 * only a bond's component along K's weak direction is amplified by 1 / lambda_min(K)
 * (docs/theory/materials.md §2.6). */
static double spread_of(const pf_pd_body *b, const pf_points *pts, pf_int i, double Ki[3][3]) {
  double sum = 0;
  for (int64_t k = b->fam.offset[i - b->first]; k < b->fam.offset[i - b->first + 1]; k++) {
    double xi[3], r0, w, z[3];
    if (!pf_pd_own_bond(b, pts, i, k, xi, &r0, &w)) continue;
    for (int r = 0; r < 3; r++) z[r] = Ki[r][0] * xi[0] + Ki[r][1] * xi[1] + Ki[r][2] * xi[2];
    sum += w * sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
  }
  return sum;
}

/* A point's stable step in the reference configuration (Fbar = I, the model's initial P-wave
 * speed), before its first evaluation. */
static double reference_step(const pf_pd_body *b, const pf_points *pts, pf_int i) {
  const pf_family *fam = &b->fam;
  double K[3][3] = {{0}}, Ki[3][3], I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, sums[2] = {0, 0}, rate, whg2;
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
    double xi[3], r0, w;
    if (!pf_pd_own_bond(b, pts, i, k, xi, &r0, &w)) continue;
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) K[r][c] += w * xi[r] * xi[c];
    sums[0] += w * r0, sums[1] += w / r0;
  }
  const double spread = pf_mat3_inverse(K, Ki) > 0 ? spread_of(b, pts, i, Ki) : INFINITY;
  step_rates(b, i, pf_sym3_min_eigenvalue(K), I, sums, spread, &rate, &whg2);
  const double cl = cl_at(b, i);
  return 2.0 / sqrt(cl * cl * rate * rate + whg2);
}

/* The uniform-stress ghost vector of the standard form (docs/theory/coupling.md §2.5): under a
 * uniform stress nu the standard force of point i is V_i nu c_i, c_i = sum_j w V_j ([j in H_i]
 * K_i^-1 + [i in H_j] K_j^-1) xi, zero on a complete family of constant horizon; where the horizon
 * varies, the part of it a constant horizon would give is c_i^ref = 2 sum_{j in H_i} w V_j K_i^-1 xi
 * (the surface traction of the weak form), and the ghost force is V_i nu_i d_i, d_i = c_i - c_i^ref.
 * Into d[3 (i - first)] for the owned points whose region has a bit of mask (0 elsewhere), with the
 * neighbours' K^-1 through a ghosted field. Collective. */
static int ghost_vector(pf_pd_body *b, pf_points *pts, int mask, double *d) {
  int idx;
  PF_CALL(pf_points_field_register(pts, "shape_tensor_inverse", 9, PF_FIELD_GHOST, &idx));
  double *kinv = pts->fields[idx].data;
  for (pf_int i = b->first; i < b->first + b->n; i++) pf_pd_shape_tensor_inverse(b, pts, i, &kinv[9 * i]);
  PF_CALL(pf_points_exchange(pts, kinv, 9));
  const pf_family *fam = &b->fam;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    double *di = &d[3 * (i - b->first)];
    di[0] = di[1] = di[2] = 0.0;
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1] && ((int)b->region[i] & mask); k++) {
      const pf_int j = fam->neighbor[k];
      double xi[3], r02 = 0;
      for (int a = 0; a < 3; a++) xi[a] = pts->X[3 * j + a] - pts->X[3 * i + a], r02 += xi[a] * xi[a];
      const double r0 = sqrt(r02), hi = pf_pd_in_family(b, i, r0), hj = pf_pd_in_family(b, j, r0);
      const double w = pf_pd_omega(&b->influence, r0) * pf_pd_bond_volume(fam, pts->vol, k, j);
      for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) di[a] += w * (hj * kinv[9 * j + 3 * a + c] - hi * kinv[9 * i + 3 * a + c]) * xi[c];
    }
  }
  return 0;
}

/* Does any point of the body, on any rank, have region bit mask? (collective) */
static int any_region(const pf_pd_body *b, int mask) {
  int any = 0;
  for (pf_int i = b->first; i < b->first + b->n; i++) any |= ((int)b->region[i] & mask) != 0;
  return pf_sum_all(any) > 0;
}

/* The corrected form (§2.5) takes V_i nu_i d_i off the standard force of its points. d is the
 * reference geometry's: computed at t = 0 and kept as a point field that migrates and is
 * checkpointed (a neighbour's later broken bonds must not change it on a re-partition or a
 * restart). */
static int ghost_vectors(pf_pd_body *b, pf_points *pts) {
  corr *p = b->mat;
  int idx;
  if (!any_region(b, 4)) return 0;
  PF_CALL(pf_points_field_register(pts, "ghost_correction", 3, PF_FIELD_RESTART, &idx));
  p->ghost = pts->fields[idx].data;
  return b->fresh ? ghost_vector(b, pts, 4, &p->ghost[3 * b->first]) : 0;
}

/* Does point i's row reach a point of another horizon? */
static int horizon_varies(const pf_pd_body *b, pf_int i) {
  const pf_family *fam = &b->fam;
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++)
    if (b->hz[fam->neighbor[k]] != b->hz[i]) return 1;
  return 0;
}

/* The targets t_n of the consistent form's condition (C), sum_j (beta_j V_j h_jn - beta_n V_n h_nj)
 * = t_n (docs/theory/coupling.md §2.6, §3.4): the change of the uniform-stress vector
 * C_n = sum_j (beta_j V_j g_jn - beta_n V_n g_nj) + sum_e (1 - beta_e) V_e B_en that takes it to
 * its value in one model of constant horizon. With d_n the standard form's ghost vector
 * (ghost_vector, at the points whose row reaches another horizon) and, coupled in the energy
 * form, the blending's part,
 *   t_n = beta_n V_n d_n + V_n sum_j (beta_j - beta_n) w V_j [n in H_j] K_j^-1 xi_nj
 *         - sum_e (beta_n - beta_e) V_e B_en,
 * the last sum given by the elements (pf_pd_body_set_fe_vector). Uncoupled, t_n = V_n d_n. Into
 * t[3 (n - first)] for every owned point; K^-1 comes in the ghosted field ghost_vector filled. */
static int consistent_targets(pf_pd_body *b, pf_points *pts, double *t) {
  PF_CALL(ghost_vector(b, pts, 8, t));
  const double *kinv = pf_points_field_get(pts, "shape_tensor_inverse");
  const pf_family *fam = &b->fam;
  const int blended = b->blend && b->blend_states;
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    double *ti = &t[3 * (i - b->first)], s[3] = {0, 0, 0}, fe[3] = {0, 0, 0};
    const double bi = pf_pd_energy_weight(b, i), V = pts->vol[i];
    const int varies = pf_pd_consistent_at(b, i) && horizon_varies(b, i);
    for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1] && blended; k++) {
      const pf_int j = fam->neighbor[k];
      if (b->blend[j] == b->blend[i]) continue;
      double xi[3], r02 = 0;
      for (int a = 0; a < 3; a++) xi[a] = pts->X[3 * j + a] - pts->X[3 * i + a], r02 += xi[a] * xi[a];
      const double r0 = sqrt(r02);
      if (!pf_pd_in_family(b, j, r0)) continue;
      const double w = (b->blend[j] - b->blend[i]) * pf_pd_omega(&b->influence, r0) * pf_pd_bond_volume(fam, pts->vol, k, j);
      for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) s[a] += w * kinv[9 * j + 3 * a + c] * xi[c];
    }
    if (blended && b->fe_vector) b->fe_vector(b->fe_vector_ctx, i, fe);
    for (int a = 0; a < 3; a++) ti[a] = (varies ? bi * V * ti[a] : 0.0) + V * s[a] - fe[a];
  }
  return 0;
}

/* The consistent form (§2.6): the multipliers of its weight corrections, solved for at t = 0
 * (pd/consistent.c) and kept as a ghosted point field that migrates and is checkpointed. */
static int consistent_weights(pf_pd_body *b, pf_points *pts) {
  corr *p = b->mat;
  int idx;
  if (!any_region(b, 8)) return 0;
  PF_CALL(pf_points_field_register(pts, "consistent_weights", PF_CONSISTENT_NLM, PF_FIELD_GHOST | PF_FIELD_RESTART, &idx));
  p->lm = pts->fields[idx].data;
  if (b->fresh) {
    double *t;
    PF_MALLOC(t, 3 * (size_t)b->n + 1);
    int ierr = consistent_targets(b, pts, t);
    if (!ierr) ierr = pf_pd_consistent_solve(b, pts, t, p->lm);
    free(t);
    PF_CALL(ierr);
  }
  return pf_points_exchange(pts, p->lm, PF_CONSISTENT_NLM);
}

/* Each owned point's whole own family (its broken bonds too, so the same after a re-partition or
 * a restart): the number of its bonds and their shape tensor K0, for the span test. */
static void whole_families(pf_pd_body *b, const pf_points *pts) {
  corr *p = b->mat;
  const pf_family *fam = &b->fam;
  for (pf_int li = 0; li < b->n; li++) {
    const pf_int i = b->first + li;
    double *K0 = &p->K0[9 * li];
    memset(K0, 0, 9 * sizeof(double));
    p->nfam[li] = 0;
    for (int64_t k = fam->offset[li]; k < fam->offset[li + 1]; k++) {
      const pf_int j = fam->neighbor[k];
      double xi[3], r02 = 0;
      for (int a = 0; a < 3; a++) xi[a] = pts->X[3 * j + a] - pts->X[3 * i + a], r02 += xi[a] * xi[a];
      const double r0 = sqrt(r02);
      if (!pf_pd_in_family(b, i, r0)) continue;
      const double w = pf_pd_omega(&b->influence, r0) * pf_pd_bond_volume(fam, pts->vol, k, j);
      for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) K0[3 * r + c] += w * xi[r] * xi[c];
      p->nfam[li]++;
    }
  }
}

/* Does a shape tensor K of nb bonds and determinant det span three dimensions:
 * nb >= 3 and det K > 1e-6 (tr K / 3)^3 (docs/theory/materials.md §2)? */
static int shape_spans(int nb, double det, double K[3][3]) {
  const double tr = (K[0][0] + K[1][1] + K[2][2]) / 3.0;
  return nb >= 3 && det > 1e-6 * tr * tr * tr;
}

/* A point whose whole family does not span three dimensions (shape_spans on K0) is detached from
 * the first step, its bonds failed: a horizon below the spacing there, or a point alone. Said
 * once, at the run's start, naming the first such point (the lowest global id); a coupled body's
 * points that take no PD force (idle) are passed over. Collective. */
static void warn_flat_families(const pf_pd_body *b, const pf_points *pts) {
  const corr *p = b->mat;
  double n = 0, gid = INFINITY, x[3] = {0, 0, 0};
  for (pf_int li = 0; li < b->n; li++) {
    double K0[3][3];
    if (b->blend && (b->idle ? b->idle[li] : b->blend[b->first + li] == 0)) continue; /* (no PD force wanted) */
    memcpy(K0, &p->K0[9 * li], sizeof K0);
    if (shape_spans(p->nfam[li], pf_mat3_det(K0), K0)) continue;
    n++, gid = fmin(gid, (double)pts->gid[b->first + li]);
  }
  if (!(pf_sum_all(n) > 0)) return;
  const double first = pf_min_all(gid);
  for (pf_int li = 0; li < b->n && gid == first; li++)
    if ((double)pts->gid[b->first + li] == first) memcpy(x, &pts->X[3 * (b->first + li)], sizeof x);
  for (int a = 0; a < 3; a++) x[a] = pf_sum_all(x[a]);
  pf_deck_warn(b->deck, b->node, "horizon",
               "body '%s': %.0f points have families that do not span three dimensions (the first at (%g, %g, %g) m): "
               "they are detached and their bonds fail at the first step (a horizon below the spacing there?)",
               b->name, pf_sum_all(n), x[0], x[1], x[2]);
}

static int corr_setup(pf_pd_body *b, pf_points *pts) {
  corr *p = b->mat;
  PF_CALL(register_fields(b, pts));
  if (b->n > p->cap) {
    free(p->F), free(p->D), free(p->s_old), free(p->saved), free(p->Jm);
    free(p->rate), free(p->whg2), free(p->cw), free(p->Ki), free(p->K0), free(p->nfam), free(p->lost);
    free(p->kcount), free(p->kinv), free(p->kshape), free(p->nearz), free(p->jump), free(p->mrow), free(p->crow);
    p->lost = p->nearz = NULL;
    p->mrow = p->crow = NULL;
    p->F = p->D = p->s_old = p->saved = p->Jm = p->rate = p->whg2 = p->cw = p->Ki = p->K0 = p->jump = NULL;
    p->kinv = p->kshape = NULL;
    p->nfam = p->kcount = NULL;
    PF_MALLOC(p->kcount, b->n);
    PF_MALLOC(p->kinv, 9 * (size_t)b->n);
    PF_MALLOC(p->kshape, KS * (size_t)b->n);
    PF_MALLOC(p->nearz, b->n);
    PF_MALLOC(p->Ki, 9 * (size_t)b->n);
    PF_MALLOC(p->K0, 9 * (size_t)b->n);
    PF_MALLOC(p->nfam, b->n);
    PF_MALLOC(p->lost, b->n);
    PF_MALLOC(p->jump, b->n);
    PF_MALLOC(p->Jm, b->n);
    PF_MALLOC(p->rate, b->n);
    PF_MALLOC(p->whg2, b->n);
    PF_MALLOC(p->cw, b->n);
    PF_MALLOC(p->mrow, b->n);
    PF_MALLOC(p->crow, b->n);
    PF_MALLOC(p->F, 9 * (size_t)b->n);
    PF_MALLOC(p->D, 6 * (size_t)b->n);
    PF_MALLOC(p->s_old, 6 * (size_t)b->n);
    PF_MALLOC(p->saved, (size_t)p->nstate * b->n + 1);
    p->cap = b->n;
  }
  if (b->fresh) { /* (the last step's record, read by fail_bonds, travels with the points) */
    for (pf_int i = b->first; i < b->first + b->n; i++)
      for (int k = 0; k < GX; k++) p->gx[GX * i + k] = 0.0;
    for (pf_int i = b->first; i < b->first + b->n; i++) {
      for (int k = 0; k < 6; k++) p->sigma[6 * i + k] = 0.0;
      p->work[i] = p->hgwork[i] = 0.0;
      for (int a = 0; a < 3; a++) p->hgforce[3 * i + a] = 0.0;
    }
    for (pf_int a = 0, e; p->nstate && a < b->n; a = e) { /* (runs of one part's points) */
      for (e = a + 1; e < b->n && (!b->part || b->part[b->first + e] == b->part[b->first + a]);) e++;
      pf_material_init(model_at(b, b->first + a), e - a, &p->state[(size_t)p->nstate * (b->first + a)]);
    }
  }
  p->gamma = wave_factor(&b->influence, b->horizon); /* (the largest horizon, once known) */
  double h = NAN, K = NAN, c = 0; /* the PMB micromodulus of each point's horizon and bulk modulus, for the
                                     hourglass force (each end its own, docs/theory/interfaces.md §3a) */
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    if (b->hz[i] != h || pf_pd_K(b, i) != K) h = b->hz[i], K = pf_pd_K(b, i), c = pf_pd_pmb_micromodulus(K, &b->influence, h);
    p->gx[GX * i + G_C] = c;
  }
  whole_families(b, pts);
  if (b->fresh) warn_flat_families(b, pts);
  if (b->part) row_bounds(b);
  if (b->fresh)
    for (pf_int i = b->first; i < b->first + b->n; i++) p->step[i] = reference_step(b, pts, i);
  PF_CALL(ghost_vectors(b, pts));
  PF_CALL(consistent_weights(b, pts));
  for (pf_int li = 0; li < b->n; li++) { /* (the shape tensors are formed at the first step) */
    const pf_int i = b->first + li;
    int z = p->lm && pf_pd_consistent_at(b, i);
    for (int64_t k = b->fam.offset[li]; k < b->fam.offset[li + 1] && p->lm && !z; k++) z = pf_pd_consistent_at(b, b->fam.neighbor[k]);
    p->kcount[li] = -1, p->nearz[li] = (uint8_t)z;
  }
  return pf_points_exchange(pts, p->gx, GX);
}

static void mat_mul(double A[3][3], double B[3][3], double C[3][3]) {
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) C[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j] + A[i][2] * B[2][j];
}

/* The shape tensor and the deformation and rate sums of point i over its intact bonds; fails
 * bonds beyond the critical stretch. At a point of the consistent form, also the corrections'
 * sums H = sum_k Y (x) h_ik and Hd = sum_k Ydot (x) h_ik over its whole row (pd/consistent.c).
 * Returns the number of intact bonds. Taken at the consistent form's points only (the others
 * take row_sums); kinematics uses the cached K (shape_of), the same sums. */
static int bond_sums(pf_pd_body *b, const pf_points *pts, pf_int i, double K[3][3], double A[3][3],
                     double B[3][3], double H[3][3], double Hd[3][3], double sums[2]) {
  const corr *p = b->mat;
  const pf_family *fam = &b->fam;
  const pf_int li = i - b->first;
  const int consistent = pf_pd_consistent_at(b, i), stretch = pf_pd_stretch_limited(b);
  double smin = INFINITY;
  int nb = 0;
  memset(K, 0, 9 * sizeof(double)), memset(A, 0, 9 * sizeof(double)), memset(B, 0, 9 * sizeof(double));
  memset(H, 0, 9 * sizeof(double)), memset(Hd, 0, 9 * sizeof(double));
  sums[0] = sums[1] = 0.0;
  for (int64_t k = fam->offset[li]; k < fam->offset[li + 1]; k++) {
    if (fam->broken[k]) continue;
    const pf_int j = fam->neighbor[k];
    double xi[3], Y[3], Yd[3], r02 = 0, r2 = 0;
    for (int a = 0; a < 3; a++) {
      xi[a] = pts->X[3 * j + a] - pts->X[3 * i + a];
      Y[a] = pts->y[3 * j + a] - pts->y[3 * i + a];
      Yd[a] = pts->v[3 * j + a] - pts->v[3 * i + a];
      r02 += xi[a] * xi[a], r2 += Y[a] * Y[a];
    }
    const double r0 = sqrt(r02);
    if (stretch && pf_pd_may_fail(b, i, j)) { /* (both ends test every row bond) */
      const double s = (sqrt(r2) - r0) / r0;
      if (s > fmin(b->s0[i], b->s0[j])) {
        fam->broken[k] = PF_BOND_FRESH, p->lost[li] = 1;
        continue;
      }
      smin = fmin(smin, s);
    }
    const double w = pf_pd_omega(&b->influence, r0) * pf_pd_bond_volume(fam, pts->vol, k, j);
    if (consistent) {
      double h[3];
      pf_pd_consistent_h(&p->lm[PF_CONSISTENT_NLM * i], &p->lm[PF_CONSISTENT_NLM * j], w,
                         pf_pd_energy_weight(b, i) * pts->vol[i], xi, h);
      for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) H[r][c] += Y[r] * h[c], Hd[r][c] += Yd[r] * h[c];
    }
    if (!pf_pd_in_family(b, i, r0)) continue;
    for (int r = 0; r < 3; r++)
      for (int s = 0; s < 3; s++) {
        K[r][s] += w * xi[r] * xi[s];
        A[r][s] += w * Y[r] * xi[s];
        B[r][s] += w * Yd[r] * xi[s];
      }
    sums[0] += w * r0, sums[1] += w / r0;
    nb++;
  }
  b->smin[li] = smin;
  return nb;
}

/* Does the bond between points of failure records fi and fj fail before this step's sums
 * (fail_bonds)? When either end was detached last step, or either end's damage exceeded D_c and
 * both are points of the standard force (pf_pd_may_fail). */
static inline int record_fails(uint8_t fi, uint8_t fj) {
  return ((fi | fj) & 1) || (((fi | fj) & 2) && (fi & fj & 4));
}

/* The deformation and rate sums A = sum_j w Y (x) xi, B = sum_j w Ydot (x) xi of a point outside
 * the consistent form over its intact own bonds, in one pass over its row that first fails the
 * bonds fail_bonds would (last step's records, fails) and those beyond the critical stretch, as
 * bond_sums does (the same terms in the same order; its K and the sums of the step's bound are
 * the cached ones, shape_of). Returns the number of intact own bonds. */
static inline __attribute__((always_inline)) int row_kernel(pf_pd_body *b, const pf_points *pts, pf_int i,
                                                             double A[3][3], double B[3][3], const int general) {
  corr *p = b->mat;
  const pf_family *fam = &b->fam;
  const pf_int li = i - b->first;
  const int stretch = general && pf_pd_stretch_limited(b), one_sided = general && b->one_sided;
  const pf_influence *infl = &b->influence;
  const int unit_w = !general || infl->kind == PF_INFLUENCE_CONSTANT;
  const double *restrict X = pts->X, *restrict y = pts->y, *restrict v = pts->v, *restrict vol = pts->vol;
  const pf_int *restrict nbr = fam->neighbor;
  const float *restrict vfrac = general ? fam->vfrac : NULL;
  const uint8_t *restrict fails = p->fails;
  uint8_t *restrict broken = fam->broken;
  const uint8_t fi = fails[i];
  const double xi0 = X[3 * i], xi1 = X[3 * i + 1], xi2 = X[3 * i + 2], hzi = b->hz[i];
  const v4d yi = {y[3 * i], y[3 * i + 1], y[3 * i + 2], 0}, vi = {v[3 * i], v[3 * i + 1], v[3 * i + 2], 0};
  /* the columns of A and B: A[r][s] += (w Y_r) xi_s lane r of column s */
  v4d a0 = {0, 0, 0, 0}, a1 = a0, a2 = a0, b0 = a0, b1 = a0, b2 = a0;
  double smin = INFINITY;
  int nb = 0, lost = 0;
  for (int64_t k = fam->offset[li]; k < fam->offset[li + 1]; k++) {
    if (broken[k]) continue;
    const pf_int j = nbr[k];
    if (record_fails(fi, fails[j])) {
      broken[k] = PF_BOND_FRESH, lost = 1;
      continue;
    }
    const double x0 = X[3 * j] - xi0, x1 = X[3 * j + 1] - xi1, x2 = X[3 * j + 2] - xi2;
    const v4d Y = (v4d){y[3 * j], y[3 * j + 1], y[3 * j + 2], 0} - yi;
    const double r0 = sqrt(x0 * x0 + x1 * x1 + x2 * x2);
    if (stretch && (fi & fails[j] & 4)) { /* (both ends test every row bond) */
      const double s = (sqrt(Y[0] * Y[0] + Y[1] * Y[1] + Y[2] * Y[2]) - r0) / r0;
      if (s > fmin(b->s0[i], b->s0[j])) {
        broken[k] = PF_BOND_FRESH, lost = 1;
        continue;
      }
      smin = fmin(smin, s);
    }
    if (one_sided && !(r0 <= hzi)) continue;
    const double w = (unit_w ? 1.0 : pf_pd_omega(infl, r0)) * (vfrac ? vol[j] * vfrac[k] : vol[j]);
    const v4d wY = w * Y, wD = w * ((v4d){v[3 * j], v[3 * j + 1], v[3 * j + 2], 0} - vi);
    a0 += wY * x0, a1 += wY * x1, a2 += wY * x2;
    b0 += wD * x0, b1 += wD * x1, b2 += wD * x2;
    nb++;
  }
  for (int r = 0; r < 3; r++) {
    A[r][0] = a0[r], A[r][1] = a1[r], A[r][2] = a2[r];
    B[r][0] = b0[r], B[r][1] = b1[r], B[r][2] = b2[r];
  }
  b->smin[li] = smin;
  p->lost[li] = (uint8_t)lost;
  return nb;
}

/* row_kernel in its general form, or with the critical stretch, the variable horizon, the
 * influence function and the partial volumes folded away when the body has none of them. */
static int row_sums(pf_pd_body *b, const pf_points *pts, pf_int i, double A[3][3], double B[3][3]) {
  if (pf_pd_stretch_limited(b) || b->one_sided || b->influence.kind != PF_INFLUENCE_CONSTANT || b->fam.vfrac)
    return row_kernel(b, pts, i, A, B, 1);
  return row_kernel(b, pts, i, A, B, 0);
}

/* fail_bonds' test alone over the row of owned point i (a point of the consistent form, whose
 * sums bond_sums takes, or an idle one). */
static void fail_row(pf_pd_body *b, pf_int i) {
  corr *p = b->mat;
  const pf_family *fam = &b->fam;
  const pf_int li = i - b->first;
  p->lost[li] = 0;
  for (int64_t k = fam->offset[li]; k < fam->offset[li + 1]; k++)
    if (!fam->broken[k] && record_fails(p->fails[i], p->fails[fam->neighbor[k]])) fam->broken[k] = PF_BOND_FRESH, p->lost[li] = 1;
}

/* Marks the PF_BOND_FRESH bonds of owned point i's row PF_BOND_BROKEN (an idle point: no force
 * state acted through them, nothing to book). */
static void settle_row(pf_pd_body *b, pf_int i) {
  pf_family *fam = &b->fam;
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++)
    if (fam->broken[k]) fam->broken[k] = PF_BOND_BROKEN;
  ((corr *)b->mat)->jump[i - b->first] = NAN;
}

/* Last step's record of every store point for the failure test (owned points and ghosts read the
 * same exchanged record, so both ends of a bond decide alike). */
static int failure_records(pf_pd_body *b, const pf_points *pts) {
  corr *p = b->mat;
  if (pts->n_total > p->fcap) {
    free(p->fails);
    p->fcap = pts->n_total + pts->n_total / 8 + 16;
    PF_MALLOC(p->fails, p->fcap);
  }
#pragma omp parallel for schedule(static)
  for (pf_int j = 0; j < pts->n_total; j++) {
    const double *g = &p->gx[GX * j];
    p->fails[j] = (uint8_t)((g[G_DETACHED] != 0) | (g[G_DAMAGE] > p->dcrit) << 1 | (b->region[j] == 0) << 2);
  }
  return 0;
}

/* A point whose intact bonds keep less than this fraction of its whole family's span in some
 * direction, min_n (n.K n)/(n.K0 n), is detached (docs/theory/materials.md §2, "the span test"):
 * 1 for an intact family, 1/2 on either side of a crack through the point, 0 when the bonds left
 * lie in a plane. Below it, Fbar = A K^-1 divides by a small second moment and turns any
 * non-affine motion of the few bonds left into wild stresses (the 740 m/s panel threw points out
 * at 38 km/s). */
static const double PF_CORR_MIN_SPAN = 0.1;

/* A point whose Fbar says its neighbourhood holds less than this fraction of its volume is
 * detached (docs/theory/materials.md §2.7, "crushed points"): no solid is compressed so far (a
 * metal at 100 GPa keeps about 0.7 of its volume), so such a Fbar is no estimate of a continuum
 * deformation but a family that has been pinched, or passed through. */
static const double PF_CORR_MIN_J = 0.5;

/* Do the intact bonds' K of owned point li keep the span (a point that lost no bond does)? */
static int spans(const corr *p, pf_int li, double K[3][3]) {
  double K0[3][3];
  memcpy(K0, &p->K0[9 * li], sizeof K0);
  return pf_sym3_min_relative_eigenvalue(K, K0) >= PF_CORR_MIN_SPAN;
}

/* Point i at rest for the model (F = I, D = 0, no force state): detached (then its bonds fail
 * next step) or idle (coupled, beta = 0 around it: its stress stays zero, no step limit). */
static void at_rest(pf_pd_body *b, pf_int i, int detached) {
  corr *p = b->mat;
  const pf_int li = i - b->first;
  double *g = &p->gx[GX * i];
  for (int k = 0; k < 9; k++) {
    p->F[9 * li + k] = g[G_F + k] = (k % 4 == 0);
    g[G_PK + k] = g[G_FDOT + k] = g[G_NU + k] = p->Ki[9 * li + k] = 0.0;
  }
  for (int k = 0; k < 6; k++) p->D[6 * li + k] = 0.0, p->s_old[6 * li + k] = p->sigma[6 * i + k];
  g[G_DETACHED] = detached;
  p->rate[li] = p->whg2[li] = 0.0, p->Jm[li] = 1.0;
}

/* Point i lost bonds this step, so its Fbar jumped to another estimate of a material that did not
 * move: the model keeps the elastic state it would have reached with Fbar carried over the step
 * by the velocity gradient L, F* = (I - dt/2 L)^-1 (I + dt/2 L) Fbar_n (the midpoint rule),
 * re-expressed for the new Fbar (docs/theory/materials.md §2.7). Not after a state at rest. */
static void rereference(pf_pd_body *b, pf_int i, double Fb[3][3], double L[3][3]) {
  corr *p = b->mat;
  const double *g = &p->gx[GX * i];
  double Fn[3][3], Am[3][3], Ap[3][3], Ai[3][3], T[3][3], Fs[3][3];
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) {
      Fn[r][c] = g[G_F + r + 3 * c];
      Am[r][c] = (r == c) - 0.5 * b->dt * L[r][c], Ap[r][c] = (r == c) + 0.5 * b->dt * L[r][c];
    }
  if (!p->nstate || g[G_DETACHED] || !(pf_mat3_det(Fn) > 0) || !(pf_mat3_inverse(Am, Ai) > 0)) return;
  mat_mul(Ai, Ap, T), mat_mul(T, Fn, Fs);
  pf_material_rereference(model_at(b, i), 1, &Fs[0][0], &Fb[0][0], &p->state[(size_t)p->nstate * i]);
}

/* K = sum_j w V_j xi (x) xi over the intact own bonds of owned point i (the order and terms of
 * bond_sums), with what a step needs of it, into the cache: K^-1, lambda_min(K), the sums of the
 * step's bound (step_rates) and whether K spans space (kinematics). */
static void shape_of(pf_pd_body *b, const pf_points *pts, pf_int i) {
  corr *p = b->mat;
  const pf_int li = i - b->first;
  double K[3][3] = {{0}}, Ki[3][3], sums[2] = {0, 0}, *c = &p->kshape[KS * li];
  int nb = 0;
  for (int64_t k = b->fam.offset[li]; k < b->fam.offset[li + 1]; k++) {
    double xi[3], r0, w;
    if (!pf_pd_own_bond(b, pts, i, k, xi, &r0, &w)) continue;
    for (int r = 0; r < 3; r++)
      for (int s = 0; s < 3; s++) K[r][s] += w * xi[r] * xi[s];
    sums[0] += w * r0, sums[1] += w / r0;
    nb++;
  }
  const double detK = pf_mat3_inverse(K, Ki);
  memcpy(&p->kinv[9 * li], Ki, sizeof Ki);
  c[KS_LMIN] = pf_sym3_min_eigenvalue(K), c[KS_LEN] = sums[0], c[KS_INV] = sums[1];
  c[KS_SPANS] = shape_spans(nb, detK, K) && (nb == p->nfam[li] || spans(p, li, K));
  c[KS_SPREAD] = detK > 0 ? spread_of(b, pts, i, Ki) : INFINITY;
  p->kcount[li] = nb;
}

/* Half the work of point i's last force state over this step, on the bonds it acted through:
 * (dt/2) P^n : Fdot_S, with Fdot_S = [sum_S w V_j Ydot (x) xi] K_S^-1 (+ sum_S Ydot (x) h_ik at a
 * point of the consistent form) over the set S the last evaluation used, this step's intact bonds
 * and its PF_BOND_FRESH ones (Tupek et al. 2013, eqs. 3-4; the first term of the step's account,
 * docs/theory/pd.md §5.1). Ydot = v^{n+1/2} differences, so dt Fdot_S is the change of that set's
 * Fbar over the step. Pn: P^n, row-major. Marks the fresh bonds PF_BOND_BROKEN. */
static double old_half_work(pf_pd_body *b, const pf_points *pts, pf_int i, const double Pn[9]) {
  const corr *p = b->mat;
  pf_family *fam = &b->fam;
  const pf_int li = i - b->first;
  const int consistent = pf_pd_consistent_at(b, i);
  double K[3][3] = {{0}}, B[3][3] = {{0}}, Hd[3][3] = {{0}}, Ki[3][3];
  for (int64_t k = fam->offset[li]; k < fam->offset[li + 1]; k++) {
    if (fam->broken[k] == PF_BOND_BROKEN) continue;
    if (fam->broken[k]) fam->broken[k] = PF_BOND_BROKEN;
    const pf_int j = fam->neighbor[k];
    double xi[3], Yd[3], r02 = 0;
    for (int a = 0; a < 3; a++) {
      xi[a] = pts->X[3 * j + a] - pts->X[3 * i + a], Yd[a] = pts->v[3 * j + a] - pts->v[3 * i + a];
      r02 += xi[a] * xi[a];
    }
    const double r0 = sqrt(r02), w = pf_pd_omega(&b->influence, r0) * pf_pd_bond_volume(fam, pts->vol, k, j);
    if (consistent) {
      double h[3];
      pf_pd_consistent_h(&p->lm[PF_CONSISTENT_NLM * i], &p->lm[PF_CONSISTENT_NLM * j], w,
                         pf_pd_energy_weight(b, i) * pts->vol[i], xi, h);
      for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) Hd[r][c] += Yd[r] * h[c];
    }
    if (!pf_pd_in_family(b, i, r0)) continue;
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) K[r][c] += w * xi[r] * xi[c], B[r][c] += w * Yd[r] * xi[c];
  }
  if (!(pf_mat3_inverse(K, Ki) > 0)) return 0.0; /* (then no force state acted: detached) */
  double pw = 0;
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++)
      pw += Pn[3 * r + c] * (B[r][0] * Ki[0][c] + B[r][1] * Ki[1][c] + B[r][2] * Ki[2][c] + Hd[r][c]);
  return 0.5 * b->dt * pw;
}

/* Kinematics of point i for the model: Fbar into F, D into D, the rotated previous stress; K^-1
 * kept in the ghost record until the stress is known. Returns 0 when the point is detached: too
 * few bonds for an invertible K, intact bonds that lost the span, or an inverted or crushed Fbar
 * (det Fbar < PF_CORR_MIN_J: a point with no continuum left around it). K is reference geometry:
 * it is formed again only when the point's count of intact own bonds changed (shape_of). */
static int kinematics(pf_pd_body *b, const pf_points *pts, pf_int i) {
  corr *p = b->mat;
  const pf_int li = i - b->first;
  double A[3][3], B[3][3], H[3][3] = {{0}}, Hd[3][3] = {{0}}, Ki[3][3], Fb[3][3], Fd[3][3], Fm[3][3], Fmi[3][3];
  double L[3][3], R[3][3], *g = &p->gx[GX * i], *F = &p->F[9 * li], *D = &p->D[6 * li], Pn[9];
  int nb;
  memcpy(Pn, &g[G_NU], sizeof Pn); /* the last evaluation's P, for failure_work */
  if (pf_pd_consistent_at(b, i)) {
    double K[3][3], sums[2];
    fail_row(b, i);
    nb = bond_sums(b, pts, i, K, A, B, H, Hd, sums);
  } else nb = row_sums(b, pts, i, A, B);
  p->jump[li] = p->lost[li] ? old_half_work(b, pts, i, Pn) : NAN;
  if (nb != p->kcount[li]) shape_of(b, pts, i);
  const double *c = &p->kshape[KS * li];
  memcpy(Ki, &p->kinv[9 * li], sizeof Ki);
  int ok = c[KS_SPANS] != 0;
  if (ok) {
    mat_mul(A, Ki, Fb), mat_mul(B, Ki, Fd);
    for (int r = 0; r < 3; r++)
      for (int s = 0; s < 3; s++) {
        Fb[r][s] += H[r][s], Fd[r][s] += Hd[r][s]; /* (zero but at the consistent form's points) */
        Fm[r][s] = Fb[r][s] - 0.5 * b->dt * Fd[r][s];
      }
    ok = pf_mat3_det(Fb) > PF_CORR_MIN_J && (p->Jm[li] = pf_mat3_inverse(Fm, Fmi)) > 0;
    if (ok) step_rates(b, i, c[KS_LMIN], Fb, &c[KS_LEN], c[KS_SPREAD], &p->rate[li], &p->whg2[li]);
  }
  if (!ok) { /* the model sees a state at rest; its result is discarded */
    if (!p->lost[li]) p->jump[li] = old_half_work(b, pts, i, Pn); /* (its force state goes) */
    at_rest(b, i, 1);
    return 0;
  }
  mat_mul(Fd, Fmi, L);
  if (p->lost[li] && p->keep_stress) rereference(b, i, Fb, L);
  g[G_DETACHED] = 0;
  for (int k = 0; k < 6; k++) D[k] = 0.5 * (L[pf_voigt_i[k]][pf_voigt_j[k]] + L[pf_voigt_j[k]][pf_voigt_i[k]]);
  pf_mat3_hughes_winget(L, b->dt, R);
  pf_sym6_rotate(R, &p->sigma[6 * i]);
  memcpy(&p->s_old[6 * li], &p->sigma[6 * i], 6 * sizeof(double));
  for (int r = 0; r < 3; r++)
    for (int s = 0; s < 3; s++) {
      F[3 * r + s] = g[G_F + r + 3 * s] = Fb[r][s]; /* (the record by columns) */
      g[G_PK + r + 3 * s] = p->Ki[9 * li + 3 * r + s] = Ki[r][s], g[G_FDOT + r + 3 * s] = Fd[r][s];
    }
  return 1;
}

/* After the model: stress work (trapezoid in time, per reference volume, det Fm sigma : D),
 * P K^-1 = J sigma Fbar^-T K^-1 into the ghost record, damage for w_D. */
static void stress_to_force_state(pf_pd_body *b, pf_int i) {
  corr *p = b->mat;
  const pf_int li = i - b->first;
  double *g = &p->gx[GX * i], S[3][3], Fb[3][3], Fi[3][3], Ki[3][3], P[3][3], T[3][3];
  const double *s = &p->sigma[6 * i], *so = &p->s_old[6 * li], *D = &p->D[6 * li];
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) Fb[r][c] = g[G_F + r + 3 * c], Ki[r][c] = g[G_PK + r + 3 * c];
  const double J = pf_mat3_inverse(Fb, Fi);
  double power = 0;
  for (int k = 0; k < 6; k++) power += (k < 3 ? 1.0 : 2.0) * 0.5 * (s[k] + so[k]) * D[k];
  p->work[i] += b->dt * p->Jm[li] * power;
  pf_sym6_to_mat(s, S);
  for (int r = 0; r < 3; r++) /* P = J sigma F^-T */
    for (int c = 0; c < 3; c++) P[r][c] = J * (S[r][0] * Fi[c][0] + S[r][1] * Fi[c][1] + S[r][2] * Fi[c][2]);
  mat_mul(P, Ki, T);
  if (!isnan(p->jump[li])) { /* failure_work: + (dt/2) P^n+1 : Fdot - the stress work just booked */
    double pf = 0;
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) pf += P[r][c] * g[G_FDOT + r + 3 * c];
    p->jump[li] += 0.5 * b->dt * pf - b->dt * p->Jm[li] * power;
  }
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) g[G_PK + r + 3 * c] = T[r][c], g[G_NU + 3 * r + c] = P[r][c];
}

/* Bonds to a point detached last step, or whose either end's damage exceeded D_c last step, fail
 * before the sums, so that Fbar and the force of this step use the same bonds (angular
 * momentum): failure_records, then each row's first pass (row_sums, fail_row). Both ends read the
 * same exchanged record, so both decide alike. */

/* The model over the body's points in batches, leaving out the idle ones (coupled, beta = 0 all
 * round: at rest for good, their stress stays zero; in a coupled panel most of the body). The
 * models are pointwise, so the threads take blocks of PF_CORR_BLOCK points, each block its runs
 * of points that are not idle: the same numbers however the points are batched. */
enum { PF_CORR_BLOCK = 64 };
static void update_block(pf_pd_body *b, int ns, pf_int lo, pf_int hi) {
  corr *p = b->mat;
  for (pf_int a = lo, e; a < hi; a = e) {
    if (b->idle && b->idle[a]) {
      p->cw[a] = 0.0, e = a + 1;
      continue;
    }
    for (e = a + 1; e < hi && !(b->idle && b->idle[e]) && (!b->part || b->part[b->first + e] == b->part[b->first + a]);) e++;
    double *state = ns ? &p->state[(size_t)ns * (b->first + a)] : NULL; /* (a run of one part's points) */
    pf_material_update(model_at(b, b->first + a), e - a, b->dt, &p->F[9 * a], &p->D[6 * a], &p->sigma[6 * (b->first + a)], state,
                           &p->cw[a]);
  }
}

static void update_model(pf_pd_body *b) {
  const int ns = ((corr *)b->mat)->nstate;
  const pf_int nblocks = (b->n + PF_CORR_BLOCK - 1) / PF_CORR_BLOCK;
#pragma omp parallel for schedule(dynamic, 4)
  for (pf_int blk = 0; blk < nblocks; blk++) {
    const pf_int lo = blk * PF_CORR_BLOCK, hi = b->n - lo < PF_CORR_BLOCK ? b->n : lo + PF_CORR_BLOCK;
    update_block(b, ns, lo, hi);
  }
}

/* What the step's failures leave out of the balance (docs/theory/pd.md §5.1): at each point whose
 * row lost bonds, or that detached, the work its force states did over the step, by the trapezoid
 * velocity Verlet applies, (dt/2) (P^n : Fdot_{S^n} + P^{n+1} : Fdot_{S^{n+1}}), less the stress
 * work the step booked, dt J_m sigma_m : D (zero for a point that detached: P^{n+1} = 0 and no
 * work). Times beta_i V_i (the stress work's weight in corr_energy), into b->damage_work in point
 * order: each point's term is its own data, the same on any partition. */
static void failure_work(pf_pd_body *b, const pf_points *pts) {
  const corr *p = b->mat;
  for (pf_int li = 0; li < b->n; li++) {
    const pf_int i = b->first + li;
    if (!isnan(p->jump[li])) b->damage_work += (b->blend ? b->blend[i] : 1.0) * pts->vol[i] * p->jump[li];
  }
}

/* Pass 1 for every owned point, the model batched over the body, then the ghost exchange. */
static int corr_pass1(pf_pd_body *b, pf_points *pts) {
  corr *p = b->mat;
  const int ns = p->nstate;
  pf_int ndetached = 0;
  PF_CALL(failure_records(b, pts));
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : ndetached)
  for (pf_int i = b->first; i < b->first + b->n; i++)
    if (b->idle && b->idle[i - b->first]) fail_row(b, i), settle_row(b, i), at_rest(b, i, 0);
    else ndetached += !kinematics(b, pts, i);
  double *state = ns ? &p->state[(size_t)ns * b->first] : NULL;
  if (ndetached && ns) memcpy(p->saved, state, sizeof(double) * ns * b->n);
  update_model(b);
#pragma omp parallel for schedule(static)
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    const pf_int li = i - b->first;
    double *g = &p->gx[GX * i];
    if (g[G_DETACHED]) { /* keep its stress and history as they were */
      memcpy(&p->sigma[6 * i], &p->s_old[6 * li], 6 * sizeof(double));
      if (ns) memcpy(&state[(size_t)ns * li], &p->saved[(size_t)ns * li], sizeof(double) * ns);
      p->step[i] = INFINITY; /* it carries no stress */
    } else {
      stress_to_force_state(b, i);
      const double wc = p->cw[li] * p->rate[li];
      p->step[i] = 2.0 / sqrt(wc * wc + p->whg2[li]);
    }
    g[G_DAMAGE] = p->idamage >= 0 ? state[(size_t)ns * li + p->idamage] : 0.0;
    for (int k = 0; k < ns; k++) p->out[k][i] = state[(size_t)ns * li + k];
  }
  failure_work(b, pts);
  return pf_points_exchange(pts, p->gx, GX);
}

/* The consistent form's part of the pair force on i (before the factor V_i): beta_i P_i h_ij -
 * (beta_j V_j / V_i) P_j h_ji, for the ends that are its points (docs/theory/coupling.md §2.6,
 * §3.4; beta = 1 but coupled in the energy form); om = omega(|xi|). */
static void consistent_pair(const pf_pd_body *b, const pf_points *pts, pf_int i, pf_int j, double om,
                            const double xi[3], double f[3]) {
  const corr *p = b->mat;
  const int zi = pf_pd_consistent_at(b, i), zj = pf_pd_consistent_at(b, j);
  if (!zi && !zj) return;
  const double *li = &p->lm[PF_CONSISTENT_NLM * i], *lj = &p->lm[PF_CONSISTENT_NLM * j];
  const double *Pi = &p->gx[GX * i + G_NU], *Pj = &p->gx[GX * j + G_NU], Vi = pts->vol[i], Vj = pts->vol[j];
  const double bi = pf_pd_energy_weight(b, i), bj = pf_pd_energy_weight(b, j);
  double h[3];
  if (zi) {
    pf_pd_consistent_h(li, lj, om * Vj, bi * Vi, xi, h);
    for (int a = 0; a < 3; a++) f[a] += bi * (Pi[3 * a] * h[0] + Pi[3 * a + 1] * h[1] + Pi[3 * a + 2] * h[2]);
  }
  if (zj) {
    const double xr[3] = {-xi[0], -xi[1], -xi[2]}, s = bj * Vj / Vi;
    pf_pd_consistent_h(lj, li, om * Vi, bj * Vj, xr, h);
    for (int a = 0; a < 3; a++) f[a] -= s * (Pj[3 * a] * h[0] + Pj[3 * a + 1] * h[1] + Pj[3 * a + 2] * h[2]);
  }
}

/* The pair-force sums of owned point i over its intact bonds (corr_force): f gets
 * sum_j w ([j in H_i] b_i P_i K_i^-1 + [i in H_j] b_j P_j K_j^-1) xi when `standard`, fh the
 * hourglass forces. One pass over the row with the point's own record in registers; the record's
 * matrices are stored by columns (G_PK, G_F, G_FDOT), so that M xi is three lane-wise
 * multiply-adds of a column by a component of xi, column 0 first: each component is the sum of
 * the formula in its order. (A column load reads one double past it, still in the record.) */
static inline __attribute__((always_inline)) void pair_row(const pf_pd_body *b, const pf_points *pts, pf_int i,
                                                            int standard, double f[3], double fh[3], const int general) {
  const corr *p = b->mat;
  const pf_family *fam = &b->fam;
  const int states = general && b->blend && b->blend_states, one_sided = general && b->one_sided;
  const int viscous = general && p->viscous;
  const int gdev = viscous ? G_FDOT : G_F; /* the predicted relative position or velocity */
  const double *restrict dev = viscous ? pts->v : pts->y, *restrict X = pts->X, *restrict y = pts->y;
  const double *restrict vol = pts->vol, *restrict gx = p->gx, *restrict hz = b->hz, *restrict blend = b->blend;
  const float *restrict vfrac = general ? fam->vfrac : NULL;
  const pf_int *restrict nbr = fam->neighbor;
  const uint8_t *restrict broken = fam->broken;
  const pf_influence *infl = &b->influence;
  const int consistent = general && p->lm && p->nearz[i - b->first];
  const int unit_w = !general || infl->kind == PF_INFLUENCE_CONSTANT;
  const double *gi = &gx[GX * i], bi = states ? blend[i] : 1.0, hg = p->hg, hzi = hz[i];
  const double ki = hg * gi[G_C] * (viscous ? hzi / cl_at(b, i) : 1.0);
  const double x0 = X[3 * i], x1 = X[3 * i + 1], x2 = X[3 * i + 2], y0 = y[3 * i], y1 = y[3 * i + 1], y2 = y[3 * i + 2];
  const double z0 = dev[3 * i], z1 = dev[3 * i + 1], z2 = dev[3 * i + 2];
  const int detached_i = gi[G_DETACHED] != 0;
  const v4d zero = {0, 0, 0, 0};
  const v4d Pi0 = v4d_load(gi + G_PK), Pi1 = v4d_load(gi + G_PK + 3), Pi2 = v4d_load(gi + G_PK + 6);
  const v4d Gi0 = v4d_load(gi + gdev), Gi1 = v4d_load(gi + gdev + 3), Gi2 = v4d_load(gi + gdev + 6);
  v4d fv = zero, hv = zero;
  for (int64_t k = fam->offset[i - b->first]; k < fam->offset[i - b->first + 1]; k++) {
    if (broken[k]) continue;
    const pf_int j = nbr[k];
    const double *restrict gj = &gx[GX * j];
    const double xi[3] = {X[3 * j] - x0, X[3 * j + 1] - x1, X[3 * j + 2] - x2};
    const double Y0 = y[3 * j] - y0, Y1 = y[3 * j + 1] - y1, Y2 = y[3 * j + 2] - y2;
    const v4d Yv = {Y0, Y1, Y2, 0};
    const v4d Z = viscous ? (v4d){dev[3 * j] - z0, dev[3 * j + 1] - z1, dev[3 * j + 2] - z2, 0} : Yv;
    const double r0 = sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]), r = sqrt(Y0 * Y0 + Y1 * Y1 + Y2 * Y2);
    const double bj = states ? blend[j] : 1.0;
    const double hi = bi * (!one_sided || r0 <= hzi), hj = bj * (!one_sided || r0 <= hz[j]);
    const double om = unit_w ? 1.0 : pf_pd_omega(infl, r0), w = om * (vfrac ? vol[j] * vfrac[k] : vol[j]);
    const double kj = hg * gj[G_C] * (viscous ? hz[j] / cl_at(b, j) : 1.0);
    v4d t = (hi * Pi0 + hj * v4d_load(gj + G_PK)) * xi[0] + zero;
    t = (hi * Pi1 + hj * v4d_load(gj + G_PK + 3)) * xi[1] + t;
    t = (hi * Pi2 + hj * v4d_load(gj + G_PK + 6)) * xi[2] + t;
    v4d pi = Gi0 * xi[0] + zero, pj = v4d_load(gj + gdev) * xi[0] + zero;
    pi = Gi1 * xi[1] + pi, pj = v4d_load(gj + gdev + 3) * xi[1] + pj;
    pi = Gi2 * xi[2] + pi, pj = v4d_load(gj + gdev + 6) * xi[2] + pj;
    if (standard) fv += w * t;
    const v4d d = hi * ki * (pi - Z) + hj * kj * (pj - Z);
    double gam = d[0] * Y0 + 0.0;
    gam = d[1] * Y1 + gam;
    gam = d[2] * Y2 + gam;
    if (consistent) {
      double fc[3] = {fv[0], fv[1], fv[2]};
      consistent_pair(b, pts, i, j, om, xi, fc);
      fv[0] = fc[0], fv[1] = fc[1], fv[2] = fc[2];
    }
    if (gam != 0 && r > 0 && !detached_i && gj[G_DETACHED] == 0) {
      const double s = -w * gam / (r0 * r * r);
      hv += s * Yv;
    }
  }
  for (int a = 0; a < 3; a++) f[a] = fv[a], fh[a] = hv[a];
}

/* Does point i need pair_row's general form (a variable horizon, blending weights in the force
 * states, the viscous hourglass control, an influence function other than 1, partial volumes or
 * the consistent form's corrections)? Else the common case, with those terms folded away. */
static int needs_general(const pf_pd_body *b, pf_int i) {
  const corr *p = b->mat;
  return b->one_sided || (b->blend && b->blend_states) || p->viscous || b->influence.kind != PF_INFLUENCE_CONSTANT ||
         b->fam.vfrac || (p->lm && p->nearz[i - b->first]);
}

static void pair_sums(const pf_pd_body *b, const pf_points *pts, pf_int i, int standard, double f[3], double fh[3]) {
  if (needs_general(b, i)) pair_row(b, pts, i, standard, f, fh, 1);
  else pair_row(b, pts, i, standard, f, fh, 0);
}

/* Pass 2: pair forces from both ends' force states and the hourglass control. A point detached
 * in this step's pass 1 has P K^-1 = 0 and no hourglass force (its Fbar is not defined); its
 * bonds fail at the start of the next step. With a variable horizon each end contributes only to
 * the bonds of its own family (T_i<xi> for j within delta_i, T_j<-xi> for i within delta_j):
 * f_i = V_i sum_j w V_j ([j in H_i] P_i K_i^-1 + [i in H_j] P_j K_j^-1) xi. A point of the
 * partial-stress form takes V_i div nu instead (pd/partial_stress.c); the hourglass pair
 * forces, zero under any affine motion, are the same in both forms. Coupled in the energy form
 * (pf_pd_body_set_blending), each end's force state carries its own blending weight,
 * beta_i P_i K_i^-1 and beta_j P_j K_j^-1, and so does each end's hourglass stiffness: the
 * forces of sum_i beta_i W_i V_i (docs/theory/coupling.md §3.4); so do the consistent form's
 * corrections (consistent_pair). */
static int corr_force(pf_pd_body *b, pf_points *pts) {
  corr *p = b->mat;
  PF_CALL(corr_pass1(b, pts));
#pragma omp parallel for schedule(dynamic, 64)
  for (pf_int i = b->first; i < b->first + b->n; i++) {
    const int states = b->blend && b->blend_states; /* coupled, energy form */
    if (b->blend && (states ? b->idle[i - b->first] : b->blend[i] == 0)) continue; /* no PD force wanted */
    const double *gi = &p->gx[GX * i];
    const int standard = !pf_pd_partial_stress_at(b, i);
    double f[3], fh[3];
    pair_sums(b, pts, i, standard, f, fh);
    if (pf_pd_corrected_at(b, i)) { /* less the ghost force of its own uniform stress */
      const double *d = &p->ghost[3 * i];
      for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) f[a] -= gi[G_NU + 3 * a + c] * d[c];
    }
    const double V = pts->vol[i];
    double *fo = &p->hgforce[3 * i], dw = 0;
    for (int a = 0; a < 3; a++) { /* work over the step: (f_n + f_n+1)/2 . dt v_n+1/2 */
      pts->f[3 * i + a] += V * (f[a] + fh[a]);
      dw += 0.5 * (fo[a] + V * fh[a]) * pts->v[3 * i + a];
      fo[a] = V * fh[a];
    }
    p->hgwork[i] -= b->dt * dw; /* the work done against the hourglass forces */
    if (!standard) pf_pd_partial_stress_force(b, pts, i, &p->gx[G_NU], GX, &p->Ki[9 * (i - b->first)]);
  }
  return 0;
}

/* Stress work (elastic energy plus plastic dissipation of the model) and hourglass work. */
static double corr_energy(const pf_pd_body *b, const pf_points *pts) {
  const corr *p = b->mat;
  double e = 0;
  for (pf_int i = b->first; i < b->first + b->n; i++) { /* (coupled to FE: its blended share) */
    const double w = b->blend ? b->blend[i] : 1.0; /* (energy form: the hourglass forces carry it) */
    e += b->blend_states ? w * pts->vol[i] * p->work[i] + p->hgwork[i] : w * (pts->vol[i] * p->work[i] + p->hgwork[i]);
  }
  return e;
}

/* The body's stable step now: the smallest of its points' (docs/theory/materials.md §2.6). */
static double corr_stable_dt(const pf_pd_body *b, const pf_points *pts) {
  (void)pts;
  const corr *p = b->mat;
  double dt = INFINITY;
  for (pf_int i = b->first; i < b->first + b->n; i++) dt = fmin(dt, p->step[i]);
  return dt;
}

/* The points' own stable steps (field stable_step, their last evaluation), by store index. */
static double *corr_point_steps(pf_pd_body *b) { return ((corr *)b->mat)->step; }

static void corr_destroy(pf_pd_body *b) {
  corr *p = b->mat;
  pf_material_destroy(&p->cm);
  for (int q = 1; q < PF_PD_MAX_PARTS; q++)
    if (p->cms[q]) pf_material_destroy(&p->cms[q]);
  free(p->F), free(p->D), free(p->s_old), free(p->saved), free(p->Jm), free(p->out);
  free(p->rate), free(p->whg2), free(p->cw), free(p->Ki), free(p->K0), free(p->nfam), free(p->lost);
  free(p->kcount), free(p->kinv), free(p->kshape), free(p->nearz), free(p->fails), free(p->jump);
  free(p->mrow), free(p->crow);
  PF_FREE(b->mat);
}

/* The body keys only correspondence reads (pf_pd_body_keys). */
static const char *const body_keys[] = {"hourglass", "critical_damage", "bond_loss", NULL};

const pf_pd_material_ops pf_pd_material_correspondence = {
    .name = "correspondence",
    .create = corr_create,
    .setup = corr_setup,
    .force = corr_force,
    .energy = corr_energy,
    .stable_dt = corr_stable_dt,
    .point_steps = corr_point_steps,
    .destroy = corr_destroy,
    .partial_stress = 1,
    .gradient_forms = 1,
    .uses_velocity = 1,
    .several_materials = 1,
    .read_part = corr_read_part,
    .body_keys = body_keys,
};

void pf_pd_correspondence_upgrade(pf_points *pts) {
  double *g = pf_points_field_get(pts, "correspondence");
  for (pf_int i = 0; g && i < pts->n_owned; i++)
    for (int m = G_PK; m <= G_FDOT; m += 9)
      for (int r = 0; r < 3; r++)
        for (int c = r + 1; c < 3; c++) {
          double *a = &g[GX * i + m + 3 * r + c], *b = &g[GX * i + m + 3 * c + r], t = *a;
          *a = *b, *b = t;
        }
}
