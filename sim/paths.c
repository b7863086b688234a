/* One rule for every file a run writes, checked before anything is written: the Exodus output
 * (output.file), the history (output.history_file), the fragments table, the checkpoint
 * (restart.file, or the path given to perifem_checkpoint) and the checkpoint's temporary file
 * <checkpoint>.tmp. Each of them
 *  - is no input of the run (the deck, the included decks, the FE bodies' mesh files, the point
 *    files, the checkpoint restarted from: a run may rewrite that one, it is read first) and no
 *    other output or temporary file. Files are compared through the file system: the same inode
 *    when both exist, else the same canonical path (the real path of the folder and the name), so
 *    `o.e` and `./o.e`, a symbolic link and its target, or a mesh reached through `../` are the
 *    same file;
 *  - is absent or a regular file: not a folder, a device, a FIFO or a socket;
 *  - when it is a symbolic link, is its target: the log names it, the target is written and the
 *    link stays;
 *  - lies in a folder that exists (or is the --output-dir the run creates) and is writable, and is
 *    writable when it exists; the message gives the system's reason;
 *  - has a path of at most PF_SIM_PATH_MAX bytes (sim/output.c; the Exodus library's own limits
 *    are core/exodus_path.c's).
 * A breach is an input error naming the key, the file and the reason. The lock that keeps two
 * runs from writing the same files is sim/output_lock.c. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "sim/sim_impl.h"

#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef struct {
  char path[4200];
  const pf_node *node; /* where the deck names it (or its section), for the message */
  const char *key;     /* outputs: the key that names it; NULL with node NULL: perifem_checkpoint's path */
  char what[160];
  char *target;        /* outputs: the sim's copy of the path, rewritten to a link's target (or NULL) */
  size_t target_len;
  int temporary;       /* the checkpoint's temporary file */
  int may_be_restart;  /* the checkpoint: may be the file restarted from */
} named_file;

enum { MAX_INPUTS = 2 * PF_MAX_BODIES + 8 + PF_DECK_MAX_INCLUDES, MAX_OUTPUTS = 6 };
typedef struct {
  named_file in[MAX_INPUTS], out[MAX_OUTPUTS];
  int nin, nout;
} file_lists;

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

static named_file *add(named_file *list, int *n, int cap, const char *path, const pf_node *node, const char *key,
                       const char *what) {
  if (*n >= cap || !path || !*path) return NULL;
  named_file *f = &list[(*n)++];
  memset(f, 0, sizeof *f);
  snprintf(f->path, sizeof f->path, "%s", path);
  f->node = node, f->key = key;
  snprintf(f->what, sizeof f->what, "%s", what);
  return f;
}

/* An input error about output o: at its deck key, or perifem_checkpoint's. */
static int refuse(const pf_sim *sim, const named_file *o, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int refuse(const pf_sim *sim, const named_file *o, const char *fmt, ...) {
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (!o->key) return pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__, "perifem_checkpoint: %s", msg);
  return pf_deck_error(sim->deck, o->node, o->key, "%s", msg);
}

/* A file body b's mapping names under `section.file` (mesh:, geometry:), relative to the deck. */
static void add_body_file(const pf_sim *sim, file_lists *l, int b, const char *section) {
  const pf_node *map = pf_node_get(pf_node_item(pf_node_get(pf_deck_root(sim->deck), "bodies"), b), section);
  const pf_node *file = pf_node_get(map, "file");
  if (!file) return;
  char path[4096], what[160];
  pf_deck_relative_path(sim->deck, pf_node_text(file), path, sizeof path);
  snprintf(what, sizeof what, "the input bodies[%d].%s.file", b, section);
  add(l->in, &l->nin, MAX_INPUTS, path, file, "file", what);
}

static void list_inputs(const pf_sim *sim, file_lists *l) {
  const pf_node *root = pf_deck_root(sim->deck);
  add(l->in, &l->nin, MAX_INPUTS, pf_deck_path(sim->deck), root, NULL, "the deck");
  for (int k = 0; pf_deck_included(sim->deck, k); k++)
    add(l->in, &l->nin, MAX_INPUTS, pf_deck_included(sim->deck, k), pf_node_get(root, "include"), "include",
        "an included deck");
  for (int b = 0; b < sim->nbodies; b++) {
    add_body_file(sim, l, b, "mesh");
    add_body_file(sim, l, b, "geometry");
  }
  if (sim->opt.restart_from) add(l->in, &l->nin, MAX_INPUTS, sim->opt.restart_from, NULL, NULL, "the checkpoint restarted from");
}

/* The folder a path's file is in ("." for a bare name). */
static void folder_of(const char *path, char *dir, size_t len) {
  const char *slash = strrchr(path, '/');
  snprintf(dir, len, "%.*s", slash ? (int)(slash - path) + (slash == path) : 1, slash ? path : ".");
}

/* The file a symbolic link leads to: the real path of an existing one; for a link to a file not
 * there yet, the link's text (relative to the link's folder) with its folder's real path. */
