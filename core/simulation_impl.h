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
  /* time */
  double t, dt, final_time;
  long step, nsteps;
  /* energy bookkeeping */
  double contact_energy, external_work;
  /* output */
  long output_interval, history_interval;
  char exodus_path[4096], history_path[4096];
  pf_exodus *exo;
  pf_history *hist;
  double wall_loop;
};

int pf_sim_setup_time(pf_sim *sim);
int pf_sim_setup_output(pf_sim *sim);

#endif
