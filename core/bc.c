/* Prescribed velocities and displacements, and applied body forces, on point sets chosen by
 * region (a shape, or a named node set or side set) and body. In the
 * velocity-Verlet step the mid-step velocity is what moves the points, so a prescribed
 * velocity v(t) sets it to v(t + dt/2) and a prescribed displacement g(t) sets it to
 * (g(t + dt) - g(t)) / dt, which lands the point exactly on g(t + dt). A body force b(x, t)
 * (force per unit mass) is no constraint: it adds m b to each selected point's force with the
 * internal forces, so the two half kicks of a step carry it. */
#include "core/core.h"

#include <stdlib.h>
#include <string.h>

enum { BC_VELOCITY, BC_DISPLACEMENT, BC_BODY_FORCE };

struct pf_bc {
  int kind;         /* BC_VELOCITY, BC_DISPLACEMENT or BC_BODY_FORCE */
  pf_expr *e[3]; /* NULL: component free */
  pf_region region;
  int body;      /* -1: every body */
  pf_int n;
  pf_int *points; /* owned points selected */
  char name[64];  /* the deck's `name:`, or "bc<k>" by its place in the list (k from 0) */
  /* this rank's impulse of the reaction on its points, N s: over the last hook called (summed
   * from 0, so that what is booked does not depend on what came before: a restarted run books
   * the same bits), and over the step being taken (from the mid-step hook, which starts it, to
   * the end-of-step hook) */
  double hook_impulse[3], step_impulse[3];
};

const pf_key pf_bc_keys[] = {
    {"name", PF_KEY_STRING, 0, NULL, "", "names its history columns <name>_reaction_x ... (default bc<k>)", NULL},
    {"region", PF_KEY_MAP, 0, "shape: all", "", "where: a region", pf_region_keys},
    {"body", PF_KEY_STRING, 0, NULL, "", "only the points of this body", NULL},
    {"velocity", PF_KEY_EXPR3, 0, NULL, "m/s", "expressions in x, y, z, t, or free", NULL},
    {"displacement", PF_KEY_EXPR3, 0, NULL, "m", "expressions in x, y, z, t, or free", NULL},
    {"body_force", PF_KEY_EXPR3, 0, NULL, "N/kg",
     "force per unit mass b in x, y, z, t added to the points' force (f += m b; a load, not a constraint; "
     "free = 0): a traction sigma on a layer of points of depth h is b = sigma / (rho h)",
     NULL},
    PF_KEY_END};

static int read_exprs(const pf_deck *d, const pf_node *map, const char *key, pf_bc *bc) {
  const pf_node *v = pf_node_get(map, key);
  for (int c = 0; c < 3; c++) {
    const pf_node *it = pf_node_item(v, c);
    if (!strcmp(pf_node_text(it), "free")) continue;
    PF_CALL(pf_expr_create(pf_node_text(it), d, it, key, &bc->e[c]));
  }
  return 0;
}

int pf_bc_check_finite(const pf_bc *bc, const pf_points *pts, double t_end, int nt) {
  double *X;
  PF_MALLOC(X, 3 * (size_t)bc->n + 3);
  for (pf_int k = 0; k < bc->n; k++)
    for (int c = 0; c < 3; c++) X[3 * k + c] = pts->X[3 * bc->points[k] + c];
  int ierr = 0;
  for (int c = 0; c < 3 && !ierr; c++) /* (every rank reaches the same verdict: the check reduces) */
    if (bc->e[c]) ierr = pf_expr_check_finite(bc->e[c], X, bc->n, t_end, nt);
  free(X);
  return ierr;
}

int pf_bc_select(pf_bc *bc, const pf_points *pts) {
  PF_FREE(bc->points);
  bc->n = 0;
  PF_MALLOC(bc->points, pts->n_owned);
  for (pf_int i = 0; i < pts->n_owned; i++)
    if ((bc->body < 0 || pts->body[i] == bc->body) && pf_region_selects(&bc->region, pts, i))
      bc->points[bc->n++] = i;
  return 0;
}

