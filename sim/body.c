/* The body interface's optional ops with their defaults (sim/body.h): the only place that
 * tests a body's op for NULL. */
#include "sim/body.h"

#include <math.h>

int pf_body_always(const void *data) {
  (void)data;
  return 1;
}

/* ---- the optional ops with their defaults (sim/body.h), the only place that tests them ---- */
int pf_body_find_rows(const pf_body *b, const pf_point_cloud *pc, const pf_points *pts, const pf_body_span *s,
                      pf_bond_rows *rows) {
  return b->ops->find_rows ? b->ops->find_rows(b->data, pc, pts, s, rows) : b->ops->rows(b->data, pts, s, rows);
}
int pf_body_bond_fields(const pf_body *b, pf_bond_rows *rows) {
  return b->ops->bond_fields ? b->ops->bond_fields(b->data, rows) : 0;
}
int pf_body_step_varies(const pf_body *b) { return b->ops->step_varies && b->ops->step_varies(b->data); }
int pf_body_uses_velocity(const pf_body *b) { return b->ops->uses_velocity && b->ops->uses_velocity(b->data); }
int pf_body_post_step(const pf_body *b, pf_points *pts) { return b->ops->post_step ? b->ops->post_step(b->data, pts) : 0; }
int pf_body_freeze_damage(const pf_body *b, const pf_points *pts, int frozen) {
  return b->ops->freeze_damage ? b->ops->freeze_damage(b->data, pts, frozen) : 0;
}
double pf_body_failure_ratio(const pf_body *b, const pf_points *pts) {
  return b->ops->failure_ratio ? b->ops->failure_ratio(b->data, pts) : 0.0;
}
int pf_body_fails_without_ratio(const pf_body *b) { return b->ops->freeze_damage && !b->ops->failure_ratio; }
int64_t pf_body_softened(const pf_body *b) { return b->ops->softened ? b->ops->softened(b->data) : -1; }
int pf_body_keeps_history(const pf_body *b, pf_points *pts) {
  return b->ops->history && b->ops->history(b->data, pts, PF_HISTORY_KEPT) == 1;
}
int pf_body_history(const pf_body *b, pf_points *pts, pf_history_op op) {
  return pf_body_keeps_history(b, pts) ? b->ops->history(b->data, pts, op) : 0;
}
int pf_body_failures(const pf_body *b, int restore) {
  return b->ops->failures ? b->ops->failures(b->data, restore) : 0;
}
int64_t pf_body_broken_bonds(const pf_body *b) {
  const pf_family *fam = pf_body_family(b);
  int64_t n = 0;
  for (int64_t k = 0; fam && k < fam->offset[fam->n]; k++) n += fam->broken[k] != 0;
  return n;
}
void pf_body_take_damage_work(const pf_body *b, double w[2]) {
  if (b->ops->take_damage_work) b->ops->take_damage_work(b->data, w);
}
const pf_family *pf_body_family(const pf_body *b) { return b->ops->family ? b->ops->family(b->data) : NULL; }
double pf_body_bytes_per_bond(const pf_body *b) { return b->ops->bytes_per_bond ? b->ops->bytes_per_bond(b->data) : 0; }
double pf_body_bond_rate(const pf_body *b) { return b->ops->bond_rate ? b->ops->bond_rate(b->data) : 1.5e8; }
void pf_body_record_breaks(const pf_body *b, const pf_points *pts) {
  if (b->ops->record_breaks) b->ops->record_breaks(b->data, pts);
}
double pf_body_horizon(const pf_body *b) { return b->ops->horizon ? b->ops->horizon(b->data) : 0; }
double pf_body_point_horizon(const pf_body *b, pf_int i) {
  return b->ops->point_horizon ? b->ops->point_horizon(b->data, i) : pf_body_horizon(b);
}
double pf_body_reach(const pf_body *b, const pf_points *pts, pf_int i) {
  return b->ops->reach ? b->ops->reach(b->data, pts, i) : pts->cell[i];
}
const char *pf_body_reach_name(const pf_body *b) { return b->ops->reach ? b->ops->reach_name : "cell"; }
const pf_mesh *pf_body_mesh(const pf_body *b) { return b->ops->mesh ? b->ops->mesh(b->data) : NULL; }
const pf_mesh *pf_body_contact_surface(const pf_body *b) {
  return b->ops->contact_surface ? b->ops->contact_surface(b->data) : NULL;
}
long pf_body_eroded_count(const pf_body *b) {
  long n = 0;
  return b->ops->eroded && b->ops->eroded(b->data, &n) ? n : -1;
}
int pf_body_output_fields(const pf_body *b, pf_points *pts) {
  return b->ops->output_fields ? b->ops->output_fields(b->data, pts) : 0;
}
int pf_body_table_shape(const pf_body *b, pf_gid *total, int *ncomp, pf_int *nlocal) {
  if (!b->ops->table_shape) return 0;
  b->ops->table_shape(b->data, total, ncomp, nlocal);
  return 1;
}
void pf_body_table_set(const pf_body *b, const double *full) {
  if (b->ops->table_set) b->ops->table_set(b->data, full);
}
int pf_body_carries_stable_dt(const pf_body *b) { return b->ops->set_stable_dt != NULL; }
double pf_body_stable_dt_all(const pf_body *b, const pf_points *pts) {
  return pf_min_all(b->ops->stable_dt(b->data, pts));
}
void pf_body_set_stable_dt(const pf_body *b, double dt) {
  if (b->ops->set_stable_dt) b->ops->set_stable_dt(b->data, dt);
}
pf_pd_body *pf_body_as_pd(const pf_body *b) { return b->ops->as_pd ? b->ops->as_pd(b->data) : NULL; }
struct pf_fem_body *pf_body_as_fem(const pf_body *b) { return b->ops->as_fem ? b->ops->as_fem(b->data) : NULL; }
struct pf_fem_particles *pf_body_as_particles(const pf_body *b) {
  return b->ops->as_particles ? b->ops->as_particles(b->data) : NULL;
}

/* The default: an explicit operator is stable for dt < 2 / omega_max, so a body whose stable step
 * is dt_b has omega_max^2 = K_i / m_i <= 4 / dt_b^2 at each point: K_i ~ 4 m_i / dt_b^2. */
int pf_body_stiffness_bounds(const pf_body *b, pf_points *pts, pf_int first, pf_int n, double *k) {
  if (b->ops->stiffness_bounds) return b->ops->stiffness_bounds(b->data, pts, first, n, k);
  const double dt = pf_body_stable_dt_all(b, pts);
  for (pf_int i = 0; i < n; i++) k[i] = isfinite(dt) && dt > 0 ? 4 * pts->m[first + i] / (dt * dt) : 0;
  return 0;
}
