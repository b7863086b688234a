/* What made a run's output files, written into them (Exodus QA and info records, HDF5 history
 * attributes): the deck's title, perifem's version and the git commit it was built from, the date,
 * the number of ranks, the command line, and the text of the deck and of every file it included,
 * so that an output file says how to make it again. */
#include "sim/sim_impl.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "git_version.h"

static int add_line(pf_sim *sim, const char *text, size_t len) {
  char **grown = realloc(sim->prov_lines, sizeof *grown * (size_t)(sim->prov.nlines + 1));
  PF_CHECK(grown, PF_ERR_MEMORY, "out of memory for the outputs' provenance");
  sim->prov_lines = grown;
  PF_CHECK(grown[sim->prov.nlines] = strndup(text, len), PF_ERR_MEMORY, "out of memory for the outputs' provenance");
  sim->prov.nlines++;
  return 0;
}

static int add_format(pf_sim *sim, const char *fmt, const char *a, const char *b) {
  char line[4600];
  snprintf(line, sizeof line, fmt, a, b);
  return add_line(sim, line, strlen(line));
}

/* A header line, then the file's lines as they are (a file that cannot be read says so). */
static int add_file(pf_sim *sim, const char *what, const char *path) {
  PF_CALL(add_format(sim, "---- %s %s ----", what, path));
  FILE *fp = fopen(path, "rb");
  if (!fp) return add_format(sim, "(cannot be read: %s%s)", strerror(errno), "");
  char buf[4096];
  int ierr = 0;
  while (!ierr && fgets(buf, sizeof buf, fp)) {
    size_t len = strlen(buf);
    while (len && (buf[len - 1] == '\n' || buf[len - 1] == '\r')) len--;
    ierr = add_line(sim, buf, len);
  }
  fclose(fp);
  return ierr;
}

/* A deck given as text (the library): its lines under the name it stands for. */
static int add_text(pf_sim *sim, const char *what, const char *path, const char *text) {
  PF_CALL(add_format(sim, "---- %s %s ----", what, path));
  for (const char *line = text; *line;) {
    size_t len = strcspn(line, "\r\n");
    PF_CALL(add_line(sim, line, len));
    line += len;
    if (*line == '\r') line++;
    if (*line == '\n') line++;
  }
  return 0;
}

int pf_sim_provenance(pf_sim *sim) {
  const char *title = NULL;
  PF_CALL(pf_deck_string(sim->deck, pf_deck_root(sim->deck), "title", &title));
  snprintf(sim->title, sizeof sim->title, "%s", title && title[0] ? title : pf_deck_path(sim->deck));
  sim->prov.title = sim->title;
  char when[64], ranks[32];
  const time_t now = time(NULL);
  struct tm utc;
  gmtime_r(&now, &utc);
  strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S UTC", &utc);
  snprintf(ranks, sizeof ranks, "%d", pf_comm_size());
  PF_CALL(add_format(sim, "perifem %s, git %s", PERIFEM_VERSION, PERIFEM_GIT));
  PF_CALL(add_format(sim, "run %s on %s MPI ranks", when, ranks));
  PF_CALL(add_format(sim, "command: %s%s", sim->opt.command_line ? sim->opt.command_line : "(not given)", ""));
  if (sim->opt.deck_text) PF_CALL(add_text(sim, "deck (text)", pf_deck_path(sim->deck), sim->opt.deck_text));
  else PF_CALL(add_file(sim, "deck", pf_deck_path(sim->deck)));
  for (int k = 0; pf_deck_included(sim->deck, k); k++) PF_CALL(add_file(sim, "included", pf_deck_included(sim->deck, k)));
  sim->prov.lines = (const char *const *)sim->prov_lines;
  return 0;
}

void pf_sim_provenance_free(pf_sim *sim) {
  for (int k = 0; k < sim->prov.nlines; k++) free(sim->prov_lines[k]);
  PF_FREE(sim->prov_lines);
  sim->prov.nlines = 0;
}
