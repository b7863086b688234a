/* Rigid analytic surfaces with prescribed motion: a sphere, a plane or a cylinder pushing the
 * points it contains (of the bodies it names) out along its outward normal n.
 *
 * Depth d of a point y (> 0 inside):
 *   sphere of centre c, radius R:        d = R - |y - c|,          n = (y - c) / |y - c|;
 *   plane through p, unit normal n_p towards the body: d = -(y - p) . n_p,   n = n_p;
 *   cylinder of axis (c, unit a), radius R, length L: with s = (y - c) . a and
 *     r = (y - c) - s a, d = R - |r|, n = r / |r|, for |s| <= L/2 (every s when L is not
 *     given). Only the curved side pushes: a point inside the solid cylinder goes radially out,
 *     the end caps exert no force (a point beyond |s| = L/2 is free).
 *
 * Normal force on point i of volume V_i:
 *   quadratic law (default): F = k d^2 V_i, energy k d^3 V_i / 3, k in N/m^5. This is LAMMPS
 *     fix indent as used with the PERI package, where per-atom forces are force densities, so
 *     the force density k d^2 times V_i: the indenter of the Silling & Askari 2005 / Parks et
 *     al. 2008 disk impact (k = 1e17 N/m^5); the foundation's contact/rigid.c, whose
 *     arithmetic is kept here operation for operation for the frictionless sphere and plane.
 *   linear law: F = k d, energy k d^2 / 2, k in N/m (a penalty spring per point; the stable
 *     step of a point of mass m on it is 2 / omega = 2 sqrt(m / k)).
 *
 * Coulomb friction, regularized as the stick limit of explicit codes: with the point's velocity
 * relative to the surface v_rel = v_i - v_s (v_s the surface velocity of the last advance, the
 * same mid-step instant as the points' v_i), its tangential part v_t = v_rel - (v_rel . n) n,
 *   F_t = -min(mu |F|, m_i |v_t| / dt) v_t / |v_t|,
 * i.e. the Coulomb force mu |F| while sliding, capped by the stick limit of explicit codes:
 * never more than the force m_i |v_t| / dt that stops the relative tangential velocity in one
 * step (so friction cannot reverse the sliding within a step). The work dissipated over the
 * step is -F_t . v_t dt = |F_t| |v_t| dt >= 0. Frictionless when mu = 0, dt = 0 or v_t = 0.
 *
 * Under the quasi-static solver (pf_rigid_force_static; docs/theory/quasi_static_methods.md §8) friction
 * is a tangential penalty with a stick/slip return mapping (Wriggers 2006, ch. 5; Simo & Laursen
 * 1992): each point keeps its slip s_i (a point field), committed at converged load steps only;
 * with D the surface's motion since the start, the elastic tangential displacement is
 * g_t = (I - n n^T)(u_i - D - s_i), the trial force -k_t g_t, and the force
 *   F_t = -k_t g_t  while k_t |g_t| <= mu F (stick),   F_t = -mu F g_t / |g_t|  else (slip).
 * At a load step's equilibrium the slip takes what the elastic part does not hold,
 * s_i = u_i - D + F_t / k_t (u_i - D for a point out of contact), and the slip increment's work
 * |F_t| |g_t + F_t / k_t| is dissipated. */
#include "contact/contact_impl.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef enum { RIGID_SPHERE, RIGID_PLANE, RIGID_CYLINDER } rigid_shape;
typedef enum { LAW_QUADRATIC, LAW_LINEAR } rigid_law;

static const char *const shape_names[] = {"sphere", "plane", "cylinder"};
static const char *const law_names[] = {"quadratic", "linear"};

struct pf_rigid {
  char name[64];
  rigid_shape shape;
  rigid_law law;
  double x[3];       /* sphere centre, a point of the plane, a point of the cylinder axis */
  double normal[3];  /* plane: unit normal pointing into the body */
  double axis[3];    /* cylinder: unit axis */
  double radius;     /* sphere, cylinder */
  double half_length; /* cylinder: L / 2 (INFINITY: infinite) */
  double stiffness;  /* N/m^5 (quadratic) or N/m (linear) */
  double friction;   /* Coulomb coefficient mu */
  double tangential; /* quasi-static: the tangential penalty k_t, N/m (NAN: not given) */
  double x0[3];      /* the initial position (quasi-static friction: D = x - x0) */
  double v[3];       /* velocity of the last advance (m/s; 0 before the first) */
  pf_expr *vel[3];
  uint64_t motion;   /* the deck's velocity node, hashed (pf_node_hash; 0: none) */
  int nbodies;
  unsigned char *acts; /* [nbodies] 1: the surface pushes that body; NULL: every body */
};

