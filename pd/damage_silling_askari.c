/* Bond failure by an evolving critical stretch (Silling & Askari 2005, eq. 10): a bond fails for
 * good when its stretch exceeds min(s0_i, s0_j), with
 *   s0_i = s00 - alpha s_min_i,
 * s_min_i the smallest stretch among point i's intact bonds in the previous step (as LAMMPS'
 * peri/pmb); every point starts at s00. */
#include "pd/pd_impl.h"

static const pf_key keys[] = {
    {"s00", PF_KEY_REAL, 0, NULL, "", "silling_askari: s00 in s0 = s00 - alpha s_min", NULL},
    {"alpha", PF_KEY_REAL, 0, "0.25", "", "silling_askari: alpha in s0 = s00 - alpha s_min", NULL},
    PF_KEY_END};

typedef struct {
  double s00, alpha;
} silling_askari;

static int read_silling_askari(const pf_deck *d, const pf_node *map, pf_pd_body *b) {
  silling_askari *p;
  PF_MALLOC(p, 1);
  b->damage_data = p;
  PF_CALL(pf_pd_damage_read_required(d, map, "s00", &p->s00));
  p->alpha = 0.25;
  PF_CALL(pf_deck_real(d, map, "alpha", &p->alpha));
  b->s0_init = p->s00;
  return 0;
}

/* s0_i = s00 - alpha * s_min_i for the next step (eq. 10); a point with no intact bond keeps
 * its s0. */
static int post_step(pf_pd_body *b, pf_points *pts) {
  const silling_askari *p = b->damage_data;
  for (pf_int k = 0; k < b->n; k++)
    if (isfinite(b->smin[k])) b->s0[b->first + k] = p->s00 - p->alpha * b->smin[k];
  return pf_points_exchange(pts, b->s0, 1); /* the ghosts' s0 for the next step's bond test */
}

const pf_pd_damage_ops pf_pd_damage_silling_askari = {
    .name = "silling_askari",
    .keys = keys,
    .read = read_silling_askari,
    .post_step = post_step,
};
