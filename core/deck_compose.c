/* Composing a deck from its parts, after the YAML is read and before it is validated:
 *  1. include: [a.yaml, ...] — each file (relative to the including file's folder, itself able to
 *     include, 8 levels at most, no cycles) is merged in, in order, then the including file:
 *     mappings merge key by key, lists are joined (the included items first), and a value given
 *     twice is an error naming both places;
 *  2. --set a.b.c=value overrides from the command line (a list item by its index or its name:),
 *     each applied or refused: a parameter must be one the deck declares, include: cannot be set;
 *  3. parameters: {name: value or expression of the earlier ones}, then every ${expression} in a
 *     value is replaced by its value (written back exactly, %.17g), so a deck with parameters
 *     reads the same numbers as the deck written out; inside x, y, z, t expressions the names
 *     can also be used bare (core/expr.c defines them).
 * Every node keeps the file it came from, so errors name the included file or the override. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "core/deck_impl.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_INCLUDE_DEPTH = 8 };

static pf_node *new_node(node_kind kind, const char *file) {
  pf_node *n = calloc(1, sizeof *n);
  if (n) n->kind = kind, n->file = file;
  return n;
}

static void where(const pf_deck *d, const pf_node *n, char *out, size_t len) { pf_node_where(d, n, out, len); }

/* Append the pair (key, value) to a mapping (takes value; copies key). */
static int map_append(pf_node *map, const char *key, int line, int col, pf_node *value) {
  const int n = map->n + 1;
  pf_node **items = realloc(map->items, sizeof *items * (size_t)n);
  if (items) map->items = items;
  char **keys = items ? realloc(map->keys, sizeof *keys * (size_t)n) : NULL;
  if (keys) map->keys = keys;
  int *kl = keys ? realloc(map->key_line, sizeof *kl * (size_t)n) : NULL;
  if (kl) map->key_line = kl;
  int *kc = kl ? realloc(map->key_col, sizeof *kc * (size_t)n) : NULL;
  if (kc) map->key_col = kc;
  char *copy = kc ? strdup(key) : NULL;
  PF_CHECK(copy, PF_ERR_MEMORY, "out of memory composing the deck");
  map->items[map->n] = value, map->keys[map->n] = copy;
  map->key_line[map->n] = line, map->key_col[map->n] = col;
  map->n = n;
  return 0;
}

/* ---- 1. include ---------------------------------------------------------------------- */

/* Move src's pairs into dst (src is left empty): see the file's comment. */
static int merge(pf_deck *d, pf_node *dst, pf_node *src) {
  for (int i = 0; i < src->n; i++) {
    pf_node *v = src->items[i];
    int j = 0;
    while (j < dst->n && strcmp(dst->keys[j], src->keys[i])) j++;
    if (j == dst->n) {
      PF_CALL(map_append(dst, src->keys[i], src->key_line[i], src->key_col[i], v));
      src->items[i] = NULL;
      continue;
    }
    pf_node *u = dst->items[j];
    if (u->kind == NODE_MAP && v->kind == NODE_MAP) {
      PF_CALL(merge(d, u, v));
    } else if (u->kind == NODE_SEQ && v->kind == NODE_SEQ) {
      pf_node **items = realloc(u->items, sizeof *items * (size_t)(u->n + v->n + 1));
      PF_CHECK(items, PF_ERR_MEMORY, "out of memory composing the deck");
      memcpy(items + u->n, v->items, sizeof *items * (size_t)v->n);
      u->items = items, u->n += v->n, v->n = 0;
    } else {
      char a[512], b[512];
      where(d, u, a, sizeof a), where(d, v, b, sizeof b);
      PF_CHECK(0, PF_ERR_INPUT, "%s: key '%s': given again at %s (an included value can be added to, not "
               "replaced: use --set to change it)", b, src->keys[i], a);
    }
  }
  return 0;
}

/* The file named by an include item, relative to the including file's folder. */
static void include_path(const char *from, const char *name, char *out, size_t len) {
  const char *slash = strrchr(from, '/');
  if (name[0] == '/' || !slash) snprintf(out, len, "%s", name);
  else snprintf(out, len, "%.*s/%s", (int)(slash - from), from, name);
}

static int expand_includes(pf_deck *d, pf_node **root, char **chain, int depth);

