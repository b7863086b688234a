/* Checking a deck mapping against a schema table (pf_key) and reading typed values.
 * An unknown key is reported with the closest known key (Levenshtein distance). */
#include "core/deck_impl.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

int pf_edit_distance(const char *a, const char *b) {
  size_t la = strlen(a), lb = strlen(b);
  if (la > 63 || lb > 63) return 99;
  int row[64];
  for (size_t j = 0; j <= lb; j++) row[j] = (int)j;
  for (size_t i = 1; i <= la; i++) {
    int diag = row[0];
    row[0] = (int)i;
    for (size_t j = 1; j <= lb; j++) {
      int up = row[j], sub = diag + (a[i - 1] != b[j - 1]);
      int best = up + 1 < row[j - 1] + 1 ? up + 1 : row[j - 1] + 1;
      row[j] = sub < best ? sub : best;
      diag = up;
    }
  }
  return row[lb];
}

/* Where key i of a map was given (its value's file: a key and its value come from one file). */
static void key_where(const pf_deck *d, const pf_node *map, int i, char *out, size_t len) {
  const char *file = map->items[i]->file ? map->items[i]->file : d->path;
  if (map->key_line[i] > 0) snprintf(out, len, "%s:%d:%d", file, map->key_line[i], map->key_col[i]);
  else snprintf(out, len, "%s", file);
}

static int key_error(const pf_deck *d, const pf_node *map, int i, const char *fmt, const char *a,
                     const char *b) {
  char where[512];
  key_where(d, map, i, where, sizeof where);
  return pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__, "%s: key '%s': %s%s%s", where,
                        map->keys[i], fmt, a, b);
}

static int unknown_key(const pf_deck *d, const pf_node *map, int i, const pf_key *table,
                       const char *where) {
  const char *best = NULL;
  int bestd = 1 << 30;
  char known[1024] = "";
  for (const pf_key *k = table; k->name; k++) {
    int dist = pf_edit_distance(map->keys[i], k->name);
    if (dist < bestd) bestd = dist, best = k->name;
    if (strlen(known) + strlen(k->name) + 3 < sizeof known) {
      strcat(known, known[0] ? ", " : "");
      strcat(known, k->name);
    }
  }
  char msg[1200];
  if (best && bestd <= 3) snprintf(msg, sizeof msg, "unknown key in %s — did you mean '%s'?", where, best);
  else snprintf(msg, sizeof msg, "unknown key in %s (known keys: %s)", where, known);
  return key_error(d, map, i, msg, "", "");
}

static int parse_real(const char *s, double *v) {
  if (!s || !*s) return 0;
  char *end;
  errno = 0;
  *v = strtod(s, &end);
  while (*end == ' ') end++;
  return *end == '\0' && errno == 0 && isfinite(*v);
}

static int parse_bool(const char *s, int *b) {
  if (!s) return 0;
  if (!strcasecmp(s, "true") || !strcasecmp(s, "yes") || !strcasecmp(s, "on")) return *b = 1, 1;
  if (!strcasecmp(s, "false") || !strcasecmp(s, "no") || !strcasecmp(s, "off")) return *b = 0, 1;
  return 0;
}

static const char *type_name(pf_key_type t) {
  static const char *names[] = {"a real number", "an integer", "true or false", "a string",
                                "a list of 3 reals [x, y, z]",
                                "a list of 3 expressions in x, y, z, t",
                                "a real or an expression in x, y, z",
                                "a mapping", "a list of mappings", "a list of strings",
                                "a mapping of names",
                                "three rows of 3 reals [[a, b, c], [d, e, f], [g, h, i]]"};
  return names[t];
}

static int check_value(const pf_deck *d, const pf_node *map, int i, const pf_key *k,
                       const char *where);

static int check_scalar_type(const pf_node *v, pf_key_type t) {
  double r;
  int b;
  if (v->kind != NODE_SCALAR) return 0;
  switch (t) {
  case PF_KEY_REAL: return !v->quoted && parse_real(v->text, &r);
  case PF_KEY_INT: return !v->quoted && parse_real(v->text, &r) && r == floor(r) && fabs(r) < 9e15;
  case PF_KEY_BOOL: return parse_bool(v->text, &b);
  default: return 1;
  }
}

static int check_seq(const pf_node *v, pf_key_type t) {
  if (v->kind != NODE_SEQ) return 0;
  if (t == PF_KEY_MAT3) {
    if (v->n != 3) return 0;
    for (int j = 0; j < 3; j++)
      if (!check_seq(v->items[j], PF_KEY_VEC3)) return 0;
    return 1;
  }
  if ((t == PF_KEY_VEC3 || t == PF_KEY_EXPR3) && v->n != 3) return 0;
  for (int j = 0; j < v->n; j++) {
    const pf_node *it = v->items[j];
    if (t == PF_KEY_LIST ? it->kind != NODE_MAP : it->kind != NODE_SCALAR) return 0;
    if (t == PF_KEY_VEC3 && !check_scalar_type(it, PF_KEY_REAL)) return 0;
  }
  return 1;
}

