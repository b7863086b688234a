/* Element-to-particle conversion in the driver (fem/particles.c, docs/theory/fem.md §9b): each
 * `type: particles` body is linked at set-up to the FE body it names, and at each step's end
 * takes the elements that body's erosion deleted in the step. The contact search is then rebuilt
 * so that the new particles take part in it from the next step on. */
#include "sim/sim_impl.h"

#include <stdlib.h>
#include <string.h>

int pf_sim_link_particles(pf_sim *sim) {
  int used[PF_MAX_BODIES] = {0};
  for (int b = 0; b < sim->nbodies; b++) {
    pf_fem_particles *p = pf_body_as_particles(&sim->body[b]);
    if (!p) continue;
    struct pf_fem_body *fe = NULL;
    for (int q = 0; q < sim->nbodies; q++)
      if (!strcmp(sim->body_name[q], pf_fem_particles_source(p)) && pf_body_as_fem(&sim->body[q]) && !used[q])
        fe = pf_body_as_fem(&sim->body[q]), used[q] = 1;
    PF_CALL(pf_fem_particles_link(p, fe));
  }
  const pf_node *bodies = pf_node_get(pf_deck_root(sim->deck), "bodies");
  for (int q = 0; q < sim->nbodies; q++) { /* an FE body that converts needs its particles body */
    const pf_node *er = pf_node_get(pf_node_item(bodies, q), "erosion");
    int convert = 0;
    if (er && pf_node_get(er, "convert_to_particles")) PF_CALL(pf_deck_bool(sim->deck, er, "convert_to_particles", &convert));
    if (convert && !used[q])
      return pf_deck_error(sim->deck, pf_node_get(er, "convert_to_particles"), "convert_to_particles",
                           "body '%s' converts its deleted elements, but no body of type: particles names it "
                           "(add one: {name: %s_particles, type: particles, from: %s})",
                           sim->body_name[q], sim->body_name[q], sim->body_name[q]);
  }
  return 0;
}

/* The penalty energy in the books now: the accounts that add into contact_energy (each the same
 * on every rank). */
static double contact_energy(const pf_sim *sim) {
  const pf_ledger *l = &sim->ledger;
  double U = 0;
  for (int k = 0; k < l->n; k++)
    if (l->a[k].total == sim->acc.totals.contact) U += l->a[k].local[0];
  return U;
}

/* The penalty energy the new particles bring in where they overlap a surface or another point
 * (a particle is born at its element's centre of mass, which may lie closer to a neighbour than
 * the contact radius): the contact energy at the same positions with and without them, the
 * difference booked against the conversion (on the rank owning the first new particle), so
 * that the balance still closes. The step's forces and books are left as they were. */
static int book_overlap(pf_sim *sim, pf_fem_particles *first_p) {
  pf_points *p = sim->pts;
  pf_ledger *l = &sim->ledger;
  double *f = NULL;
  pf_account *books = NULL;
  PF_MALLOC(f, 3 * (size_t)p->n_owned);
  books = malloc(sizeof *books * (size_t)l->n);
  if (!books) free(f);
  PF_CHECK(books, PF_ERR_MEMORY, "out of memory");
  memcpy(f, p->f, sizeof(double) * 3 * (size_t)p->n_owned);
  memcpy(books, l->a, sizeof *books * (size_t)l->n);
  const double U0 = contact_energy(sim);
  int ierr = pf_sim_interactions_force(sim, 0.0, NULL); /* (dt 0: no friction, no work) */
  const double U = contact_energy(sim);
  memcpy(p->f, f, sizeof(double) * 3 * (size_t)p->n_owned);
  memcpy(l->a, books, sizeof *books * (size_t)l->n);
  free(f), free(books);
  if (!ierr) pf_fem_particles_book(first_p, p, -(U - U0));
  return ierr;
}

/* After a restart restored the conversions: the stable step of the restored masses. */
int pf_sim_converts(const pf_sim *sim) {
  for (int b = 0; b < sim->nbodies; b++)
    if (pf_body_as_particles(&sim->body[b])) return 1;
  return 0;
}

int pf_sim_convert_elements(pf_sim *sim, long *converted) {
  long any = 0;
  *converted = 0;
  pf_fem_particles *first = NULL;
  for (int b = 0; b < sim->nbodies; b++) {
    pf_fem_particles *fp = pf_body_as_particles(&sim->body[b]);
    if (!fp) continue;
    long n = 0;
    PF_CALL(pf_fem_particles_convert(fp, sim->pts, sim->dt, sim->t, &n));
    if (n && !first) first = fp;
    any += n;
  }
  if (!any) return 0;
  *converted = any;
  pf_sim_interactions_masses_changed(sim);
  return sim->ninter ? book_overlap(sim, first) : 0;
}