/* The merged tree of the files root includes, then root itself: the new *root. */
static int include_all(pf_deck *d, pf_node **root, const pf_node *list, char **chain, int depth) {
  char pos[512];
  where(d, list, pos, sizeof pos);
  PF_CHECK(list->kind == NODE_SEQ, PF_ERR_INPUT, "%s: key 'include': expected a list of file names ([a.yaml, ...])",
           pos);
  pf_node *base = new_node(NODE_MAP, (*root)->file);
  PF_CHECK(base, PF_ERR_MEMORY, "out of memory composing the deck");
  int ierr = 0;
  for (int k = 0; k < list->n && !ierr; k++) {
    const pf_node *item = list->items[k];
    char path[PATH_MAX];
    where(d, item, pos, sizeof pos);
    if (item->kind != NODE_SCALAR) {
      ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__, "%s: key 'include': expected a file name", pos);
      break;
    }
    include_path((*root)->file, item->text, path, sizeof path);
    if (d->nincluded == PF_DECK_MAX_INCLUDES) {
      ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__, "%s: key 'include': more than %d included files",
                            pos, PF_DECK_MAX_INCLUDES);
      break;
    }
    FILE *fp = fopen(path, "rb");
    if (!fp) {
      ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__, "%s: key 'include': cannot open '%s': %s",
                            pos, path, strerror(errno));
      break;
    }
    fclose(fp);
    pf_node *part = NULL;
    ierr = pf_deck_parse_file(d, path, &part);
    const char **grown = ierr ? NULL : realloc(d->included, sizeof *grown * (size_t)(d->nincluded + 1));
    if (grown) d->included = grown, d->included[d->nincluded++] = d->names[d->nnames - 1];
    else if (!ierr) ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory");
    if (!ierr) ierr = expand_includes(d, &part, chain, depth + 1);
    if (!ierr) ierr = merge(d, base, part);
    pf_deck_node_free(part);
  }
  if (!ierr) ierr = merge(d, base, *root);
  pf_deck_node_free(*root);
  *root = base;
  return ierr;
}

/* Remove pair i from a mapping; its value is returned, the key's position kept in line, col. */
static pf_node *map_take(pf_node *map, int i, int *line, int *col) {
  pf_node *v = map->items[i];
  *line = map->key_line[i], *col = map->key_col[i];
  free(map->keys[i]);
  for (int j = i + 1; j < map->n; j++) {
    map->items[j - 1] = map->items[j], map->keys[j - 1] = map->keys[j];
    map->key_line[j - 1] = map->key_line[j], map->key_col[j - 1] = map->key_col[j];
  }
  map->n--;
  return v;
}

/* Replace *root by itself merged after the files its include: names (the list is put back at
 * the end, for the record). chain holds the real paths of the including files, to refuse a
 * cycle. */
static int expand_includes(pf_deck *d, pf_node **root, char **chain, int depth) {
  int at = 0, line, col;
  while (at < (*root)->n && strcmp((*root)->keys[at], "include")) at++;
  if (at == (*root)->n) return 0;
  char pos[512];
  where(d, (*root)->items[at], pos, sizeof pos);
  PF_CHECK(depth < MAX_INCLUDE_DEPTH, PF_ERR_INPUT, "%s: key 'include': includes nested deeper than %d files",
           pos, MAX_INCLUDE_DEPTH);
  chain[depth] = realpath((*root)->file, NULL);
  PF_CHECK(chain[depth], PF_ERR_INPUT, "%s: cannot resolve '%s': %s", pos, (*root)->file, strerror(errno));
  int ierr = 0;
  for (int k = 0; k < depth && !ierr; k++)
    if (!strcmp(chain[k], chain[depth]))
      ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                            "%s: key 'include': '%s' includes itself (a cycle of %d file%s)", pos, (*root)->file, depth - k,
                            depth - k > 1 ? "s" : "");
  pf_node *list = map_take(*root, at, &line, &col);
  if (!ierr) ierr = include_all(d, root, list, chain, depth);
  if (!ierr) ierr = map_append(*root, "include", line, col, list), list = NULL;
  pf_deck_node_free(list);
  free(chain[depth]), chain[depth] = NULL;
  return ierr;
}

/* ---- 2. --set overrides ---------------------------------------------------------------- */

/* The item of a list named by part: its index, or the item whose name: is part; -1 if none. */
static int list_index(const pf_node *seq, const char *part) {
  char *end;
  long k = strtol(part, &end, 10);
  if (*part && !*end) return k >= 0 && k < seq->n ? (int)k : -1;
  for (int i = 0; i < seq->n; i++) {
    const pf_node *name = pf_node_get(seq->items[i], "name");
    if (name && name->kind == NODE_SCALAR && !strcmp(name->text, part)) return i;
  }
  return -1;
}

/* Put value at the path parts[0..nparts) below root: a missing mapping key is added (mappings
 * on the way too), a list item must exist, a single value has nothing below it. */