static int select_points(const pf_deck *d, const pf_node *map, const pf_points *pts, int nbodies,
                         const char *const *body_names, const pf_point_sets *sets, pf_bc *bc) {
  bc->region.kind = PF_REGION_ALL;
  bc->body = -1;
  if (pf_node_get(map, "body"))
    PF_CALL(pf_deck_body_index(d, pf_node_get(map, "body"), "body", nbodies, body_names, &bc->body));
  if (pf_node_get(map, "region"))
    PF_CALL(pf_region_from_deck(d, pf_node_get(map, "region"), sets, bc->body, &bc->region));
  PF_CALL(pf_bc_select(bc, pts));
  if (pf_sum_all(bc->n) == 0)
    return pf_deck_error(d, map, "region", "the boundary condition selects no point");
  return 0;
}

static int bc_setup(const pf_deck *d, const pf_node *map, const pf_points *pts, int nbodies,
                    const char *const *body_names, const pf_point_sets *sets, pf_bc *bc) {
  const char *name = NULL;
  PF_CALL(pf_deck_string(d, map, "name", &name));
  if (name) {
    if (!name[0] || strlen(name) >= sizeof bc->name)
      return pf_deck_error(d, pf_node_get(map, "name"), "name", "1 to %d characters (got '%s')",
                           (int)sizeof bc->name - 1, name);
    snprintf(bc->name, sizeof bc->name, "%s", name);
  }
  static const char *const kinds[] = {"velocity", "displacement", "body_force"};
  int given = 0;
  for (int k = 0; k < 3; k++)
    if (pf_node_get(map, kinds[k])) given++, bc->kind = k;
  if (given != 1)
    return pf_deck_error(d, map, "velocity", "give exactly one of 'velocity', 'displacement' and 'body_force'");
  PF_CALL(read_exprs(d, map, kinds[bc->kind], bc));
  return select_points(d, map, pts, nbodies, body_names, sets, bc);
}

int pf_bc_create(const pf_deck *d, const pf_node *map, const pf_points *pts, int nbodies,
                 const char *const *body_names, const pf_point_sets *sets, int index, pf_bc **out) {
  *out = NULL;
  pf_bc *bc;
  PF_MALLOC(bc, 1);
  snprintf(bc->name, sizeof bc->name, "bc%d", index);
  int ierr = bc_setup(d, map, pts, nbodies, body_names, sets, bc);
  if (ierr) {
    pf_bc_destroy(&bc);
    return ierr;
  }
  *out = bc;
  return 0;
}

int pf_bc_destroy(pf_bc **bc) {
  if (!*bc) return 0;
  pf_expr3_destroy((*bc)->e);
  free((*bc)->points);
  PF_FREE(*bc);
  return 0;
}

pf_int pf_bc_npoints(const pf_bc *bc) { return bc->n; }

const char *pf_bc_name(const pf_bc *bc) { return bc->name; }

void pf_bc_impulse(const pf_bc *bc, double step[3], double hook[3]) {
  for (int c = 0; c < 3; c++) step[c] = bc->step_impulse[c], hook[c] = bc->hook_impulse[c];
}

/* Setting a velocity component from v- (after the half kick of dt/2 by the force f) to v+ is
 * the impulse J = m (v+ - v-) of the condition's reaction over that half step (added to the
 * condition's impulses), during which the
 * velocity went from v0 = v- - f dt / (2m) to v+; its work, booked in work[body of the point], is taken by the
 * trapezoidal rule, J (v0 + v+) / 2. This is the reaction's power integrated consistently with
 * the centred kinetic energy: a point held at a constant velocity against a force f does work
 * -f v dt per step exactly (an impulse's m (v+^2 - v-^2) / 2 would add a spurious
 * -m (f dt / 2m)^2 each time). */
static void set_velocity(pf_bc *bc, pf_points *pts, pf_int i, int c, double vnew, double half_dt, double *work) {
  double vkick = pts->v[3 * i + c], v0 = vkick - half_dt * pts->f[3 * i + c] / pts->m[i];
  const double J = pts->m[i] * (vnew - vkick);
  work[pts->body[i]] += J * 0.5 * (v0 + vnew);
  bc->hook_impulse[c] += J, bc->step_impulse[c] += J;
  pts->v[3 * i + c] = vnew;
}

