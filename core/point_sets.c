/* Named point sets of the bodies: a mesh's node sets, the nodes of its side sets' faces, an
 * Exodus discretization's node sets, each held as the ascending global ids of its points. Every
 * rank holds the whole table (the meshes are whole on every rank at set-up), so a region that
 * names a set selects its owned points by global id wherever the partition put them. */
#include "core/core.h"

#include <stdlib.h>
#include <string.h>

static int by_gid(const void *a, const void *b) {
  const pf_gid x = *(const pf_gid *)a, y = *(const pf_gid *)b;
  return (x > y) - (x < y);
}

int pf_point_sets_add(pf_point_sets *t, const char *name, int body, int side, const pf_gid *id, pf_gid n) {
  pf_point_set *grown = realloc(t->set, sizeof *grown * (size_t)(t->n + 1));
  PF_CHECK(grown, PF_ERR_MEMORY, "out of memory for %d point sets", t->n + 1);
  t->set = grown;
  pf_point_set *s = &grown[t->n];
  memset(s, 0, sizeof *s);
  snprintf(s->name, sizeof s->name, "%s", name);
  s->body = body;
  s->side = side;
  PF_MALLOC(s->gid, n + 1);
  t->n++;
  if (n) memcpy(s->gid, id, sizeof *id * (size_t)n);
  qsort(s->gid, (size_t)n, sizeof *s->gid, by_gid);
  pf_gid k = 0;
  for (pf_gid i = 0; i < n; i++)
    if (k == 0 || s->gid[i] != s->gid[k - 1]) s->gid[k++] = s->gid[i];
  s->n = k;
  return 0;
}

void pf_point_sets_free(pf_point_sets *t) {
  for (int k = 0; t->set && k < t->n; k++) free(t->set[k].gid);
  PF_FREE(t->set);
  t->n = 0;
}

int pf_point_set_has(const pf_point_set *s, pf_gid gid) {
  return bsearch(&gid, s->gid, (size_t)s->n, sizeof gid, by_gid) != NULL;
}

static const char *set_kind(int side) { return side ? "side set" : "node set"; }

static const char *body_of(const pf_point_sets *t, int body) {
  return t->body_name && body >= 0 ? t->body_name[body] : "?";
}

/* "'top' (body plate), 'bottom' (body plate)" or "none" */
static void known_sets(const pf_point_sets *t, int side, int body, char *out, size_t len) {
  snprintf(out, len, "none");
  size_t used = 0;
  for (int k = 0; t && k < t->n; k++) {
    const pf_point_set *s = &t->set[k];
    if (s->side != side || (body >= 0 && s->body != body)) continue;
    int w = snprintf(out + used, len - used, "%s'%s' (body %s)", used ? ", " : "", s->name, body_of(t, s->body));
    if (w < 0 || (size_t)w >= len - used) break;
    used += (size_t)w;
  }
}

int pf_point_sets_find(const pf_point_sets *t, const pf_deck *d, const pf_node *key_node, const char *key,
                       const char *name, int side, int body, const pf_point_set **out) {
  *out = NULL;
  int found = 0, other = -1;
  /* with no body named, an empty set (a Peridigm node set on another block's points, read
   * with each body's blocks) gives way to a set of the same name that holds points */
  for (int pass = body >= 0; pass < 2 && !found; pass++)
    for (int k = 0; t && k < t->n; k++) {
      const pf_point_set *s = &t->set[k];
      if (s->side != side || strcmp(s->name, name) || (body >= 0 && s->body != body) || (!pass && !s->n)) continue;
      if (found++) other = s->body;
      else *out = s;
    }
  if (found == 1) return 0;
  char known[2048];
  known_sets(t, side, body, known, sizeof known);
  if (found > 1)
    return pf_deck_error(d, key_node, key, "the %s '%s' is in bodies '%s' and '%s': say which with the 'body' key",
                         set_kind(side), name, body_of(t, (*out)->body), body_of(t, other));
  *out = NULL;
  if (body >= 0)
    return pf_deck_error(d, key_node, key, "body '%s' has no %s '%s' (its %ss: %s)", body_of(t, body), set_kind(side),
                         name, set_kind(side), known);
  return pf_deck_error(d, key_node, key, "no body has a %s '%s' (the %ss: %s)", set_kind(side), name, set_kind(side),
                       known);
}