const pf_key pf_rigid_keys[] = {
    {"name", PF_KEY_STRING, 0, "indenter", "", "name used in the history", NULL},
    {"shape", PF_KEY_STRING, 1, NULL, "", "sphere | plane | cylinder", NULL},
    {"center", PF_KEY_VEC3, 0, NULL, "m", "sphere: initial centre; cylinder: initial point on the axis", NULL},
    {"radius", PF_KEY_REAL, 0, NULL, "m", "sphere, cylinder: radius", NULL},
    {"point", PF_KEY_VEC3, 0, NULL, "m", "plane: initial point on the plane", NULL},
    {"normal", PF_KEY_VEC3, 0, NULL, "", "plane: normal pointing towards the body", NULL},
    {"axis", PF_KEY_VEC3, 0, NULL, "", "cylinder: axis direction (normalized)", NULL},
    {"length", PF_KEY_REAL, 0, NULL, "m", "cylinder: length, centred on 'center' (infinite when absent)", NULL},
    {"velocity", PF_KEY_EXPR3, 0, "[0, 0, 0]", "m/s", "expressions in t", NULL},
    {"law", PF_KEY_STRING, 0, "quadratic", "", "quadratic (F = k d^2 V) | linear (F = k d)", NULL},
    {"stiffness", PF_KEY_REAL, 0, "1e17", "N/m^5 | N/m",
     "k: quadratic law N/m^5 (default 1e17); linear law N/m (required)", NULL},
    {"friction", PF_KEY_REAL, 0, "0", "", "Coulomb friction coefficient mu >= 0", NULL},
    {"tangential_stiffness", PF_KEY_REAL, 0, "stiffness", "N/m",
     "quasi_static with friction: k_t of the tangential penalty F_t = -k_t g_t of a point that sticks (the "
     "linear law's stiffness by default; required with the quadratic law)", NULL},
    {"bodies", PF_KEY_STRLIST, 0, "all", "", "the bodies the surface pushes", NULL},
    PF_KEY_END};

static int need(const pf_deck *d, const pf_node *map, const char *key, const char *what) {
  return pf_node_get(map, key) ? 0 : pf_deck_error(d, map, key, "%s needs '%s'", what, key);
}

/* The index of name in names[n], or -1; "a, b, c" into buf for the error message. */
static int lookup(const char *name, const char *const *names, int n, char *buf, size_t len) {
  buf[0] = '\0';
  for (int k = 0; k < n; k++) {
    if (!strcmp(name, names[k])) return k;
    size_t at = strlen(buf);
    snprintf(buf + at, len - at, "%s%s", k ? ", " : "", names[k]);
  }
  return -1;
}

static int read_shape(const pf_deck *d, const pf_node *map, pf_rigid *r) {
  const char *shape = "";
  char known[64];
  PF_CALL(pf_deck_string(d, map, "shape", &shape));
  int k = lookup(shape, shape_names, 3, known, sizeof known);
  if (k < 0)
    return pf_deck_error(d, pf_node_get(map, "shape"), "shape",
                         "unknown rigid surface shape '%s' (known: %s)", shape, known);
  r->shape = (rigid_shape)k;
  r->half_length = INFINITY;
  if (r->shape == RIGID_SPHERE) {
    PF_CALL(need(d, map, "center", "a sphere"));
    PF_CALL(need(d, map, "radius", "a sphere"));
    PF_CALL(pf_deck_vec3(d, map, "center", r->x));
    PF_CALL(pf_deck_positive(d, map, "radius", &r->radius));
  } else if (r->shape == RIGID_PLANE) {
    PF_CALL(need(d, map, "point", "a plane"));
    PF_CALL(need(d, map, "normal", "a plane"));
    PF_CALL(pf_deck_vec3(d, map, "point", r->x));
    PF_CALL(pf_deck_unit_vec3(d, map, "normal", r->normal));
  } else {
    PF_CALL(need(d, map, "center", "a cylinder"));
    PF_CALL(need(d, map, "axis", "a cylinder"));
    PF_CALL(need(d, map, "radius", "a cylinder"));
    PF_CALL(pf_deck_vec3(d, map, "center", r->x));
    PF_CALL(pf_deck_unit_vec3(d, map, "axis", r->axis));
    PF_CALL(pf_deck_positive(d, map, "radius", &r->radius));
    if (pf_node_get(map, "length")) {
      double len;
      PF_CALL(pf_deck_positive(d, map, "length", &len));
      r->half_length = 0.5 * len;
    }
  }
  return 0;
}

