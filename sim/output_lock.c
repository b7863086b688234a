/* One run at a time writes a file. Before its first output a run creates <file>.lock (O_CREAT |
 * O_EXCL) next to each of its outputs, the Exodus file, the history and the checkpoint, holding
 * its host name and process id; a second run that would write one of them finds the lock and is
 * refused, naming the first (its process and host). The locks go when the run ends, on an error
 * and after a signal stopped it (pf_sim_destroy); a lock whose process has ended on this host, or
 * ends within a few seconds (a killed run going down, a zombie), is taken over with a warning.
 * Rank 0 takes and removes them and every rank returns its verdict. */
#define _XOPEN_SOURCE 700 /* gethostname, kill, nanosleep */
#include "sim/sim_impl.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* The host and process id a lock file holds (pid 0 when it holds none). */
static void holder(const char *lock, char *host, size_t len, long *pid) {
  char line[512] = "";
  host[0] = '\0', *pid = 0;
  FILE *f = fopen(lock, "r");
  if (!f) return;
  if (fgets(line, sizeof line, f)) {
    char *space = strrchr(line, ' ');
    if (space) *pid = strtol(space + 1, NULL, 10), *space = '\0';
    snprintf(host, len, "%s", line);
  }
  fclose(f);
}

static int write_lock(const char *lock, const char *host, char *why, size_t len) {
  const int fd = open(lock, O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) return errno == EEXIST ? 1 : (snprintf(why, len, "cannot create the lock file '%.300s': %s", lock, strerror(errno)), -1);
  char line[320];
  const int n = snprintf(line, sizeof line, "%s %ld\n", host, (long)getpid());
  const int ok = write(fd, line, (size_t)n) == n, err = errno;
  if (close(fd) == 0 && ok) return 0;
  unlink(lock);
  snprintf(why, len, "cannot write the lock file '%.300s': %s", lock, strerror(ok ? errno : err));
  return -1;
}

/* Whether process pid of this host has ended: gone, or a zombie nobody has reaped yet. */
static int process_ended(long pid) {
  if (kill((pid_t)pid, 0) != 0) return errno == ESRCH;
  char path[64], stat[256] = "";
  snprintf(path, sizeof path, "/proc/%ld/stat", pid);
  FILE *f = fopen(path, "r");
  if (!f) return 0;
  const size_t n = fread(stat, 1, sizeof stat - 1, f);
  fclose(f);
  stat[n] = '\0';
  const char *paren = strrchr(stat, ')'); /* "pid (name) state ..." */
  return paren && (paren[2] == 'Z' || paren[2] == 'X');
}

/* Whether the holder has ended or ends within LOCK_WAIT_S seconds (a killed run's processes
 * may still be going down when the next run, a restart, starts). */
enum { LOCK_WAIT_S = 3 };
static int holder_ends(long pid) {
  for (int k = 0; k < 20 * LOCK_WAIT_S; k++) {
    if (process_ended(pid)) return 1;
    nanosleep(&(struct timespec){.tv_nsec = 50000000}, NULL);
  }
  return process_ended(pid);
}

/* 0: lock taken; else why (a message) not. */
static int take(const char *lock, char *why, size_t len) {
  char host[256] = "", other[256];
  long pid;
  gethostname(host, sizeof host - 1);
  for (int attempt = 0; attempt < 2; attempt++) {
    const int st = write_lock(lock, host, why, len);
    if (st <= 0) return st;
    holder(lock, other, sizeof other, &pid);
    if (attempt || pid <= 0 || strcmp(other, host) || !holder_ends(pid)) break;
    fprintf(stderr, "perifem warning: the lock file '%s' was left by process %ld on %s, which has ended: taken over\n",
            lock, pid, other);
    unlink(lock);
  }
  char who[320] = "another run";
  if (pid > 0) snprintf(who, sizeof who, "another run (process %ld on %s)", pid, other);
  snprintf(why, len, "%s is writing it: its lock file '%.300s' exists; wait until that run ends or name other output "
           "files (remove the lock file if no run is using it)", who, lock);
  return 1;
}

int pf_sim_lock_outputs(pf_sim *sim) {
  if (sim->nlocks) return 0;
  const pf_node *root = pf_deck_root(sim->deck), *output = pf_node_get(root, "output"),
                *restart = pf_node_get(root, "restart");
  const struct {
    const char *path, *key, *what;
    const pf_node *node;
  } file[3] = {{sim->exodus_path, "file", "the Exodus output (output.file)", pf_node_get(output, "file")},
               {sim->history_path, "history_file", "the history (output.history_file)", pf_node_get(output, "history_file")},
               {sim->restart_path, "file", "the checkpoint (restart.file)", pf_node_get(restart, "file")}};
  char msg[1024] = "";
  int ok = 1;
  for (int k = 0; k < 3 && ok && pf_comm_rank() == 0; k++) {
    char lock[PATH_MAX + 8], why[1024], where[512];
    snprintf(lock, sizeof lock, "%s.lock", file[k].path);
    int st = take(lock, why, sizeof why);
    if (!st && !(sim->lock_path[sim->nlocks] = strdup(lock))) {
      unlink(lock);
      snprintf(why, sizeof why, "out of memory");
      st = 1;
    }
    if (!st) {
      sim->nlocks++;
      continue;
    }
    pf_node_where(sim->deck, file[k].node ? file[k].node : (k < 2 ? output : restart), where, sizeof where);
    snprintf(msg, sizeof msg, "%.200s: key '%s': %s '%.200s': %.500s", where, file[k].key, file[k].what, file[k].path,
             why);
    ok = 0;
  }
  if (!ok) pf_sim_unlock_outputs(sim);
  PF_AGREE(ok, PF_ERR_INPUT, msg);
  return 0;
}

void pf_sim_unlock_outputs(pf_sim *sim) {
  for (int k = 0; k < sim->nlocks; k++) {
    unlink(sim->lock_path[k]);
    PF_FREE(sim->lock_path[k]);
  }
  sim->nlocks = 0;
}
