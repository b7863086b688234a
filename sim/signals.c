/* Signals: SIGTERM and SIGINT end the set-up at once, and stop a run at the end of a step with a
 * checkpoint (sim/run.c takes the signal the step's guard reduction agreed on). */
#include "sim/sim_impl.h"

#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* SIGTERM / SIGINT: during the set-up, stop at once (nothing is written during the set-up, so
 * nothing is left half-written: a long mesh generation or neighbour search can be stopped);
 * afterwards, checkpoint at the end of the current step, then stop. Under mpirun every rank
 * receives the signal (mpirun forwards it) and ends; rank 0 prints the message. */
static volatile sig_atomic_t stop_signal = 0, in_setup = 0;
static char setup_msg[2][160]; /* [0] SIGTERM, [1] SIGINT; formatted before they are needed */
static size_t setup_len[2];

static void on_signal(int sig) {
  if (in_setup) {
    int k = sig == SIGINT;
    if (setup_len[k] && write(STDERR_FILENO, setup_msg[k], setup_len[k]) < 0) setup_len[k] = 0;
    _exit(128 + sig);
  }
  stop_signal = sig;
}

static void catch_setup_signals(int rank0) {
  const int sigs[2] = {SIGTERM, SIGINT};
  for (int k = 0; k < 2; k++) {
    snprintf(setup_msg[k], sizeof setup_msg[k],
             "perifem: %s (signal %d) during the set-up: stopped (exit status %d); nothing was run "
             "or written\n",
             k ? "SIGINT" : "SIGTERM", sigs[k], 128 + sigs[k]);
    setup_len[k] = rank0 ? strlen(setup_msg[k]) : 0;
  }
  in_setup = 1;
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  for (int k = 0; k < 2; k++) sigaction(sigs[k], &sa, NULL);
}

void pf_sim_catch_signals(void) { catch_setup_signals(pf_comm_rank() == 0); }

/* Before MPI_Init (the command line): the same set-up handler, so that a signal arriving while
 * MPI starts (a second or more) ends the process with the set-up's message instead of none. The
 * rank is not known yet: the launcher's variables say it (rank 0 prints, as later). */
void pf_sim_catch_signals_early(void) {
  const char *vars[] = {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"};
  int rank0 = 1;
  for (int k = 0; k < 3; k++)
    if (getenv(vars[k])) rank0 &= atoi(getenv(vars[k])) == 0;
  catch_setup_signals(rank0);
}

void pf_sim_setup_done(void) { in_setup = 0; }

int pf_sim_signal_here(void) { return (int)stop_signal; }

/* The library's caller (perifem_catch_signals): the run's handler only (no set-up exit), and the
 * caller's handlers kept to be put back. */
static struct sigaction caller_action[2];
static int caller_saved = 0;

void pf_sim_catch_run_signals(int on) {
  const int sigs[2] = {SIGTERM, SIGINT};
  if (on && !caller_saved) {
    in_setup = 0, stop_signal = 0;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    for (int k = 0; k < 2; k++) {
      sigaction(sigs[k], &sa, &caller_action[k]);
      if (caller_action[k].sa_handler == SIG_IGN) sigaction(sigs[k], &caller_action[k], NULL); /* (stays ignored) */
    }
    caller_saved = 1;
  } else if (!on && caller_saved) {
    for (int k = 0; k < 2; k++) sigaction(sigs[k], &caller_action[k], NULL);
    caller_saved = 0;
  }
}