/* The largest magnitude a length, a stress or modulus, a density and a speed may have: well beyond
 * any body or material (10^4 times diamond's modulus, 40 times osmium's density, light's speed),
 * so that a typing error such as 1e300 is refused here, not at the first step after the output
 * files are written (the step, wave speeds and forces of such a value overflow). */
static const struct {
  const char *units, *what;
  double limit;
} magnitude_limits[] = {{"m", "a length beyond 1e6 m", 1e6},
                        {"Pa", "a stress or modulus beyond 1e16 Pa", 1e16},
                        {"kg/m^3", "a density beyond 1e6 kg/m^3", 1e6},
                        {"m/s", "a speed beyond light's, 3e8 m/s", 3e8}};

static int check_magnitude(const pf_deck *d, const pf_node *v, const pf_key *k) {
  if (!k->units) return 0;
  for (size_t j = 0; j < sizeof magnitude_limits / sizeof magnitude_limits[0]; j++) {
    if (strcmp(k->units, magnitude_limits[j].units)) continue;
    for (int c = 0; c < (v->kind == NODE_SEQ ? v->n : 1); c++) {
      const pf_node *x = v->kind == NODE_SEQ ? v->items[c] : v;
      double r;
      if (parse_real(x->text, &r) && !(fabs(r) <= magnitude_limits[j].limit))
        return pf_deck_error(d, x, k->name, "%g %s is %s: a typing error?", r, k->units, magnitude_limits[j].what);
    }
  }
  return 0;
}

static int check_value(const pf_deck *d, const pf_node *map, int i, const pf_key *k,
                       const char *where) {
  const pf_node *v = map->items[i];
  char sub[256];
  int ok;
  switch (k->type) {
  case PF_KEY_REAL: case PF_KEY_INT: case PF_KEY_BOOL: case PF_KEY_STRING: case PF_KEY_EXPR:
    ok = check_scalar_type(v, k->type);
    break;
  case PF_KEY_MAP: case PF_KEY_ANYMAP: ok = v->kind == NODE_MAP; break;
  default: ok = check_seq(v, k->type);
  }
  if (!ok) {
    char got[160];
    snprintf(got, sizeof got, " (got %s%.100s%s)", v->kind == NODE_SCALAR ? "'" : "",
             v->kind == NODE_SCALAR ? v->text : v->kind == NODE_SEQ ? "a list" : "a mapping",
             v->kind == NODE_SCALAR ? "'" : "");
    return key_error(d, map, i, "expected ", type_name(k->type), got);
  }
  if (k->type == PF_KEY_REAL || k->type == PF_KEY_VEC3) PF_CALL(check_magnitude(d, v, k));
  if (k->type == PF_KEY_MAP) {
    snprintf(sub, sizeof sub, "%s.%s", where, k->name);
    return pf_deck_validate(d, v, k->sub, sub);
  }
  if (!k->sub) return 0; /* the nested mappings are checked by their owner (e.g. by body type) */
  if (k->type == PF_KEY_LIST) {
    for (int j = 0; j < v->n; j++) {
      snprintf(sub, sizeof sub, "%s.%s[%d]", where, k->name, j);
      PF_CALL(pf_deck_validate(d, v->items[j], k->sub, sub));
    }
  }
  if (k->type == PF_KEY_ANYMAP) {
    for (int j = 0; j < v->n; j++) {
      snprintf(sub, sizeof sub, "%s.%s.%s", where, k->name, v->keys[j]);
      if (v->items[j]->kind != NODE_MAP) return key_error(d, v, j, "expected a mapping", "", "");
      PF_CALL(pf_deck_validate(d, v->items[j], k->sub, sub));
    }
  }
  return 0;
}

int pf_deck_validate(const pf_deck *d, const pf_node *map, const pf_key *table, const char *where) {
  char pos[512];
  pf_node_where(d, map, pos, sizeof pos);
  PF_CHECK(map && map->kind == NODE_MAP, PF_ERR_INPUT, "%s: %s must be a mapping", pos, where);
  for (int i = 0; i < map->n; i++) {
    const pf_key *k = table;
    while (k->name && strcmp(k->name, map->keys[i])) k++;
    if (!k->name) return unknown_key(d, map, i, table, where);
    PF_CALL(check_value(d, map, i, k, where));
  }
  for (const pf_key *k = table; k->name; k++)
    if (k->required && !pf_node_get(map, k->name))
      return pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                            "%s: missing required key '%s' in %s (%s%s%s)", pos, k->name, where, k->doc,
                            k->units && k->units[0] ? ", " : "", k->units ? k->units : "");
  return 0;
}

/* ---- typed getters: values were type-checked by pf_deck_validate ---- */
int pf_deck_real(const pf_deck *d, const pf_node *map, const char *key, double *out) {
  const pf_node *v = pf_node_get(map, key);
  if (!v) return 0;
  if (v->kind != NODE_SCALAR || !parse_real(v->text, out))
    return pf_deck_error(d, v, key, "expected a real number");
  return 0;
}

