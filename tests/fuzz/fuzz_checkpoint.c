/* libFuzzer target for the checkpoint reader: the first byte of the input picks one of the small
 * decks in tests/fuzz/decks (PD with damage and an indenter, FE with element state and a wall,
 * coupled PD/FE, FE-PD contact), the rest is written as the HDF5 checkpoint a `--restart FILE`
 * run of that deck would read. The simulation is built from it as perifem --restart builds it
 * (pf_sim_create: core/checkpoint.c and its checks in core/checkpoint_check.c, the checks against
 * the deck in sim/restart_check.c, the restore in sim/restart.c) and, when the checkpoint is
 * taken, advanced one step. Nothing may crash, hang or hit undefined behaviour; a damaged file
 * only returns an error. The decks are found under $PF_FUZZ_DECKS (default ../tests/fuzz/decks,
 * the run folder being build-fuzz/). Built by scripts/fuzz.sh; not part of the ctest run. */
#include "sim/sim.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static const char *const decks[] = {"pd", "fe", "coupled", "contact"};
enum { NDECKS = sizeof decks / sizeof decks[0] };
static char path[64], deck_path[NDECKS][512];

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  MPI_Init(argc, argv);
  pf_error_set_quiet(1);
  pf_log_set_quiet(1);
  const char *dir = getenv("PF_FUZZ_DECKS");
  if (!dir) dir = "../tests/fuzz/decks";
  for (int k = 0; k < NDECKS; k++) snprintf(deck_path[k], sizeof deck_path[k], "%s/%s.yaml", dir, decks[k]);
  snprintf(path, sizeof path, "/tmp/pf_fuzz_checkpoint_%d.h5", (int)getpid());
  return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 1) return 0;
  FILE *f = fopen(path, "wb");
  if (!f) return 0;
  fwrite(data + 1, 1, size - 1, f);
  fclose(f);
  pf_sim_options opt = {.no_output = 1, .restart_from = path};
  pf_sim *sim = NULL;
  if (pf_sim_create(deck_path[data[0] % NDECKS], &opt, &sim) == 0) pf_sim_step(sim, 1);
  pf_sim_destroy(&sim);
  pf_error_clear();
  return 0;
}
