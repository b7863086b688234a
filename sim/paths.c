/* No output overwrites an input or another output. Files are compared through the file system:
 * the same inode when both exist, else the same canonical path (the real path of the folder and
 * the name), so `o.e` and `./o.e`, a symbolic link and its target, or a mesh reached through
 * `../` are the same file. Inputs: the deck, the FE bodies' mesh files, the point files, the
 * checkpoint restarted from; outputs: the Exodus file, the history, the checkpoint and the
 * fragments table. A clash is an input error naming the output's key; nothing has been written. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "sim/sim_impl.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef struct {
  char path[4200];
  const pf_node *node; /* where the deck names it (or its section), for the message */
  const char *key;     /* outputs: the key that names it */
  char what[160];
} named_file;

/* The real path of an existing file, or of its folder joined with its name (out: PATH_MAX). */
static void canonical(const char *p, char *out, size_t len) {
  char *r = realpath(p, NULL);
  if (r) {
    snprintf(out, len, "%s", r);
    free(r);
    return;
  }
  const char *slash = strrchr(p, '/');
  char dir[4200];
  snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - p) : 1, slash ? (slash == p ? "/" : p) : ".");
  r = realpath(dir, NULL);
  snprintf(out, len, "%s/%s", r ? r : dir, slash ? slash + 1 : p);
  free(r);
}

static int same_file(const char *a, const char *b) {
  struct stat sa, sb;
  if (!stat(a, &sa) && !stat(b, &sb)) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  char ca[8500], cb[8500];
  canonical(a, ca, sizeof ca), canonical(b, cb, sizeof cb);
  return !strcmp(ca, cb);
}

static void add(named_file *list, int *n, int cap, const char *path, const pf_node *node, const char *key,
                const char *what) {
  if (*n >= cap || !path || !*path) return;
  snprintf(list[*n].path, sizeof list[*n].path, "%s", path);
  list[*n].node = node, list[*n].key = key;
  snprintf(list[*n].what, sizeof list[*n].what, "%s", what);
  (*n)++;
}

/* A file body b's mapping names under `section.file` (mesh:, geometry:), relative to the deck. */
static void add_body_file(const pf_sim *sim, named_file *list, int *n, int cap, int b, const char *section) {
  const pf_node *map = pf_node_get(pf_node_item(pf_node_get(pf_deck_root(sim->deck), "bodies"), b), section);
  const pf_node *file = pf_node_get(map, "file");
  if (!file) return;
  char path[4096], what[160];
  pf_deck_relative_path(sim->deck, pf_node_text(file), path, sizeof path);
  snprintf(what, sizeof what, "the input bodies[%d].%s.file", b, section);
  add(list, n, cap, path, file, "file", what);
}

int pf_sim_check_paths(pf_sim *sim) {
  enum { CAP = 2 * PF_MAX_BODIES + 8 + PF_DECK_MAX_INCLUDES };
  named_file in[CAP], out[4];
  int nin = 0, nout = 0;
  const pf_node *root = pf_deck_root(sim->deck), *output = pf_node_get(root, "output"),
                *restart = pf_node_get(root, "restart");
  add(in, &nin, CAP, pf_deck_path(sim->deck), root, NULL, "the deck");
  for (int k = 0; pf_deck_included(sim->deck, k); k++)
    add(in, &nin, CAP, pf_deck_included(sim->deck, k), pf_node_get(root, "include"), "include", "an included deck");
  for (int b = 0; b < sim->nbodies; b++) {
    add_body_file(sim, in, &nin, CAP, b, "mesh");
    add_body_file(sim, in, &nin, CAP, b, "geometry");
  }
  if (sim->opt.no_output) return 0;
  const pf_node *file = pf_node_get(output, "file");
  add(out, &nout, 4, sim->exodus_path, file ? file : output, "file", "the Exodus output (output.file)");
  file = pf_node_get(output, "history_file");
  add(out, &nout, 4, sim->history_path, file ? file : output, "history_file", "the history (output.history_file)");
  if (sim->fragments) add(out, &nout, 4, sim->fragments_path, pf_node_get(output, "fragments"), "fragments", "the fragments table");
  /* the checkpoint may be the one the run restarts from (it is read before it is rewritten) */
  if (sim->opt.restart_from) add(in, &nin, CAP, sim->opt.restart_from, NULL, NULL, "the checkpoint restarted from");
  file = pf_node_get(restart, "file");
  add(out, &nout, 4, sim->restart_path, file ? file : restart, "file", "the checkpoint (restart.file)");
  for (int k = 0; k < nout; k++) {
    const int checkpoint = k == nout - 1, inputs = checkpoint && sim->opt.restart_from ? nin - 1 : nin;
    for (int q = 0; q < inputs; q++)
      if (same_file(out[k].path, in[q].path))
        return pf_deck_error(sim->deck, out[k].node, out[k].key, "%s '%s' would overwrite %s '%s'; name another file",
                             out[k].what, out[k].path, in[q].what, in[q].path);
    for (int q = 0; q < k; q++)
      if (same_file(out[k].path, out[q].path))
        return pf_deck_error(sim->deck, out[k].node, out[k].key, "%s '%s' is the same file as %s; name another file",
                             out[k].what, out[k].path, out[q].what);
  }
  return 0;
}

/* mkdir -p, one level at a time (an existing folder is fine), then the whole path a folder. */
int pf_sim_make_dir(const char *dir) {
  int err = 0;
  if (pf_comm_rank() == 0) {
    char path[4096];
    snprintf(path, sizeof path, "%s", dir);
    for (char *p = path + 1; !err; p++) {
      if (*p && *p != '/') continue;
      const char keep = *p;
      *p = '\0';
      if (mkdir(path, 0777) && errno != EEXIST) err = errno;
      *p = keep;
      if (!keep) break;
    }
    struct stat st;
    if (!err && (stat(dir, &st) || !S_ISDIR(st.st_mode))) err = ENOTDIR;
  }
  MPI_Bcast(&err, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return err;
}
