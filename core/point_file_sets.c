/* Peridigm's node-set text files for a point file's points (geometry.node_set_files): each file
 * lists point numbers, counting from 1 in the point file's order, separated by white space
 * ('#' starts a comment, as in Peridigm's text discretization); it becomes a node set of the
 * cloud named after the file without its folder and extension, for regions
 * {shape: node_set, set: <name>}. A number out of range or not an integer is an error naming
 * the file and the line. After a block filter (geometry.block) the sets keep the points taken. */
#include "core/core.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

/* "dir/node_set_1.txt" -> "node_set_1" */
static void set_name(const char *file, char *name, size_t len) {
  const char *slash = strrchr(file, '/'), *base = slash ? slash + 1 : file, *dot = strrchr(base, '.');
  const size_t n = dot && dot != base ? (size_t)(dot - base) : strlen(base);
  snprintf(name, len, "%.*s", (int)(n < len ? n : len - 1), base);
}

/* The numbers of one line (a comment cut off) appended to ids; 1-based numbers in [1, n]. On a
 * bad one: -1 and why. */
static int line_ids(const char *path, long line, char *text, pf_int n, pf_gid **ids, pf_gid *count,
                    pf_gid *cap, char *why, size_t len) {
  char *hash = strchr(text, '#'), *p = text, *end;
  if (hash) *hash = '\0';
  for (;;) {
    p += strspn(p, " \t\r\n,");
    if (!*p) return 0;
    errno = 0;
    const long long v = strtoll(p, &end, 10);
    if (end == p || (*end && !strchr(" \t\r\n,", *end)) || errno) {
      snprintf(why, len, "%s:%ld: '%.*s' is not a point number (integers counting from 1)", path, line,
               (int)(strcspn(p, " \t\r\n,") < 40 ? strcspn(p, " \t\r\n,") : 40), p);
      return -1;
    }
    if (v < 1 || v > (long long)n) {
      snprintf(why, len, "%s:%ld: point number %lld is outside the point file's 1..%" PF_INT_FMT, path, line, v, n);
      return -1;
    }
    if (*count == *cap) {
      *cap = *cap ? 2 * *cap : 1024;
      pf_gid *grown = realloc(*ids, sizeof **ids * (size_t)*cap);
      if (!grown) return snprintf(why, len, "%s: out of memory for %lld point numbers", path, (long long)*cap), -1;
      *ids = grown;
    }
    (*ids)[(*count)++] = (pf_gid)(v - 1);
    p = end;
  }
}

static int read_set(const char *path, pf_int n, pf_gid **ids, pf_gid *count, char *why, size_t len) {
  FILE *f = fopen(path, "r");
  if (!f) return snprintf(why, len, "cannot open the node-set file '%s': %s", path, strerror(errno)), -1;
  char buf[4096];
  long line = 0;
  pf_gid cap = 0;
  int ierr = 0;
  *ids = NULL, *count = 0;
  while (!ierr && fgets(buf, sizeof buf, f)) {
    line++;
    ierr = line_ids(path, line, buf, n, ids, count, &cap, why, len);
  }
  fclose(f);
  if (!ierr && *count == 0) ierr = -1, snprintf(why, len, "%s: no point numbers (an empty node set)", path);
  if (ierr) PF_FREE(*ids);
  return ierr;
}

static int add_set(pf_point_cloud *pc, const char *name, pf_gid *ids, pf_gid count) {
  pf_point_sets t = {.n = pc->nsets, .set = pc->sets};
  const int ierr = pf_point_sets_add(&t, name, -1, 0, ids, count);
  pc->sets = t.set, pc->nsets = t.n;
  return ierr;
}

int pf_point_file_sets(const pf_deck *d, const pf_node *g, pf_point_cloud *pc) {
  const pf_node *list = pf_node_get(g, "node_set_files");
  for (int k = 0; list && k < pf_node_count(list); k++) {
    const pf_node *it = pf_node_item(list, k);
    char path[4096], name[64];
    pf_deck_relative_path(d, pf_node_text(it), path, sizeof path);
    set_name(pf_node_text(it), name, sizeof name);
    for (int q = 0; q < pc->nsets; q++)
      if (!strcmp(pc->sets[q].name, name))
        return pf_deck_error(d, it, "node_set_files", "two node-set files make a set named '%s'", name);
    pf_gid *ids = NULL, count = 0;
    char why[4400];
    if (read_set(path, pc->n, &ids, &count, why, sizeof why)) return pf_deck_error(d, it, "node_set_files", "%s", why);
    const int ierr = add_set(pc, name, ids, count);
    free(ids);
    PF_CALL(ierr);
  }
  return 0;
}

void pf_point_file_sets_keep(pf_point_cloud *pc, const pf_int *new_index) {
  for (int q = 0; q < pc->nsets; q++) {
    pf_point_set *s = &pc->sets[q];
    pf_gid k = 0;
    for (pf_gid i = 0; i < s->n; i++) /* ascending in, ascending out */
      if (new_index[s->gid[i]] >= 0) s->gid[k++] = new_index[s->gid[i]];
    s->n = k;
  }
}
