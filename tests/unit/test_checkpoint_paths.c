/* perifem_checkpoint (the public C API) goes through the rule for every file a run writes
 * (sim/paths.c), on a 16-point PD deck in a fresh folder:
 *  - the deck, its point file, the deck through a symbolic link, the run's Exodus output, and a
 *    device (/dev/null) are refused: a non-zero status, a message naming the file, and the deck
 *    and point file left byte for byte as they were;
 *  - a checkpoint through a symbolic link writes the link's target (a regular file) and keeps
 *    the link; a plain new name is written, without a temporary file left beside it;
 *  - a checkpoint into a folder that does not exist, or one HDF5 cannot create (in /proc), fails
 *    alone: the run goes on, a checkpoint is written after it, and perifem_finalize succeeds.
 * Rank 0 prints only on failure. */
#include "test_common.h"

#include "include/perifem.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char dir[512];

/* dir/name */
static const char *in_dir(int slot, const char *name) {
  static char path[4][768];
  snprintf(path[slot], sizeof path[slot], "%s/%s", dir, name);
  return path[slot];
}

static void write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  if (!f || fputs(text, f) < 0 || fclose(f)) {
    fprintf(stderr, "cannot write %s: %s\n", path, strerror(errno));
    exit(1);
  }
}

static char *read_text(const char *path) {
  static char text[2][4096];
  static int slot;
  char *t = text[slot ^= 1];
  FILE *f = fopen(path, "r");
  const size_t n = f ? fread(t, 1, sizeof text[0] - 1, f) : 0;
  t[n] = '\0';
  if (f) fclose(f);
  return t;
}

/* A checkpoint over path is refused, the message naming it, the inputs unchanged. */
static void refused(perifem_sim *sim, const char *path, const char *mention) {
  const char *deck = in_dir(0, "d.yaml"), *pts = in_dir(1, "pts.txt");
  char before[2][4096];
  snprintf(before[0], sizeof before[0], "%s", read_text(deck));
  snprintf(before[1], sizeof before[1], "%s", read_text(pts));
  const int st = perifem_checkpoint(sim, path);
  PF_TEST_TRUE(st == PERIFEM_ERR_INPUT);
  PF_TEST_TRUE(strstr(perifem_last_error(), mention) != NULL);
  if (st != PERIFEM_ERR_INPUT || !strstr(perifem_last_error(), mention))
    fprintf(stderr, "  checkpoint over %s: status %d, message: %s\n", path, st, perifem_last_error());
  PF_TEST_TRUE(!strcmp(before[0], read_text(deck)) && !strcmp(before[1], read_text(pts)));
}

static int is_link(const char *path) {
  struct stat st;
  return !lstat(path, &st) && S_ISLNK(st.st_mode);
}

static int is_file(const char *path) {
  struct stat st;
  return !stat(path, &st) && S_ISREG(st.st_mode) && st.st_size > 0;
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  const char *tmp = getenv("TMPDIR");
  snprintf(dir, sizeof dir, "%s/test_checkpoint_paths.%d", tmp && *tmp ? tmp : "/tmp", (int)getpid());
  if (mkdir(dir, 0777) || mkdir(in_dir(0, "sub"), 0777)) return fprintf(stderr, "cannot make %s\n", dir), 1;
  char pts[1024] = "";
  for (int i = 0; i < 16; i++)
    snprintf(pts + strlen(pts), sizeof pts - strlen(pts), "%g %g %g 1e-9 1\n", 1e-3 * (i / 4), 1e-3 * (i / 2 % 2),
             1e-3 * (i % 2));
  write_text(in_dir(0, "pts.txt"), pts);
  write_text(in_dir(0, "d.yaml"), "materials: {m: {model: pmb, density: 1000, bulk_modulus: 1.0e9}}\n"
                                  "bodies:\n"
                                  "  - {name: b, material: m, horizon: 0.0021, geometry: {shape: points_file, file: pts.txt}}\n"
                                  "time: {steps: 3}\n");
  PF_TEST_TRUE(!symlink("d.yaml", in_dir(0, "deck_link.yaml")) && !symlink("sub/target.h5", in_dir(0, "link.h5")));
  perifem_options opt = {0};
  opt.quiet = 1, opt.silent_errors = 1, opt.output_dir = dir;
  perifem_sim *sim = NULL;
  if (perifem_create(in_dir(0, "d.yaml"), &opt, &sim)) return fprintf(stderr, "%s\n", perifem_last_error()), 1;
  PF_TEST_OK(perifem_step(sim, 2));

  refused(sim, in_dir(2, "d.yaml"), "the deck");
  refused(sim, in_dir(2, "pts.txt"), "bodies[0].geometry.file");
  refused(sim, in_dir(2, "deck_link.yaml"), "the deck");
  refused(sim, in_dir(2, "d.e"), "the Exodus output");
  refused(sim, "/dev/null", "character device");

  PF_TEST_OK(perifem_checkpoint(sim, in_dir(2, "link.h5")));
  PF_TEST_TRUE(is_link(in_dir(2, "link.h5")) && is_file(in_dir(3, "sub/target.h5")));
  PF_TEST_OK(perifem_checkpoint(sim, in_dir(2, "ok.h5")));
  PF_TEST_TRUE(is_file(in_dir(2, "ok.h5")) && access(in_dir(3, "ok.h5.tmp"), F_OK));

  /* A failed checkpoint fails that call only: a folder that does not exist (refused by the path
   * check) and a file HDF5 cannot create (/proc: the check passes for root, H5Fcreate fails); the
   * run goes on, the next checkpoint is written, and perifem_finalize succeeds (before, after
   * H5Fcreate failed: PERIFEM_ERR_RUN "a file could not be closed", the command line's exit 1). */
  const char *bad[2] = {in_dir(2, "no_such_folder/c.h5"), "/proc/perifem_checkpoint.h5"};
  for (int k = 0; k < 2; k++) {
    const int st = perifem_checkpoint(sim, bad[k]);
    const int named = strstr(perifem_last_error(), k ? "/proc" : "no_such_folder") != NULL;
    PF_TEST_TRUE(st != PERIFEM_OK && named);
    if (st == PERIFEM_OK || !named)
      fprintf(stderr, "  checkpoint %s: status %d, message: %s\n", bad[k], st, perifem_last_error());
    PF_TEST_OK(perifem_step(sim, 1));
    PF_TEST_TRUE(perifem_last_error()[0] == '\0');
  }
  PF_TEST_OK(perifem_checkpoint(sim, in_dir(2, "ok.h5")));
  PF_TEST_OK(perifem_destroy(&sim));
  PF_TEST_OK(perifem_finalize()); /* (MPI is the test's: left running) */

  const char *names[] = {"sub/target.h5", "link.h5", "ok.h5", "d.e", "d.h5", "deck_link.yaml", "d.yaml", "pts.txt"};
  for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) unlink(in_dir(0, names[k]));
  rmdir(in_dir(0, "sub"));
  rmdir(dir);
  return pf_test_finish();
}
