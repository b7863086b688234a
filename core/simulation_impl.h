/* Private to core/simulation*.c. */
#ifndef PF_SIMULATION_IMPL_H
#define PF_SIMULATION_IMPL_H

#include "contact/contact.h"
#include "core/simulation.h"

#define PF_MAX_BODIES 64

struct pf_sim {
  pf_deck *deck;
  pf_sim_options opt;
  pf_points *pts;
  int nbodies;
  pf_pd_body *body[PF_MAX_BODIES];
  const char *body_name[PF_MAX_BODIES];
  pf_int body_start[PF_MAX_BODIES + 1];
  int nindenters;
  pf_indenter **indenters;
  double (*reaction)[3]; /* [nindenters] force on each indenter, N */
  int nbcs;
  pf_bc **bcs;
  /* parallel */
  pf_partition_method decomposition;
  double rebalance_threshold; /* re-partition when max/mean work exceeds this (0: never) */
  int spread_output;          /* one Exodus file per rank */
  /* time */
  double t, dt, final_time;
  long step, nsteps;
  /* energy bookkeeping */
  double contact_energy, external_work;
  /* output */
  long output_interval, history_interval;
  char exodus_path[4096], history_path[4096];
  pf_exodus *exo;
  pf_points *joined; /* rank 0: every point in global-id order, for the joined Exodus file */
  pf_history *hist;
  double wall_loop;
};

extern const pf_key pf_parallel_keys[];
int pf_sim_setup_parallel(pf_sim *sim);
/* Partition the bodies' points (clouds generated on every rank), keep this rank's points with
 * their families and ghosts, and attach them to the bodies. Collective. */
int pf_sim_distribute(pf_sim *sim, const pf_point_cloud *pc);
/* Re-partition when the work imbalance exceeds the deck's threshold (at output steps). */
int pf_sim_rebalance(pf_sim *sim);
int pf_sim_setup_time(pf_sim *sim);
int pf_sim_setup_output(pf_sim *sim);

#endif