/* law, stiffness (required for the linear law: the quadratic default 1e17 N/m^5 is no spring
 * constant), friction. */
static int read_law(const pf_deck *d, const pf_node *map, pf_rigid *r) {
  const char *law = "quadratic";
  char known[64];
  PF_CALL(pf_deck_string(d, map, "law", &law));
  int k = lookup(law, law_names, 2, known, sizeof known);
  if (k < 0)
    return pf_deck_error(d, pf_node_get(map, "law"), "law", "unknown contact law '%s' (known: %s)",
                         law, known);
  r->law = (rigid_law)k;
  if (r->law == LAW_LINEAR && !pf_node_get(map, "stiffness"))
    return pf_deck_error(d, map, "stiffness",
                         "the linear law needs 'stiffness' (k in F = k d, N/m; the default "
                         "1e17 is the quadratic law's N/m^5)");
  r->stiffness = 1e17;
  if (pf_node_get(map, "stiffness")) PF_CALL(pf_deck_positive(d, map, "stiffness", &r->stiffness));
  r->friction = 0;
  PF_CALL(pf_deck_real(d, map, "friction", &r->friction));
  if (!(r->friction >= 0) || isinf(r->friction))
    return pf_deck_error(d, pf_node_get(map, "friction"), "friction",
                         "must be a finite coefficient >= 0 (got %g)", r->friction);
  r->tangential = r->law == LAW_LINEAR ? r->stiffness : NAN;
  if (pf_node_get(map, "tangential_stiffness"))
    PF_CALL(pf_deck_positive(d, map, "tangential_stiffness", &r->tangential));
  return 0;
}

/* `bodies`: a mask over the body indices; absent: every body. */
static int read_bodies(const pf_deck *d, const pf_node *map, int nbodies,
                       const char *const *body_names, pf_rigid *r) {
  const pf_node *list = pf_node_get(map, "bodies");
  if (!list) return 0;
  r->nbodies = nbodies;
  PF_MALLOC(r->acts, nbodies);
  for (int k = 0; k < pf_node_count(list); k++) {
    int b;
    PF_CALL(pf_deck_body_index(d, pf_node_item(list, k), "bodies", nbodies, body_names, &b));
    r->acts[b] = 1;
  }
  return 0;
}

static int rigid_setup(const pf_deck *d, const pf_node *map, int nbodies,
                       const char *const *body_names, pf_rigid *r) {
  const char *name = "indenter";
  PF_CALL(pf_deck_string(d, map, "name", &name));
  snprintf(r->name, sizeof r->name, "%s", name);
  PF_CALL(read_shape(d, map, r));
  memcpy(r->x0, r->x, sizeof r->x0);
  PF_CALL(read_law(d, map, r));
  PF_CALL(read_bodies(d, map, nbodies, body_names, r));
  if (pf_node_get(map, "velocity")) PF_CALL(pf_expr3_create(d, map, "velocity", r->vel));
  r->motion = pf_node_hash(pf_node_get(map, "velocity"));
  return 0;
}

int pf_rigid_create(const pf_deck *d, const pf_node *map, int nbodies,
                    const char *const *body_names, pf_rigid **out) {
  *out = NULL;
  pf_rigid *r;
  PF_MALLOC(r, 1);
  int ierr = rigid_setup(d, map, nbodies, body_names, r);
  if (ierr) {
    pf_rigid_destroy(&r);
    return ierr;
  }
  *out = r;
  return 0;
}

int pf_rigid_destroy(pf_rigid **r) {
  if (!*r) return 0;
  pf_expr3_destroy((*r)->vel);
  free((*r)->acts);
  PF_FREE(*r);
  return 0;
}

const char *pf_rigid_name(const pf_rigid *r) { return r->name; }
double pf_rigid_friction(const pf_rigid *r) { return r->friction; }
double pf_rigid_tangential_stiffness(const pf_rigid *r) { return r->tangential; }

static int common_body(const pf_rigid *a, const pf_rigid *b) {
  if (!a->acts || !b->acts) return 1;
  for (int k = 0; k < a->nbodies && k < b->nbodies; k++)
    if (a->acts[k] && b->acts[k]) return 1;
  return 0;
}