static int set_path(pf_node *root, char **parts, int nparts, pf_node **value, const char *origin) {
  pf_node *at = root;
  for (int p = 0; p < nparts; p++) {
    const char *part = parts[p];
    const int last = p == nparts - 1;
    if (at->kind == NODE_SEQ) {
      const int k = list_index(at, part);
      PF_CHECK(k >= 0, PF_ERR_INPUT, "%s: '%s' names no item of the list (give its index, 0 to %d, or its name)",
               origin, part, at->n - 1);
      if (last) pf_deck_node_free(at->items[k]), at->items[k] = *value, *value = NULL;
      else at = at->items[k];
      continue;
    }
    PF_CHECK(at->kind == NODE_MAP, PF_ERR_INPUT, "%s: '%s' is below a single value ('%s'), not a mapping or a list",
             origin, part, at->text ? at->text : "");
    int j = 0;
    while (j < at->n && strcmp(at->keys[j], part)) j++;
    if (j == at->n) {
      pf_node *fresh = last ? *value : new_node(NODE_MAP, origin);
      PF_CHECK(fresh, PF_ERR_MEMORY, "out of memory composing the deck");
      if (last) *value = NULL;
      PF_CALL(map_append(at, part, 0, 0, fresh));
    } else if (last) {
      pf_deck_node_free(at->items[j]), at->items[j] = *value, *value = NULL;
    }
    at = at->items[j];
  }
  return 0;
}

/* A parameter set by --set must be one the deck declares: a misspelt name would otherwise add
 * an unused parameter and leave the run unchanged. */
static int check_parameter(const pf_deck *d, const char *name, const char *origin) {
  const pf_node *map = pf_node_get(d->root, "parameters");
  PF_CHECK(map && map->kind == NODE_MAP && map->n > 0, PF_ERR_INPUT,
           "%s: the deck declares no parameters: (a parameter set from the command line must be declared in "
           "the deck, with its default value)", origin);
  const char *best = NULL;
  int bestd = 1 << 30;
  char known[1024] = "";
  size_t len = 0;
  for (int i = 0; i < map->n; i++) {
    if (!strcmp(map->keys[i], name)) return 0;
    const int dist = pf_edit_distance(name, map->keys[i]);
    if (dist < bestd) bestd = dist, best = map->keys[i];
    if (len < sizeof known) len += (size_t)snprintf(known + len, sizeof known - len, "%s%s", i ? ", " : "", map->keys[i]);
  }
  char hint[256] = "";
  if (bestd <= 3) snprintf(hint, sizeof hint, " — did you mean '%s'?", best);
  return pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__, "%s: '%s' is not one of the deck's parameters (%s)%s",
                        origin, name, known, hint);
}

static int apply_override(pf_deck *d, const char *set) {
  char origin[600];
  snprintf(origin, sizeof origin, "--set %s", set);
  for (char *c = origin; *c; c++) /* (a value of several lines: its name in messages stays one line) */
    if (*c == '\n' || *c == '\r' || *c == '\t') *c = ' ';
  const char *eq = strchr(set, '=');
  PF_CHECK(eq && eq > set && eq[1], PF_ERR_INPUT, "%s: expected KEY.PATH=VALUE (e.g. --set time.final_time=5e-6)",
           origin);
  enum { MAX_PARTS = 64 };
  char *path = strndup(set, (size_t)(eq - set)), *parts[MAX_PARTS];
  PF_CHECK(path, PF_ERR_MEMORY, "out of memory");
  int nparts = 0, ierr = 0;
  for (char *part = path, *dot;; part = dot + 1) {
    dot = strchr(part, '.');
    if (dot) *dot = '\0';
    if (!*part || nparts == MAX_PARTS) {
      ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                            "%s: %s in the key path (KEY.PATH is keys and list items joined by single dots, "
                            "e.g. bodies.0.horizon)", origin, *part ? "more than 64 parts" : "an empty part");
      break;
    }
    parts[nparts++] = part;
    if (!dot) break;
  }
  if (!ierr && !strcmp(parts[0], "include"))
    ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                          "%s: include: cannot be set from the command line: the included files are merged "
                          "before the overrides are applied (write a deck whose include: names the files)", origin);
  if (!ierr && !strcmp(parts[0], "parameters") && nparts > 1) ierr = check_parameter(d, parts[1], origin);
  pf_node *value = NULL;
  if (!ierr) ierr = pf_deck_parse_value(d, origin, eq + 1, &value);
  if (!ierr) ierr = set_path(d->root, parts, nparts, &value, d->names[d->nnames - 1]);
  pf_deck_node_free(value);
  free(path);
  return ierr;
}

/* ---- 3. parameters and ${...} ------------------------------------------------------------ */

