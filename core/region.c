/* Regions: point sets chosen by geometry (box, cylinder or tube, sphere) or by name (a node
 * set or side set of a body's mesh, core/point_sets.c), used for lattice generation (geometry
 * only), prescribed boundary conditions and probes. */
#include "core/core.h"

#include <math.h>
#include <string.h>

const pf_key pf_region_keys[] = {
    {"shape", PF_KEY_STRING, 1, NULL, "",
     "box | cylinder | sphere | all | node_set | side_set (a named set of a body's mesh or Exodus "
     "discretization; a side set selects the nodes of its faces)", NULL},
    {"set", PF_KEY_STRING, 0, NULL, "", "node_set or side_set: the set's name", NULL},
    {"lo", PF_KEY_VEC3, 0, NULL, "m", "box: lower corner", NULL},
    {"hi", PF_KEY_VEC3, 0, NULL, "m", "box: upper corner", NULL},
    {"center", PF_KEY_VEC3, 0, "[0, 0, 0]", "m", "cylinder: centre of the base; sphere: centre",
     NULL},
    {"axis", PF_KEY_STRING, 0, "z", "", "cylinder: axis x, y or z", NULL},
    {"radius", PF_KEY_REAL, 0, NULL, "m", "cylinder or sphere radius", NULL},
    {"inner_radius", PF_KEY_REAL, 0, "0", "m", "cylinder: inner radius (a tube when > 0)", NULL},
    {"height", PF_KEY_REAL, 0, NULL, "m", "cylinder: height along the axis", NULL},
    PF_KEY_END};

static int need(const pf_deck *d, const pf_node *map, const char *key, const char *shape) {
  if (pf_node_get(map, key)) return 0;
  return pf_deck_error(d, map, key, "shape '%s' needs key '%s'", shape, key);
}

static int positive(const pf_deck *d, const pf_node *map, const char *key, double v, int allow0) {
  if (v > 0 || (allow0 && v == 0)) return 0;
  return pf_deck_error(d, pf_node_get(map, key), key, "must be %s (got %g)",
                       allow0 ? "zero or positive" : "positive", v);
}

/* shape: node_set | side_set, set: NAME. */
static int set_from_deck(const pf_deck *d, const pf_node *map, const char *shape, const pf_point_sets *sets,
                         int body, pf_region *r) {
  if (!sets)
    return pf_deck_error(d, pf_node_get(map, "shape"), "shape",
                         "a %s selects points of a body that exists; it cannot make a body's points "
                         "(a geometry's shapes: box, cylinder, sphere, points_file, exodus)", shape);
  const char *name = NULL;
  PF_CALL(need(d, map, "set", shape));
  PF_CALL(pf_deck_string(d, map, "set", &name));
  r->kind = PF_REGION_SET;
  return pf_point_sets_find(sets, d, pf_node_get(map, "set"), "set", name, !strcmp(shape, "side_set"), body,
                            &r->set);
}

int pf_region_from_deck(const pf_deck *d, const pf_node *map, const pf_point_sets *sets, int body,
                        pf_region *r) {
  memset(r, 0, sizeof *r);
  r->axis = 2;
  const char *shape = "all", *axis = "z";
  PF_CALL(pf_deck_string(d, map, "shape", &shape));
  PF_CALL(pf_deck_vec3(d, map, "center", r->center));
  if (strcmp(shape, "node_set") && strcmp(shape, "side_set") && pf_node_get(map, "set"))
    return pf_deck_error(d, pf_node_get(map, "set"), "set", "'set' goes with shape node_set or side_set (got "
                         "shape '%s')", shape);
  if (!strcmp(shape, "node_set") || !strcmp(shape, "side_set")) {
    PF_CALL(set_from_deck(d, map, shape, sets, body, r));
  } else if (!strcmp(shape, "all")) {
    r->kind = PF_REGION_ALL;
  } else if (!strcmp(shape, "box")) {
    r->kind = PF_REGION_BOX;
    PF_CALL(need(d, map, "lo", shape));
    PF_CALL(need(d, map, "hi", shape));
    PF_CALL(pf_deck_vec3(d, map, "lo", r->lo));
    PF_CALL(pf_deck_vec3(d, map, "hi", r->hi));
    for (int c = 0; c < 3; c++)
      if (!(r->hi[c] >= r->lo[c]))
        return pf_deck_error(d, pf_node_get(map, "hi"), "hi", "hi[%d] = %g is below lo[%d] = %g",
                             c, r->hi[c], c, r->lo[c]);
  } else if (!strcmp(shape, "cylinder")) {
    r->kind = PF_REGION_CYLINDER;
    PF_CALL(need(d, map, "radius", shape));
    PF_CALL(need(d, map, "height", shape));
    PF_CALL(pf_deck_real(d, map, "radius", &r->radius));
    PF_CALL(pf_deck_real(d, map, "inner_radius", &r->inner_radius));
    PF_CALL(pf_deck_real(d, map, "height", &r->height));
    PF_CALL(positive(d, map, "radius", r->radius, 0));
    PF_CALL(positive(d, map, "height", r->height, 0));
    PF_CALL(positive(d, map, "inner_radius", r->inner_radius, 1));
    PF_CALL(pf_deck_string(d, map, "axis", &axis));
    if (strlen(axis) != 1 || axis[0] < 'x' || axis[0] > 'z')
      return pf_deck_error(d, pf_node_get(map, "axis"), "axis", "expected x, y or z (got '%s')",
                           axis);
    r->axis = axis[0] - 'x';
  } else if (!strcmp(shape, "sphere")) {
    r->kind = PF_REGION_SPHERE;
    PF_CALL(need(d, map, "radius", shape));
    PF_CALL(pf_deck_real(d, map, "radius", &r->radius));
    PF_CALL(positive(d, map, "radius", r->radius, 0));
  } else {
    return pf_deck_error(d, pf_node_get(map, "shape"), "shape",
                         "unknown shape '%s' (known: all, box, cylinder, sphere%s)", shape,
                         sets ? ", node_set, side_set" : "");
  }
  return 0;
}

/* Inside test, boundary inclusive. */
int pf_region_contains(const pf_region *r, const double x[3]) {
  switch (r->kind) {
  case PF_REGION_ALL: return 1;
  case PF_REGION_BOX:
    for (int c = 0; c < 3; c++)
      if (x[c] < r->lo[c] || x[c] > r->hi[c]) return 0;
    return 1;
  case PF_REGION_CYLINDER: {
    int a = r->axis, b = (a + 1) % 3, c = (a + 2) % 3;
    double h = x[a] - r->center[a];
    if (h < 0 || h > r->height) return 0;
    double db = x[b] - r->center[b], dc = x[c] - r->center[c];
    double r2 = db * db + dc * dc;
    return r2 <= r->radius * r->radius && r2 >= r->inner_radius * r->inner_radius;
  }
  case PF_REGION_SPHERE: {
    double s = 0;
    for (int c = 0; c < 3; c++) s += (x[c] - r->center[c]) * (x[c] - r->center[c]);
    return s <= r->radius * r->radius;
  }
  case PF_REGION_SET: return 0;
  }
  return 0;
}

int pf_region_selects(const pf_region *r, const pf_points *pts, pf_int i) {
  if (r->kind != PF_REGION_SET) return pf_region_contains(r, &pts->X[3 * i]);
  return pts->body[i] == r->set->body && pf_point_set_has(r->set, pts->gid[i]);
}