static int link_target(const pf_sim *sim, const named_file *o, char *out, size_t len) {
  char *real = realpath(o->path, NULL);
  if (real) {
    snprintf(out, len, "%s", real);
    free(real);
    return 0;
  }
  char text[4200], dir[4200], joined[4200];
  const ssize_t n = errno == ENOENT ? readlink(o->path, text, sizeof text - 1) : -1;
  if (n > 0) {
    text[n] = '\0';
    folder_of(o->path, dir, sizeof dir);
    if (strlen(dir) + (size_t)n + 2 > sizeof joined) return refuse(sim, o, "%s '%s' is a symbolic link to a path "
                                                                   "of more than %zu bytes", o->what, o->path, sizeof joined - 1);
    if (text[0] == '/') snprintf(joined, sizeof joined, "%s", text);
    else snprintf(joined, sizeof joined, "%.2000s/%.2100s", dir, text);
    canonical(joined, out, len);
    struct stat st;
    if (!lstat(out, &st)) errno = ELOOP; /* (the target is a link itself, leading nowhere) */
    else if (errno == ENOENT) return 0;
  }
  return refuse(sim, o, "%s '%s' is a symbolic link to nothing that can be written: %s", o->what, o->path,
                strerror(errno));
}

/* A symbolic link stands for its target: o (and the sim's copy of the path) become the target. */
static int follow_link(const pf_sim *sim, named_file *o) {
  struct stat st;
  if (lstat(o->path, &st) || !S_ISLNK(st.st_mode)) return 0;
  char real[8500];
  PF_CALL(link_target(sim, o, real, sizeof real));
  const size_t n = strlen(real);
  if (n <= PF_SIM_PATH_MAX) {
    pf_log("%s %s is a symbolic link: writing its target %s\n", o->what, o->path, real);
    snprintf(o->path, sizeof o->path, "%s", real);
    if (o->target) snprintf(o->target, o->target_len, "%s", real);
  }
  if (n > PF_SIM_PATH_MAX)
    return refuse(sim, o, "%s '%s' is a symbolic link to a path of %zu bytes; at most %d", o->what, o->path, n,
                  PF_SIM_PATH_MAX);
  return 0;
}

/* An output and, for a checkpoint, its temporary file after it (its link followed first). */
static int add_output(const pf_sim *sim, file_lists *l, char *path, size_t len, const pf_node *node, const char *key,
                      const char *what, int checkpoint) {
  named_file *o = add(l->out, &l->nout, MAX_OUTPUTS, path, node, key, what);
  if (!o) return 0;
  o->target = path, o->target_len = len, o->may_be_restart = checkpoint;
  PF_CALL(follow_link(sim, o));
  if (!checkpoint) return 0;
  char tmp[4200], tmp_what[160];
  snprintf(tmp, sizeof tmp, "%.4100s.tmp", o->path); /* (a path is at most PF_SIM_PATH_MAX bytes) */
  snprintf(tmp_what, sizeof tmp_what, "the temporary file of %.120s", what);
  named_file *t = add(l->out, &l->nout, MAX_OUTPUTS, tmp, node, key, tmp_what);
  if (t) t->temporary = 1;
  return 0;
}

static int list_outputs(pf_sim *sim, file_lists *l) {
  const pf_node *root = pf_deck_root(sim->deck), *output = pf_node_get(root, "output");
  const pf_node *file = pf_node_get(output, "file"), *hfile = pf_node_get(output, "history_file");
  PF_CALL(add_output(sim, l, sim->exodus_path, sizeof sim->exodus_path, file ? file : output, "file",
                     "the Exodus output (output.file)", 0));
  PF_CALL(add_output(sim, l, sim->history_path, sizeof sim->history_path, hfile ? hfile : output, "history_file",
                     "the history (output.history_file)", 0));
  if (sim->fragments)
    PF_CALL(add_output(sim, l, sim->fragments_path, sizeof sim->fragments_path, pf_node_get(output, "fragments"),
                       "fragments", "the fragments table", 0));
  return 0;
}

static const char *kind_of(mode_t m) {
  return S_ISDIR(m) ? "a folder" : S_ISCHR(m) ? "a character device" : S_ISBLK(m) ? "a block device"
       : S_ISFIFO(m) ? "a FIFO (named pipe)" : S_ISSOCK(m) ? "a socket" : "not a regular file";
}

/* --output-dir, which the run creates when it starts (its trailing slashes aside). */
static int is_output_dir(const pf_sim *sim, const char *dir) {
  if (!sim->opt.output_dir) return 0;
  size_t n = strlen(sim->opt.output_dir), m = strlen(dir);
  while (n > 1 && sim->opt.output_dir[n - 1] == '/') n--;
  while (m > 1 && dir[m - 1] == '/') m--;
  return n == m && !strncmp(dir, sim->opt.output_dir, n);
}