int pf_deck_int(const pf_deck *d, const pf_node *map, const char *key, long *out) {
  double r;
  const pf_node *v = pf_node_get(map, key);
  if (!v) return 0;
  if (v->kind != NODE_SCALAR || !parse_real(v->text, &r) || r != floor(r))
    return pf_deck_error(d, v, key, "expected an integer");
  if (!(fabs(r) < 9e15)) /* (the bound pf_deck_validate applies; beyond a long the cast is undefined) */
    return pf_deck_error(d, v, key, "expected an integer below 9e15 in magnitude");
  *out = (long)r;
  return 0;
}

int pf_deck_bool(const pf_deck *d, const pf_node *map, const char *key, int *out) {
  const pf_node *v = pf_node_get(map, key);
  if (!v) return 0;
  if (v->kind != NODE_SCALAR || !parse_bool(v->text, out))
    return pf_deck_error(d, v, key, "expected true or false");
  return 0;
}

int pf_deck_string(const pf_deck *d, const pf_node *map, const char *key, const char **out) {
  const pf_node *v = pf_node_get(map, key);
  if (!v) return 0;
  if (v->kind != NODE_SCALAR) return pf_deck_error(d, v, key, "expected a string");
  *out = v->text;
  return 0;
}

int pf_deck_vec3(const pf_deck *d, const pf_node *map, const char *key, double out[3]) {
  const pf_node *v = pf_node_get(map, key);
  if (!v) return 0;
  if (v->kind != NODE_SEQ || v->n != 3) return pf_deck_error(d, v, key, "expected [x, y, z]");
  for (int c = 0; c < 3; c++)
    if (v->items[c]->kind != NODE_SCALAR || !parse_real(v->items[c]->text, &out[c]))
      return pf_deck_error(d, v->items[c], key, "component %d is not a real number", c);
  return 0;
}

int pf_deck_mat3(const pf_deck *d, const pf_node *map, const char *key, double out[3][3]) {
  const pf_node *v = pf_node_get(map, key);
  if (!v) return 0;
  if (v->kind != NODE_SEQ || v->n != 3) return pf_deck_error(d, v, key, "expected three rows [[a, b, c], [d, e, f], [g, h, i]]");
  for (int r = 0; r < 3; r++) {
    const pf_node *row = v->items[r];
    if (row->kind != NODE_SEQ || row->n != 3) return pf_deck_error(d, row, key, "row %d is not a list of 3 reals", r);
    for (int c = 0; c < 3; c++)
      if (row->items[c]->kind != NODE_SCALAR || !parse_real(row->items[c]->text, &out[r][c]))
        return pf_deck_error(d, row->items[c], key, "row %d, component %d is not a real number", r, c);
  }
  return 0;
}

int pf_deck_positive(const pf_deck *d, const pf_node *map, const char *key, double *out) {
  PF_CALL(pf_deck_real(d, map, key, out));
  if (!(*out > 0)) return pf_deck_error(d, pf_node_get(map, key), key, "must be positive (got %g)", *out);
  return 0;
}

int pf_deck_unit_vec3(const pf_deck *d, const pf_node *map, const char *key, double u[3]) {
  PF_CALL(pf_deck_vec3(d, map, key, u));
  const double len = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  if (!(len > 0)) return pf_deck_error(d, pf_node_get(map, key), key, "must not be zero");
  for (int a = 0; a < 3; a++) u[a] /= len;
  return 0;
}

int pf_deck_body_index(const pf_deck *d, const pf_node *item, const char *key, int nbodies,
                       const char *const *names, int *b) {
  const char *name = pf_node_text(item);
  for (*b = 0; *b < nbodies; (*b)++)
    if (!strcmp(names[*b], name)) return 0;
  char known[512] = "";
  for (int j = 0; j < nbodies; j++) {
    size_t at = strlen(known);
    snprintf(known + at, sizeof known - at, "%s%s", j ? ", " : "", names[j]);
  }
  return pf_deck_error(d, item, key, "no body is named '%s' (known: %s)", name, known);
}

/* The row of t named name, or NULL. */
static pf_key *table_row(pf_key_table *t, const char *name) {
  for (int k = 0; k < t->n; k++)
    if (!strcmp(t->rows[k].name, name)) return &t->rows[k];
  return NULL;
}

int pf_key_table_add(pf_key_table *t, const pf_key *part) {
  for (const pf_key *r = part; r && r->name; r++) {
    pf_key *old = table_row(t, r->name);
    if (!old) {
      PF_CHECK(t->n < t->cap, PF_ERR_RUN, "key table full (%d rows) at key '%s'", t->cap, r->name);
      t->rows[t->n++] = *r;
      continue;
    }
    PF_CHECK(old->type == r->type && !strcmp(old->units, r->units), PF_ERR_RUN,
             "key '%s' is given twice with a different type or units", r->name);
    const size_t len = strlen(old->doc) + strlen(r->doc) + 3;
    PF_CHECK(t->used + len <= t->ntext, PF_ERR_RUN, "key table text full at key '%s'", r->name);
    char *doc = t->text + t->used;
    snprintf(doc, len, "%s; %s", old->doc, r->doc);
    old->doc = doc;
    t->used += len;
  }
  t->rows[t->n] = (pf_key)PF_KEY_END;
  return 0;
}
