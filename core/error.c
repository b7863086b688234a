/* Error recording and logging: the first error raised is kept with its origin
 * and printed once to stderr (with its source position when PERIFEM_DEBUG is set); the
 * PF_CALL levels above it return the same code without printing again. */
#include "core/core.h"

#include <limits.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

static char first_message[2048];
static int have_error = 0;
static int error_quiet = 0;
static int log_quiet = 0;
static int status_open = 0; /* a status line is on the terminal without its newline */
static int status_mode = -1; /* -1: when standard output is a terminal; 0: never; 1: always */
static char context[256];    /* appended to the message: where the run is */

void pf_error_context(const char *fmt, ...) {
  context[0] = '\0';
  if (!fmt) return;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(context, sizeof context, fmt, ap);
  va_end(ap);
}

/* End an open status line before other output. */
static void close_status(void) {
  if (status_open) fputc('\n', stdout), fflush(stdout);
  status_open = 0;
}

int pf_error_raise(int code, const char *file, int line, const char *func, const char *fmt, ...) {
  if (have_error) return code; /* keep the first, innermost message */
  have_error = 1;
  va_list ap;
  va_start(ap, fmt);
  char msg[1536];
  int len = vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (context[0] && len >= 0 && (size_t)len < sizeof msg) snprintf(msg + len, sizeof msg - len, " %s", context);
  int rank = pf_comm_rank();
  if (pf_comm_size() > 1)
    snprintf(first_message, sizeof first_message, "error (rank %d): %s", rank, msg);
  else
    snprintf(first_message, sizeof first_message, "error: %s", msg);
  if (!error_quiet) {
    close_status();
    fprintf(stderr, "perifem %s\n", first_message);
    if (getenv("PERIFEM_DEBUG")) fprintf(stderr, "  raised at %s:%d in %s()\n", file, line, func);
    fflush(stderr);
  }
  return code;
}

/* The lowest failing rank's message goes to every rank (a rank that has no error of its own yet
 * raises it too), so that all of them stop together at the same point and say the same. */
int pf_error_agree(int ok, int code, const char *file, int line, const char *func, const char *message) {
  int rank = pf_comm_rank(), first = ok ? INT_MAX : rank;
  if (pf_comm_size() > 1) MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == INT_MAX) return 0;
  char text[1024];
  snprintf(text, sizeof text, "%s", message ? message : "");
  if (pf_comm_size() > 1) MPI_Bcast(text, (int)sizeof text, MPI_CHAR, first, MPI_COMM_WORLD);
  if (first != rank && pf_comm_size() > 1)
    return pf_error_raise(code, file, line, func, "%s (found by rank %d)", text, first);
  return pf_error_raise(code, file, line, func, "%s", text);
}

const char *pf_error_message(void) { return have_error ? first_message : ""; }

void pf_error_clear(void) {
  have_error = 0;
  first_message[0] = '\0';
}

void pf_error_set_quiet(int quiet) { error_quiet = quiet; }

void pf_log_set_quiet(int quiet) { log_quiet = quiet; }

/* One message, one line: a message that does not end its line is given its newline, so that the
 * next message never continues it. */
void pf_log(const char *fmt, ...) {
  if (log_quiet || pf_comm_rank() != 0) return;
  close_status();
  char text[1024], *line = text;
  va_list ap, again;
  va_start(ap, fmt);
  va_copy(again, ap);
  const int len = vsnprintf(text, sizeof text, fmt, ap);
  va_end(ap);
  if (len >= (int)sizeof text && (line = malloc((size_t)len + 1))) vsnprintf(line, (size_t)len + 1, fmt, again);
  va_end(again);
  if (len > 0) {
    if (!line) line = text; /* (out of memory: the message cut short) */
    fputs(line, stdout);
    if (line[strlen(line) - 1] != '\n') fputc('\n', stdout);
  }
  if (line != text) free(line);
  fflush(stdout);
}

void pf_log_set_status(int mode) { status_mode = mode; }

int pf_log_terminal(void) {
  return !log_quiet && pf_comm_rank() == 0 && (status_mode < 0 ? isatty(fileno(stdout)) : status_mode);
}

void pf_log_status(const char *fmt, ...) {
  if (!pf_log_terminal()) return;
  va_list ap;
  va_start(ap, fmt);
  fputc('\r', stdout);
  vfprintf(stdout, fmt, ap);
  va_end(ap);
  fputs("\033[K", stdout); /* clear what a longer previous line left */
  fflush(stdout);
  status_open = 1;
}

double pf_memory_limit(void) {
  long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  double limit = pages > 0 && page > 0 ? (double)pages * (double)page : 1e18;
  double used = 0; /* the address space in use now (libraries, the deck, ...) */
  FILE *fp = fopen("/proc/self/statm", "r");
  unsigned long vm = 0;
  if (fp && fscanf(fp, "%lu", &vm) == 1 && page > 0) used = (double)vm * (double)page;
  if (fp) fclose(fp);
  const int which[2] = {RLIMIT_AS, RLIMIT_DATA};
  for (int k = 0; k < 2; k++) {
    struct rlimit rl;
    if (getrlimit(which[k], &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) {
      double left = (double)rl.rlim_cur - (k == 0 ? used : 0);
      if (left < limit) limit = left > 0 ? left : 0;
    }
  }
  return limit;
}

double pf_memory_peak(void) {
  struct rusage ru;
  return getrusage(RUSAGE_SELF, &ru) ? 0 : (double)ru.ru_maxrss * 1024.0; /* (KB on Linux) */
}

double pf_memory_resident(void) {
  const long page = sysconf(_SC_PAGE_SIZE);
  unsigned long size = 0, resident = 0;
  FILE *fp = fopen("/proc/self/statm", "r");
  const int got = fp ? fscanf(fp, "%lu %lu", &size, &resident) : 0;
  if (fp) fclose(fp);
  return got == 2 && page > 0 ? (double)resident * (double)page : 0.0;
}

void pf_memory_trim(void) {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}
