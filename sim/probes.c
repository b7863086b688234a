/* Probes (`output: probes:`): mass-averaged quantities over the points of a region, as history
 * columns probe_<name>_<quantity>, e.g. the radial velocity and displacement of the outer
 * surface of the expanding tube over +-0.4 mm rings (Vogler et al. 2003; Littlewood's model,
 * Littlewood 2014):
 *   q_probe = sum_i m_i q_i / sum_i m_i   over the owned points of the body (or of every body)
 *             whose reference position lies in the region (chosen again at every row, so the
 *             points may move between ranks; a region without points is a deck error).
 * Radial quantities are about the axis of a cylinder region (through its base centre):
 *   radial_displacement_i = |y_perp - c_perp| - |X_perp - c_perp|   (change of the radius)
 *   radial_velocity_i     = v_perp . (y_perp - c_perp) / |y_perp - c_perp|   (0 on the axis). */
#include "sim/sim_impl.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const pf_key pf_sim_probe_keys[] = {
    {"name", PF_KEY_STRING, 1, NULL, "", "the probe's name: history columns probe_<name>_<quantity>", NULL},
    {"body", PF_KEY_STRING, 0, "every body", "", "the body whose points are averaged", NULL},
    {"region", PF_KEY_MAP, 1, NULL, "", "where (reference positions); a cylinder for the radial quantities",
     pf_region_keys},
    {"quantities", PF_KEY_STRLIST, 1, NULL, "",
     "any of displacement_x|y|z (m), velocity_x|y|z (m/s), radial_displacement (m), radial_velocity (m/s)",
     NULL},
    PF_KEY_END};

enum { Q_RADIAL_DISPLACEMENT = 6, Q_RADIAL_VELOCITY = 7, NQUANT = 8 };
static const char *const quantity_names[NQUANT] = {"displacement_x", "displacement_y", "displacement_z",
                                                   "velocity_x",     "velocity_y",     "velocity_z",
                                                   "radial_displacement", "radial_velocity"};

static int read_quantities(const pf_deck *d, const pf_node *map, pf_probe *p) {
  const pf_node *list = pf_node_get(map, "quantities");
  if (pf_node_count(list) < 1 || pf_node_count(list) > PF_PROBE_MAX_QUANTITIES)
    return pf_deck_error(d, list, "quantities", "give 1 to %d quantities", PF_PROBE_MAX_QUANTITIES);
  for (int k = 0; k < pf_node_count(list); k++) {
    const pf_node *item = pf_node_item(list, k);
    const char *name = pf_node_text(item);
    int q = 0;
    while (q < NQUANT && strcmp(quantity_names[q], name)) q++;
    if (q == NQUANT)
      return pf_deck_error(d, item, "quantities",
                           "unknown quantity '%s' (known: displacement_x|y|z, velocity_x|y|z, "
                           "radial_displacement, radial_velocity)", name);
    if (q >= Q_RADIAL_DISPLACEMENT && p->region.kind != PF_REGION_CYLINDER)
      return pf_deck_error(d, item, "quantities", "'%s' is about a cylinder's axis: the region must be a cylinder",
                           name);
    p->q[p->nq++] = q;
  }
  return 0;
}

static int selected(const pf_points *pts, pf_int i, const pf_probe *p) {
  return (p->body < 0 || pts->body[i] == p->body) && pf_region_selects(&p->region, pts, i);
}