/* A prescribed displacement keeps the mid-step velocity at the step's end (pf_bc_apply_endstep),
 * so the velocity its point starts the step with, v0, is v(t - dt/2), not v(t) as for a
 * prescribed velocity. The trapezoidal work J (v0 + v+)/2 of the mid-step impulse then differs
 * from the work the point's own force takes over the step, -(f(t) + f(t + dt))/2 . dt v+, with the
 * change of its kinetic energy m (v+^2 - v0^2)/2, by dt f(t) (v+ - v0)/4 per step: first order in
 * the step when the displacement accelerates (v+ - v0 = a dt), as the grips of a ramped opening
 * do. The midstep hook books that term with the impulse, so the balance closes to second order
 * for both kinds (tests/regression/ledger_order.sh). */
void pf_bc_apply_midstep(pf_bc *bc, pf_points *pts, double t, double dt, double *work) {
  for (int c = 0; c < 3; c++) bc->hook_impulse[c] = 0.0;
  if (bc->kind == BC_BODY_FORCE) return;
  for (int c = 0; c < 3; c++) bc->step_impulse[c] = 0.0; /* a new step */
  for (pf_int k = 0; k < bc->n; k++) {
    pf_int i = bc->points[k];
    const double *x = &pts->X[3 * i];
    for (int c = 0; c < 3; c++) {
      if (!bc->e[c]) continue;
      double v = bc->kind == BC_VELOCITY ? pf_expr_eval(bc->e[c], x[0], x[1], x[2], t + 0.5 * dt)
                                 : (pf_expr_eval(bc->e[c], x[0], x[1], x[2], t + dt) - pts->u[3 * i + c]) / dt;
      const double f = pts->f[3 * i + c], v0 = pts->v[3 * i + c] - 0.5 * dt * f / pts->m[i];
      set_velocity(bc, pts, i, c, v, 0.5 * dt, work);
      if (bc->kind == BC_DISPLACEMENT) work[pts->body[i]] -= 0.25 * dt * f * (v - v0); /* (see above) */
    }
  }
}

void pf_bc_apply_endstep(pf_bc *bc, pf_points *pts, double t, double dt, double *work) {
  for (int c = 0; c < 3; c++) bc->hook_impulse[c] = 0.0;
  if (bc->kind == BC_BODY_FORCE) return;
  for (pf_int k = 0; k < bc->n; k++) {
    pf_int i = bc->points[k];
    const double *x = &pts->X[3 * i];
    for (int c = 0; c < 3; c++) {
      if (!bc->e[c]) continue;
      /* a prescribed displacement keeps its mid-step velocity (the half kick is the reaction's) */
      double v = bc->kind == BC_VELOCITY ? pf_expr_eval(bc->e[c], x[0], x[1], x[2], t)
                                 : pts->v[3 * i + c] - 0.5 * dt * pts->f[3 * i + c] / pts->m[i];
      set_velocity(bc, pts, i, c, v, 0.5 * dt, work);
    }
  }
}

void pf_bc_mark(const pf_bc *bc, uint8_t *mask) {
  if (bc->kind == BC_BODY_FORCE) return; /* a load: the point's acceleration stays its own */
  for (pf_int k = 0; k < bc->n; k++)
    for (int c = 0; c < 3; c++)
      if (bc->e[c]) mask[3 * (size_t)bc->points[k] + c] = 1;
}

/* A body force F = m b(x, t) on each selected owned point, added to f at time t (dt: the step
 * just taken, 0 for the initial forces). Velocity Verlet gives the step's two half kicks
 * F(t - dt) and F(t), so the load's impulse over the step is (F(t - dt) + F(t)) dt / 2, and its
 * work the trapezoidal (F(t - dt) + F(t)) . (u(t) - u(t - dt)) / 2 with u(t) - u(t - dt) = dt
 * v(t - dt/2), the mid-step velocity the points still hold when the forces are computed: for a
 * constant load the work summed over the steps is exactly F . u(t), the load's potential. */