int pf_rigid_same_surface(const pf_rigid *a, const pf_rigid *b) {
  const double *ga[] = {a->x, a->normal, a->axis}, *gb[] = {b->x, b->normal, b->axis};
  for (int k = 0; k < 3; k++)
    if (memcmp(ga[k], gb[k], 3 * sizeof(double))) return 0;
  return a->shape == b->shape && a->radius == b->radius && a->half_length == b->half_length &&
         a->motion == b->motion && common_body(a, b);
}

void pf_rigid_position(const pf_rigid *r, double x[3]) { memcpy(x, r->x, 3 * sizeof(double)); }

void pf_rigid_set_position(pf_rigid *r, const double x[3]) { memcpy(r->x, x, 3 * sizeof(double)); }

static int acts_on(const pf_rigid *r, const pf_points *p, pf_int i) {
  if (!r->acts) return 1;
  int32_t b = p->body[i];
  return b >= 0 && b < r->nbodies && r->acts[b];
}

/* The depth of point y inside the surface and the outward normal dir there (the file's head
 * gives the formulas); returns 0 when the point is not inside (or on the centre / axis, where
 * the normal is undefined). */
static int penetration(const pf_rigid *r, const double *y, double *depth, double dir[3]) {
  double d[3];
  for (int a = 0; a < 3; a++) d[a] = y[a] - r->x[a];
  if (r->shape == RIGID_SPHERE) {
    double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    *depth = r->radius - dist;
    if (*depth <= 0 || dist == 0) return 0;
    for (int a = 0; a < 3; a++) dir[a] = d[a] / dist;
  } else if (r->shape == RIGID_PLANE) {
    *depth = -(d[0] * r->normal[0] + d[1] * r->normal[1] + d[2] * r->normal[2]);
    if (*depth <= 0) return 0;
    memcpy(dir, r->normal, 3 * sizeof(double));
  } else {
    double s = d[0] * r->axis[0] + d[1] * r->axis[1] + d[2] * r->axis[2];
    if (fabs(s) > r->half_length) return 0;
    double rad[3];
    for (int a = 0; a < 3; a++) rad[a] = d[a] - s * r->axis[a];
    double dist = sqrt(rad[0] * rad[0] + rad[1] * rad[1] + rad[2] * rad[2]);
    *depth = r->radius - dist;
    if (*depth <= 0 || dist == 0) return 0;
    for (int a = 0; a < 3; a++) dir[a] = rad[a] / dist;
  }
  return 1;
}

int pf_rigid_force_local(pf_rigid *r, pf_points *pts, double dt, double sums[4], double *dissipation) {
  double R[3] = {0, 0, 0}, U = 0, W = 0, k = r->stiffness;
  int slide = r->friction > 0 && dt > 0;
  for (pf_int i = 0; i < pts->n_owned; i++) {
    double depth, dir[3];
    if (!acts_on(r, pts, i) || !penetration(r, &pts->y[3 * (size_t)i], &depth, dir)) continue;
    double F;
    if (r->law == LAW_QUADRATIC) { /* F = k d^2 V, U = k d^3 V / 3 (as contact/rigid.c) */
      F = k * depth * depth * pts->vol[i];
      U += k * depth * depth * depth * pts->vol[i] / 3.0;
    } else { /* F = k d, U = k d^2 / 2 */
      F = k * depth;
      U += 0.5 * k * depth * depth;
    }
    for (int a = 0; a < 3; a++) {
      pts->f[3 * (size_t)i + a] += F * dir[a];
      R[a] -= F * dir[a];
    }
    if (!slide) continue;
    double ft[3], vrel[3];
    for (int a = 0; a < 3; a++) vrel[a] = pts->v[3 * (size_t)i + a] - r->v[a];
    W += pf_contact_friction(r->friction, F, dir, vrel, pts->m[i], dt, ft);
    for (int a = 0; a < 3; a++) {
      pts->f[3 * (size_t)i + a] += ft[a];
      R[a] -= ft[a];
    }
  }
  for (int a = 0; a < 3; a++) sums[a] = R[a];
  sums[3] = U;
  *dissipation += W;
  return 0;
}

