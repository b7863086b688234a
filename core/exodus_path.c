/* Paths handed to the Exodus library. Its version 6.02 formats the path of a failed ex_create or
 * ex_open into a 256-byte message with sprintf, and the process aborts there (buffer overflow,
 * SIGABRT), measured from 211 bytes (ex_create, classic file), 141 (ex_create, netCDF-4 file) and
 * 224 (ex_open). A path longer than a limit below those is handed over as
 * /proc/self/fd/<descriptor of its folder>/<name>, the folder held open around the call; a name
 * too long even so is refused, naming the limit. */
#define _XOPEN_SOURCE 700 /* O_DIRECTORY */
#include "core/core.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <string.h>
#include <unistd.h>

static const int limit[3] = {200, 130, 210}; /* PF_EXODUS_CREATE, PF_EXODUS_CREATE4, PF_EXODUS_OPEN */

int pf_exodus_path_begin(const char *path, pf_exodus_call call, pf_exodus_path *p) {
  p->use = path, p->dirfd = -1;
  const size_t n = strlen(path);
  if (n <= (size_t)limit[call]) return 0;
  const char *slash = strrchr(path, '/'), *name = slash ? slash + 1 : path;
  char dir[PATH_MAX];
  PF_CHECK(n < sizeof dir, PF_ERR_INPUT, "the path is %zu bytes long; at most %d (PATH_MAX): %.100s...%s", n,
           PATH_MAX - 1, path, path + n - 60);
  snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) + 1 : 1, slash ? path : ".");
  p->dirfd = open(dir, O_RDONLY | O_DIRECTORY);
  PF_CHECK(p->dirfd >= 0, PF_ERR_INPUT, "cannot open the folder of %s: %s", path, strerror(errno));
  const int len = snprintf(p->alias, sizeof p->alias, "/proc/self/fd/%d/%s", p->dirfd, name);
  if (len <= limit[call]) return p->use = p->alias, 0;
  pf_exodus_path_end(p);
  return pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                        "%s: the file name is %zu bytes long; the Exodus library takes names of at most %d "
                        "bytes%s",
                        path, strlen(name), limit[call] - len + (int)strlen(name),
                        call == PF_EXODUS_CREATE4 ? " in a compressed (netCDF-4) file" : "");
}

void pf_exodus_path_end(pf_exodus_path *p) {
  if (p->dirfd >= 0) close(p->dirfd);
  p->dirfd = -1, p->use = NULL;
}
