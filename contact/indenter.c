/* Rigid indenters with prescribed motion: a sphere of radius R pushes each point it contains
 * with the force density f = k (R - r)^2 along the outward normal, i.e. the force
 * F_i = k (R - r)^2 V_i (LAMMPS fix indent as used with the PERI package, where per-atom
 * forces are force densities: the force law of the Silling & Askari 2005 / Parks et al. 2008
 * disk impact, k = 1e17 N/m^5); a plane with unit normal n (towards the body) pushes each point
 * behind it with F_i = k g^2 V_i n, g the depth. Penalty energy: k depth^3 V_i / 3. */
#include "contact/contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef enum { IND_SPHERE, IND_PLANE } ind_kind;

struct pf_indenter {
  char name[64];
  ind_kind kind;
  double x[3];      /* sphere centre or a point of the plane */
  double normal[3]; /* plane: unit normal pointing into the body */
  double radius, stiffness;
  pf_expr *vel[3];
};

const pf_key pf_indenter_keys[] = {
    {"name", PF_KEY_STRING, 0, "indenter", "", "name used in the history", NULL},
    {"shape", PF_KEY_STRING, 1, NULL, "", "sphere | plane", NULL},
    {"center", PF_KEY_VEC3, 0, NULL, "m", "sphere: initial centre", NULL},
    {"radius", PF_KEY_REAL, 0, NULL, "m", "sphere: radius", NULL},
    {"point", PF_KEY_VEC3, 0, NULL, "m", "plane: initial point on the plane", NULL},
    {"normal", PF_KEY_VEC3, 0, NULL, "", "plane: normal pointing towards the body", NULL},
    {"velocity", PF_KEY_EXPR3, 0, "[0, 0, 0]", "m/s", "expressions in t", NULL},
    {"stiffness", PF_KEY_REAL, 0, "1e17", "N/m^5", "k in the force density k depth^2 (force k depth^2 V)", NULL},
    PF_KEY_END};

static int need(const pf_deck *d, const pf_node *map, const char *key) {
  return pf_node_get(map, key) ? 0 : pf_deck_error(d, map, key, "this indenter needs '%s'", key);
}

static int read_shape(const pf_deck *d, const pf_node *map, pf_indenter *ind) {
  const char *shape = "";
  PF_CALL(pf_deck_string(d, map, "shape", &shape));
  if (!strcmp(shape, "sphere")) {
    ind->kind = IND_SPHERE;
    PF_CALL(need(d, map, "center"));
    PF_CALL(need(d, map, "radius"));
    PF_CALL(pf_deck_vec3(d, map, "center", ind->x));
    PF_CALL(pf_deck_real(d, map, "radius", &ind->radius));
    if (!(ind->radius > 0)) return pf_deck_error(d, pf_node_get(map, "radius"), "radius", "must be positive");
  } else if (!strcmp(shape, "plane")) {
    ind->kind = IND_PLANE;
    PF_CALL(need(d, map, "point"));
    PF_CALL(need(d, map, "normal"));
    PF_CALL(pf_deck_vec3(d, map, "point", ind->x));
    PF_CALL(pf_deck_vec3(d, map, "normal", ind->normal));
    double len = sqrt(ind->normal[0] * ind->normal[0] + ind->normal[1] * ind->normal[1] +
                      ind->normal[2] * ind->normal[2]);
    if (!(len > 0)) return pf_deck_error(d, pf_node_get(map, "normal"), "normal", "must not be zero");
    for (int a = 0; a < 3; a++) ind->normal[a] /= len;
  } else {
    return pf_deck_error(d, pf_node_get(map, "shape"), "shape",
                         "unknown indenter shape '%s' (known: sphere, plane)", shape);
  }
  return 0;
}

static int indenter_setup(const pf_deck *d, const pf_node *map, pf_indenter *ind) {
  const char *name = "indenter";
  PF_CALL(pf_deck_string(d, map, "name", &name));
  snprintf(ind->name, sizeof ind->name, "%s", name);
  PF_CALL(read_shape(d, map, ind));
  ind->stiffness = 1e17;
  PF_CALL(pf_deck_real(d, map, "stiffness", &ind->stiffness));
  if (!(ind->stiffness > 0))
    return pf_deck_error(d, pf_node_get(map, "stiffness"), "stiffness", "must be positive");
  if (pf_node_get(map, "velocity")) PF_CALL(pf_expr3_create(d, map, "velocity", ind->vel));
  return 0;
}

int pf_indenter_create(const pf_deck *d, const pf_node *map, pf_indenter **out) {
  *out = NULL;
  pf_indenter *ind;
  PF_MALLOC(ind, 1);
  int ierr = indenter_setup(d, map, ind);
  if (ierr) {
    pf_indenter_destroy(&ind);
    return ierr;
  }
  *out = ind;
  return 0;
}

int pf_indenter_destroy(pf_indenter **ind) {
  if (!*ind) return 0;
  pf_expr3_destroy((*ind)->vel);
  PF_FREE(*ind);
  return 0;
}

const char *pf_indenter_name(const pf_indenter *ind) { return ind->name; }

void pf_indenter_position(const pf_indenter *ind, double x[3]) { memcpy(x, ind->x, 3 * sizeof(double)); }

void pf_indenter_set_position(pf_indenter *ind, const double x[3]) { memcpy(ind->x, x, 3 * sizeof(double)); }

int pf_indenter_force(pf_indenter *ind, pf_points *pts, double reaction[3], double *energy) {
  double R[3] = {0, 0, 0}, U = 0, k = ind->stiffness;
  for (pf_int i = 0; i < pts->n_owned; i++) {
    const double *y = &pts->y[3 * i];
    double d[3], depth, dir[3];
    for (int a = 0; a < 3; a++) d[a] = y[a] - ind->x[a];
    if (ind->kind == IND_SPHERE) {
      double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      depth = ind->radius - r;
      if (depth <= 0 || r == 0) continue;
      for (int a = 0; a < 3; a++) dir[a] = d[a] / r;
    } else {
      depth = -(d[0] * ind->normal[0] + d[1] * ind->normal[1] + d[2] * ind->normal[2]);
      if (depth <= 0) continue;
      memcpy(dir, ind->normal, sizeof dir);
    }
    double F = k * depth * depth * pts->vol[i];
    for (int a = 0; a < 3; a++) {
      pts->f[3 * i + a] += F * dir[a];
      R[a] -= F * dir[a];
    }
    U += k * depth * depth * depth * pts->vol[i] / 3.0;
  }
  for (int a = 0; a < 3; a++) reaction[a] = pf_sum_all(R[a]);
  *energy = pf_sum_all(U);
  return 0;
}

void pf_indenter_advance(pf_indenter *ind, double t, double dt, const double reaction[3],
                         double *work) {
  double v[3] = {0, 0, 0};
  for (int a = 0; a < 3; a++) {
    if (ind->vel[a]) v[a] = pf_expr_eval(ind->vel[a], 0, 0, 0, t + 0.5 * dt);
    ind->x[a] += dt * v[a];
    *work -= reaction[a] * v[a] * dt;
  }
}
