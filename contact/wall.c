/* A rigid, fixed, frictionless planar wall enforced kinematically on points (FE nodes or PD
 * particles), as the rigid walls of explicit codes (LS-DYNA *RIGIDWALL_PLANAR; Hallquist 2006,
 * LS-DYNA Theory Manual ch. 26): a point found behind the plane after the drift is put back on
 * it and loses its inward normal velocity (a perfectly plastic impact of that node; the kinetic
 * energy removed, m (v.n)^2 / 2, is booked as the wall's dissipation), and a point on the plane
 * does not take the inward normal part of its force (that part is the wall's reaction).
 * With `separation: false` the wall is bilateral (Abaqus *SURFACE BEHAVIOR, NO SEPARATION): a
 * point on the plane takes neither normal part of its force, so once it has hit the wall it slides
 * on it for good. That is the roller u.n = 0 with which the Taylor-bar benchmark's frictionless
 * wall is usually modelled (Abaqus Benchmarks Manual 1.3.10, "Impact of a copper rod": zero axial
 * displacement on the impact end); docs/theory/fem.md sec. 9. */
#include "contact/contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct pf_wall {
  char name[64];
  double p[3], n[3]; /* a point of the plane and the unit normal pointing to the free side */
  uint64_t bodies;   /* bit b: the wall acts on body b */
  int separation;    /* 0: a point on the plane stays on it (bilateral) */
};

const pf_key pf_wall_keys[] = {
    {"name", PF_KEY_STRING, 1, NULL, "", "wall name (history columns <name>_force_{x,y,z})", NULL},
    {"point", PF_KEY_VEC3, 1, NULL, "m", "a point of the plane", NULL},
    {"normal", PF_KEY_VEC3, 1, NULL, "", "normal pointing to the side where the bodies are", NULL},
    {"bodies", PF_KEY_STRLIST, 0, "all", "", "the bodies the wall stops", NULL},
    {"separation", PF_KEY_BOOL, 0, "true", "",
     "false: a point that reaches the plane stays on it and slides (no separation; the roller of the Taylor-bar benchmark)",
     NULL},
    PF_KEY_END};

int pf_wall_create(const pf_deck *d, const pf_node *map, int nbodies, const char *const *body_names, pf_wall **out) {
  *out = NULL;
  pf_wall *w;
  PF_MALLOC(w, 1);
  const char *name = "";
  int ierr = pf_deck_string(d, map, "name", &name);
  snprintf(w->name, sizeof w->name, "%s", name);
  if (!ierr) ierr = pf_deck_vec3(d, map, "point", w->p);
  if (!ierr) ierr = pf_deck_unit_vec3(d, map, "normal", w->n);
  w->separation = 1;
  if (!ierr) ierr = pf_deck_bool(d, map, "separation", &w->separation);
  const pf_node *list = pf_node_get(map, "bodies");
  w->bodies = list ? 0 : ~(uint64_t)0;
  for (int k = 0; k < pf_node_count(list) && !ierr; k++) {
    int b;
    ierr = pf_deck_body_index(d, pf_node_item(list, k), "bodies", nbodies, body_names, &b);
    if (!ierr) w->bodies |= (uint64_t)1 << b;
  }
  if (ierr) {
    free(w);
    return ierr;
  }
  *out = w;
  return 0;
}

int pf_wall_destroy(pf_wall **w) {
  PF_FREE(*w);
  return 0;
}

const char *pf_wall_name(const pf_wall *w) { return w->name; }

static double gap(const pf_wall *w, const double *y) {
  return (y[0] - w->p[0]) * w->n[0] + (y[1] - w->p[1]) * w->n[1] + (y[2] - w->p[2]) * w->n[2];
}

static int acts_on(const pf_wall *w, const pf_points *p, pf_int i) {
  return p->body[i] < 64 && ((w->bodies >> p->body[i]) & 1);
}

void pf_wall_enforce_position(const pf_wall *w, pf_points *p, double *loss, double impulse[3]) {
  for (pf_int i = 0; i < p->n_owned; i++) {
    double *y = &p->y[3 * (size_t)i], g = gap(w, y);
    if (g >= 0 || !acts_on(w, p, i)) continue;
    double *v = &p->v[3 * (size_t)i], vn = v[0] * w->n[0] + v[1] * w->n[1] + v[2] * w->n[2];
    for (int a = 0; a < 3; a++) {
      p->u[3 * (size_t)i + a] -= g * w->n[a];
      y[a] = p->X[3 * (size_t)i + a] + p->u[3 * (size_t)i + a];
    }
    if (vn >= 0) continue;
    *loss += 0.5 * p->m[i] * vn * vn;
    for (int a = 0; a < 3; a++) v[a] -= vn * w->n[a], impulse[a] -= p->m[i] * vn * w->n[a];
  }
}

void pf_wall_enforce_force_local(const pf_wall *w, pf_points *p, double reaction[3]) {
  reaction[0] = reaction[1] = reaction[2] = 0;
  for (pf_int i = 0; i < p->n_owned; i++) {
    const double *y = &p->y[3 * (size_t)i];
    if (!acts_on(w, p, i) || gap(w, y) > 1e-9 * p->cell[i]) continue;
    double *f = &p->f[3 * (size_t)i], fn = f[0] * w->n[0] + f[1] * w->n[1] + f[2] * w->n[2];
    if (fn >= 0 && w->separation) continue;
    for (int a = 0; a < 3; a++) {
      f[a] -= fn * w->n[a];
      reaction[a] += fn * w->n[a]; /* the force the points press on the wall with */
    }
  }
}

void pf_wall_enforce_force(const pf_wall *w, pf_points *p, double reaction[3]) {
  pf_wall_enforce_force_local(w, p, reaction);
  for (int a = 0; a < 3; a++) reaction[a] = pf_sum_all(reaction[a]);
}