static int read_parameters(pf_deck *d) {
  const pf_node *map = pf_node_get(d->root, "parameters");
  if (!map) return 0;
  if (map->kind != NODE_MAP) return pf_deck_error(d, map, "parameters", "expected a mapping of names to values");
  PF_MALLOC(d->param_name, map->n + 1);
  PF_MALLOC(d->param_value, map->n + 1);
  for (int k = 0; k < map->n; k++) {
    const pf_node *v = map->items[k];
    const char *name = map->keys[k];
    int ok = (isalpha((unsigned char)name[0]) || name[0] == '_') && strcmp(name, "x") && strcmp(name, "y") &&
             strcmp(name, "z") && strcmp(name, "t");
    for (const char *c = name; ok && *c; c++) ok = isalnum((unsigned char)*c) || *c == '_';
    if (!ok)
      return pf_deck_error(d, v, name, "a parameter's name is a letter or '_' followed by letters, digits or '_', "
                           "and not x, y, z or t (the position and the time in expressions)");
    if (v->kind != NODE_SCALAR)
      return pf_deck_error(d, v, name, "a parameter is a number or an expression of the parameters above it");
    PF_CALL(pf_expr_constant(d, v, map->keys[k], v->text, &d->param_value[k])); /* the k above it */
    d->param_name[k] = strdup(map->keys[k]);
    PF_CHECK(d->param_name[k], PF_ERR_MEMORY, "out of memory");
    d->nparams = k + 1;
  }
  return 0;
}

/* Append the n characters at s to the text *buf of length *len in *cap bytes, growing it. */
static int append(char **buf, size_t *len, size_t *cap, const char *s, size_t n) {
  if (*len + n + 1 > *cap) {
    const size_t want = 2 * (*len + n + 1);
    char *b = realloc(*buf, want);
    PF_CHECK(b, PF_ERR_MEMORY, "out of memory substituting ${...} (%zu bytes)", want);
    *buf = b, *cap = want;
  }
  memcpy(*buf + *len, s, n);
  *len += n;
  (*buf)[*len] = '\0';
  return 0;
}

/* Replace each ${expression} in a scalar by its value; expressions and values of any length. */
static int substitute_scalar(pf_deck *d, pf_node *n, const char *key) {
  const char *mark = strstr(n->text, "${");
  if (!mark) return 0;
  const int whole = mark == n->text;
  char *out = NULL, *expr = NULL;
  size_t len = 0, cap = 0;
  const char *from = n->text;
  int ierr = 0;
  for (; mark; mark = strstr(from, "${")) {
    const char *close = strchr(mark, '}');
    if (!close) {
      ierr = pf_deck_error(d, n, key, "'${' without its closing '}' in '%s'", n->text);
      break;
    }
    const size_t elen = (size_t)(close - mark - 2);
    char *e = realloc(expr, elen + 1);
    if (!e) {
      ierr = pf_error_raise(PF_ERR_MEMORY, __FILE__, __LINE__, __func__, "out of memory for a ${...} of %zu characters",
                            elen);
      break;
    }
    expr = e;
    memcpy(expr, mark + 2, elen);
    expr[elen] = '\0';
    double v;
    char num[32];
    if ((ierr = pf_expr_constant(d, n, key, expr, &v))) break;
    snprintf(num, sizeof num, "%.17g", v);
    if ((ierr = append(&out, &len, &cap, from, (size_t)(mark - from)))) break;
    if ((ierr = append(&out, &len, &cap, num, strlen(num)))) break;
    from = close + 1;
  }
  if (!ierr) ierr = append(&out, &len, &cap, from, strlen(from));
  free(expr);
  if (ierr) {
    free(out);
    return ierr;
  }
  const int alone = whole && !*from; /* "${v0}" alone is the number (from points into the old text) */
  free(n->text);
  n->text = out;
  if (alone) n->quoted = 0;
  return 0;
}

static int substitute(pf_deck *d, pf_node *n, const char *key) {
  if (n->kind == NODE_SCALAR) return substitute_scalar(d, n, key);
  for (int i = 0; i < n->n; i++) {
    if (n == d->root && !strcmp(n->keys[i], "parameters")) continue;
    PF_CALL(substitute(d, n->items[i], n->kind == NODE_MAP ? n->keys[i] : key));
  }
  return 0;
}

int pf_deck_compose(pf_deck *d, const char *const *sets, int nsets) {
  char *chain[MAX_INCLUDE_DEPTH] = {0};
  PF_CALL(expand_includes(d, &d->root, chain, 0));
  for (int k = 0; k < nsets; k++) PF_CALL(apply_override(d, sets[k]));
  PF_CALL(read_parameters(d));
  return substitute(d, d->root, "");
}