/* Absent or a regular file that can be written, in a folder that can be written. */
static int check_kind(const pf_sim *sim, const named_file *o) {
  char dir[4200];
  struct stat st;
  folder_of(o->path, dir, sizeof dir);
  const int no_dir = stat(dir, &st) ? errno : 0;
  if (no_dir && is_output_dir(sim, dir)) return 0; /* (made when the run starts, which says why it cannot be) */
  if (no_dir) return refuse(sim, o, "the folder '%s' of %s: %s", dir, o->what, strerror(no_dir));
  if (!S_ISDIR(st.st_mode)) return refuse(sim, o, "the folder '%s' of %s: %s", dir, o->what, strerror(ENOTDIR));
  if (access(dir, W_OK | X_OK)) return refuse(sim, o, "cannot write into the folder '%s' of %s: %s", dir, o->what, strerror(errno));
  if (stat(o->path, &st)) {
    if (errno == ENOENT) return 0;
    return refuse(sim, o, "%s '%s': %s", o->what, o->path, strerror(errno));
  }
  if (!S_ISREG(st.st_mode)) return refuse(sim, o, "%s '%s' is %s; name a regular file", o->what, o->path, kind_of(st.st_mode));
  if (access(o->path, W_OK)) return refuse(sim, o, "%s '%s' cannot be written: %s", o->what, o->path, strerror(errno));
  return 0;
}

/* Output k against the inputs and the outputs before it. */
static int check_clashes(const pf_sim *sim, const file_lists *l, int k) {
  const named_file *o = &l->out[k];
  for (int q = 0; q < l->nin; q++) {
    const int restarted = sim->opt.restart_from && q == l->nin - 1; /* (read before it is rewritten) */
    if ((!restarted || !o->may_be_restart) && same_file(o->path, l->in[q].path))
      return refuse(sim, o, "%s '%s' would overwrite %s '%s'; name another file", o->what, o->path, l->in[q].what,
                    l->in[q].path);
  }
  for (int q = 0; q < k; q++) {
    if (!same_file(o->path, l->out[q].path)) continue;
    const named_file *at = o->temporary ? &l->out[q] : o, *other = o->temporary ? o : &l->out[q];
    return refuse(sim, at, "%s '%s' is the same file as %s; name another file", at->what, at->path, other->what);
  }
  return 0;
}

static int check_all(const pf_sim *sim, const file_lists *l) {
  for (int k = 0; k < l->nout; k++) {
    PF_CALL(check_kind(sim, &l->out[k]));
    PF_CALL(check_clashes(sim, l, k));
  }
  return 0;
}

int pf_sim_check_paths(pf_sim *sim) {
  if (sim->opt.no_output) return 0;
  file_lists *l;
  PF_MALLOC(l, 1);
  list_inputs(sim, l);
  const pf_node *restart = pf_node_get(pf_deck_root(sim->deck), "restart"), *file = pf_node_get(restart, "file");
  int ierr = list_outputs(sim, l);
  if (!ierr)
    ierr = add_output(sim, l, sim->restart_path, sizeof sim->restart_path, file ? file : restart, "file",
                      "the checkpoint (restart.file)", 1);
  if (!ierr) ierr = check_all(sim, l);
  free(l);
  return ierr;
}

int pf_sim_check_checkpoint_path(pf_sim *sim, const char *path, char *target, size_t len) {
  const size_t n = strlen(path);
  PF_CHECK(n <= PF_SIM_PATH_MAX && n < len, PF_ERR_INPUT, "perifem_checkpoint: the path is %zu bytes long; at most %d",
           n, PF_SIM_PATH_MAX);
  snprintf(target, len, "%s", path);
  file_lists *l;
  PF_MALLOC(l, 1);
  list_inputs(sim, l);
  int ierr = sim->opt.no_output ? 0 : list_outputs(sim, l);
  if (!ierr) ierr = add_output(sim, l, target, len, NULL, NULL, "the checkpoint", 1);
  if (!ierr) ierr = check_all(sim, l);
  free(l);
  return ierr;
}

/* The deepest existing folder of path (cut in place): 0, ENOTDIR when a file stands where a
 * folder must, or the errno of stat. */
static int deepest_existing(char *path) {
  struct stat st;
  while (stat(path, &st)) {
    if (errno != ENOENT) return errno;
    char *slash = strrchr(path, '/');
    if (slash == path) slash[1] = '\0'; /* "/a" -> "/" */
    else if (slash) *slash = '\0';
    else strcpy(path, "."); /* a relative path's first level */
  }
  return S_ISDIR(st.st_mode) ? 0 : ENOTDIR;
}

int pf_sim_dir_creatable(const char *dir) {
  int err = 0;
  if (pf_comm_rank() == 0) {
    char path[4096];
    snprintf(path, sizeof path, "%s", dir);
    err = deepest_existing(path);
    if (!err && strcmp(path, dir) && access(path, W_OK | X_OK)) err = errno;
  }
  MPI_Bcast(&err, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return err;
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