void pf_bc_apply_force(pf_bc *bc, pf_points *pts, double t, double dt, double *work) {
  for (int c = 0; c < 3; c++) bc->hook_impulse[c] = 0.0;
  if (bc->kind != BC_BODY_FORCE) return;
  for (int c = 0; c < 3; c++) bc->step_impulse[c] = 0.0;
  for (pf_int k = 0; k < bc->n; k++) {
    pf_int i = bc->points[k];
    const double *x = &pts->X[3 * i];
    for (int c = 0; c < 3; c++) {
      if (!bc->e[c]) continue;
      const double F = pts->m[i] * pf_expr_eval(bc->e[c], x[0], x[1], x[2], t);
      pts->f[3 * i + c] += F;
      if (dt <= 0) continue;
      const double Fmean = 0.5 * (pts->m[i] * pf_expr_eval(bc->e[c], x[0], x[1], x[2], t - dt) + F);
      work[pts->body[i]] += Fmean * dt * pts->v[3 * i + c];
      bc->hook_impulse[c] += Fmean * dt, bc->step_impulse[c] += Fmean * dt;
    }
  }
}

void pf_bc_apply_static(const pf_bc *bc, pf_points *pts, double t, double dt) {
  if (bc->kind == BC_BODY_FORCE) return;
  for (pf_int k = 0; k < bc->n; k++) {
    const pf_int i = bc->points[k];
    const double *x = &pts->X[3 * i];
    for (int c = 0; c < 3; c++) {
      if (!bc->e[c]) continue;
      if (bc->kind == BC_DISPLACEMENT) pts->u[3 * i + c] = pf_expr_eval(bc->e[c], x[0], x[1], x[2], t);
      else pts->u[3 * i + c] += dt * pf_expr_eval(bc->e[c], x[0], x[1], x[2], t - 0.5 * dt);
      pts->y[3 * i + c] = x[c] + pts->u[3 * i + c];
    }
  }
}

void pf_bc_displacement_sum(const pf_bc *bc, const pf_points *pts, double sum[3]) {
  for (int c = 0; c < 3; c++) sum[c] = 0;
  for (pf_int k = 0; k < bc->n; k++)
    for (int c = 0; c < 3; c++) sum[c] += pts->u[3 * bc->points[k] + c];
}

/* The force the condition exerts on component c of owned point i at pseudo-time t: the reaction
 * -f of a prescribed component (in equilibrium it holds the point against the forces of the
 * bodies, as the explicit step's impulse over dt does), a body force's load m b(X, t), 0 on a
 * component it leaves free. */
static double static_force(const pf_bc *bc, const pf_points *pts, pf_int i, int c, double t) {
  if (!bc->e[c]) return 0;
  const double *x = &pts->X[3 * i];
  return bc->kind == BC_BODY_FORCE ? pts->m[i] * pf_expr_eval(bc->e[c], x[0], x[1], x[2], t) : -pts->f[3 * i + c];
}

void pf_bc_static_terms(const pf_bc *bc, const pf_points *pts, double t, double dt, const double *g0,
                        const double *u0, const double *g1, const double *u1, const double *beyond, double *terms) {
  const pf_int n = bc->n;
  for (pf_int k = 0; k < n; k++) {
    const pf_int i = bc->points[k];
    double w = 0;
    for (int c = 0; c < 3; c++) {
      const size_t d = 3 * (size_t)i + c;
      const double g = static_force(bc, pts, i, c, t);
      const double body = bc->kind == BC_BODY_FORCE;
      const double start = body ? static_force(bc, pts, i, c, t - dt) : bc->e[c] ? g0[d] : 0;
      if (!u1) w += 0.5 * (start + g) * (pts->u[d] - u0[d]);
      else {
        const double mid = body ? g : bc->e[c] ? g1[d] : 0;
        w += 0.5 * (start + mid) * (u1[d] - u0[d]) +
             (beyond ? (bc->e[c] ? beyond[d] : 0) : 0.5 * (mid + g) * (pts->u[d] - u1[d]));
      }
      terms[(size_t)c * n + k] = g;
      terms[(size_t)(4 + c) * n + k] = pts->u[d];
    }
    terms[3 * (size_t)n + k] = w;
  }
}