int pf_sim_setup_probes(pf_sim *sim) {
  const pf_deck *d = sim->deck;
  const pf_node *list = pf_node_get(pf_node_get(pf_deck_root(d), "output"), "probes");
  sim->nprobes = pf_node_count(list);
  if (sim->nprobes == 0) return 0;
  PF_MALLOC(sim->probes, sim->nprobes);
  memset(sim->probes, 0, sizeof *sim->probes * (size_t)sim->nprobes);
  for (int k = 0; k < sim->nprobes; k++) {
    const pf_node *map = pf_node_item(list, k);
    pf_probe *p = &sim->probes[k];
    const char *name = NULL;
    PF_CALL(pf_deck_string(d, map, "name", &name));
    snprintf(p->name, sizeof p->name, "%s", name);
    for (int j = 0; j < k; j++)
      if (!strcmp(sim->probes[j].name, p->name))
        return pf_deck_error(d, pf_node_get(map, "name"), "name", "a second probe named '%s'", p->name);
    p->body = -1;
    if (pf_node_get(map, "body"))
      PF_CALL(pf_deck_body_index(d, pf_node_get(map, "body"), "body", sim->nbodies, sim->body_name, &p->body));
    PF_CALL(pf_region_from_deck(d, pf_node_get(map, "region"), &sim->sets, p->body, &p->region));
    PF_CALL(read_quantities(d, map, p));
    double n = 0;
    for (pf_int i = 0; i < sim->pts->n_owned; i++) n += selected(sim->pts, i, p);
    if (pf_sum_all(n) == 0)
      return pf_deck_error(d, pf_node_get(map, "region"), "region", "the probe's region holds no point of %s",
                           p->body >= 0 ? sim->body_name[p->body] : "any body");
  }
  return 0;
}

int pf_sim_probe_columns(const pf_sim *sim) {
  int n = 0;
  for (int k = 0; k < sim->nprobes; k++) n += sim->probes[k].nq;
  return n;
}

void pf_sim_probe_column(const pf_sim *sim, int column, char *name, size_t len, const char **units) {
  for (int k = 0; k < sim->nprobes; k++) {
    const pf_probe *p = &sim->probes[k];
    if (column >= p->nq) {
      column -= p->nq;
      continue;
    }
    int q = p->q[column];
    snprintf(name, len, "probe_%s_%s", p->name, quantity_names[q]);
    *units = (q >= 3 && q != Q_RADIAL_DISPLACEMENT) ? "m/s" : "m";
    return;
  }
}

/* Point i's value of quantity q (radial ones about the probe's cylinder axis). */
static double point_value(const pf_points *pts, pf_int i, const pf_region *r, int q) {
  if (q < 3) return pts->y[3 * i + q] - pts->X[3 * i + q];
  if (q < 6) return pts->v[3 * i + q - 3];
  double R0 = 0, R = 0, vr = 0;
  for (int a = 0; a < 3; a++) {
    if (a == r->axis) continue;
    const double dy = pts->y[3 * i + a] - r->center[a], dX = pts->X[3 * i + a] - r->center[a];
    R += dy * dy, R0 += dX * dX, vr += pts->v[3 * i + a] * dy;
  }
  R = sqrt(R), R0 = sqrt(R0);
  if (q == Q_RADIAL_DISPLACEMENT) return R - R0;
  return R > 0 ? vr / R : 0.0;
}

int pf_sim_probes_eval(const pf_sim *sim, double *values) {
  const int ncol = pf_sim_probe_columns(sim);
  if (ncol == 0) return 0;
  const pf_points *pts = sim->pts;
  double *sums; /* per column: sum m q; then per probe: sum m */
  PF_MALLOC(sums, (size_t)ncol + sim->nprobes);
  memset(sums, 0, sizeof *sums * ((size_t)ncol + sim->nprobes));
  for (int k = 0, col = 0; k < sim->nprobes; col += sim->probes[k].nq, k++) {
    const pf_probe *p = &sim->probes[k];
    for (pf_int i = 0; i < pts->n_owned; i++) {
      if (!selected(pts, i, p)) continue;
      sums[ncol + k] += pts->m[i];
      for (int c = 0; c < p->nq; c++) sums[col + c] += pts->m[i] * point_value(pts, i, &p->region, p->q[c]);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, sums, ncol + sim->nprobes, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  for (int k = 0, col = 0; k < sim->nprobes; col += sim->probes[k].nq, k++) {
    const double m = sums[ncol + k]; /* (> 0: checked at set-up, and points do not vanish) */
    for (int c = 0; c < sim->probes[k].nq; c++) values[col + c] = m > 0 ? sums[col + c] / m : 0.0;
  }
  PF_FREE(sums);
  return 0;
}