int pf_rigid_force_static(const pf_rigid *r, pf_points *pts, double *slip, double *terms, double sums[4]) {
  double R[3] = {0, 0, 0}, U = 0, D[3], k = r->stiffness, kt = r->tangential;
  for (int a = 0; a < 3; a++) D[a] = r->x[a] - r->x0[a];
  for (pf_int i = 0; i < pts->n_owned; i++) {
    double depth, dir[3], *s = &slip[3 * (size_t)i];
    const double *u = &pts->u[3 * (size_t)i];
    if (terms) terms[i] = 0;
    if (!acts_on(r, pts, i)) continue;
    if (!penetration(r, &pts->y[3 * (size_t)i], &depth, dir)) {
      if (terms)
        for (int a = 0; a < 3; a++) s[a] = u[a] - D[a]; /* out of contact: no elastic part */
      continue;
    }
    double F;
    if (r->law == LAW_QUADRATIC) {
      F = k * depth * depth * pts->vol[i];
      U += k * depth * depth * depth * pts->vol[i] / 3.0;
    } else {
      F = k * depth;
      U += 0.5 * k * depth * depth;
    }
    double g[3], gn = 0, gt = 0, ft[3];
    for (int a = 0; a < 3; a++) g[a] = u[a] - D[a] - s[a], gn += g[a] * dir[a];
    for (int a = 0; a < 3; a++) g[a] -= gn * dir[a], gt += g[a] * g[a];
    gt = sqrt(gt);
    const double lim = r->friction * F, scale = kt * gt <= lim ? kt : lim / gt; /* stick | slip */
    for (int a = 0; a < 3; a++) ft[a] = gt > 0 ? -scale * g[a] : 0.0;
    const double T = scale * gt; /* |F_t| */
    U += 0.5 * T * T / kt;
    if (terms) { /* commit: the slip takes what the elastic part -F_t / k_t does not hold */
      terms[i] = T * fmax(gt - T / kt, 0.0); /* (0 while it sticks, to round-off) */
      for (int a = 0; a < 3; a++) s[a] = u[a] - D[a] + ft[a] / kt;
      continue;
    }
    for (int a = 0; a < 3; a++) {
      pts->f[3 * (size_t)i + a] += F * dir[a] + ft[a];
      R[a] -= F * dir[a] + ft[a];
    }
  }
  for (int a = 0; a < 3; a++) sums[a] = R[a];
  sums[3] = U;
  return 0;
}

int pf_rigid_force(pf_rigid *r, pf_points *pts, double dt, double reaction[3], double *energy,
                   double *dissipation) {
  double sums[4];
  PF_CALL(pf_rigid_force_local(r, pts, dt, sums, dissipation));
  for (int a = 0; a < 3; a++) reaction[a] = pf_sum_all(sums[a]);
  *energy = pf_sum_all(sums[3]);
  return 0;
}

int pf_rigid_check_finite(const pf_rigid *r, double t_end, int nt) {
  for (int a = 0; a < 3; a++)
    if (r->vel[a]) PF_CALL(pf_expr_check_finite(r->vel[a], NULL, 0, t_end, nt)); /* (evaluated at the origin) */
  return 0;
}

void pf_rigid_advance(pf_rigid *r, double t, double dt, double dx[3]) {
  for (int a = 0; a < 3; a++) {
    r->v[a] = r->vel[a] ? pf_expr_eval(r->vel[a], 0, 0, 0, t + 0.5 * dt) : 0.0;
    dx[a] = dt * r->v[a];
    r->x[a] += dx[a];
  }
}

void pf_rigid_stiffness_bounds(const pf_rigid *r, const pf_points *pts, double *k) {
  for (pf_int i = 0; i < pts->n_owned; i++) {
    double depth = -INFINITY, dir[3];
    (void)penetration(r, &pts->y[3 * (size_t)i], &depth, dir);
    if (!acts_on(r, pts, i) || !(depth > -pts->cell[i])) continue;
    const double db = fmax(depth, 0) + pts->cell[i];
    const double kn = r->law == LAW_QUADRATIC ? 2 * r->stiffness * db * pts->vol[i] : r->stiffness;
    const double F = r->law == LAW_QUADRATIC ? r->stiffness * db * db * pts->vol[i] : r->stiffness * db;
    double kt = r->shape == RIGID_PLANE ? 0 : F / fmax(r->radius - db, 0.5 * r->radius);
    if (r->friction > 0) kt += r->tangential; /* the tangential penalty k_t (I - n n^T) */
    k[i] += sqrt(3.0) * kn + (1 + sqrt(3.0)) * kt;
  }
}

double pf_rigid_stable_dt(const pf_rigid *r, const pf_points *pts) {
  if (r->law == LAW_QUADRATIC) return INFINITY;
  double m = INFINITY;
  for (pf_int i = 0; i < pts->n_owned; i++)
    if (acts_on(r, pts, i) && pts->m[i] > 0 && pts->m[i] < m) m = pts->m[i];
  m = pf_min_all(m);
  return isinf(m) ? INFINITY : 2.0 * sqrt(m / r->stiffness);
}
