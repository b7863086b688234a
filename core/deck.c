/* The input deck: YAML read with libyaml into a small tree that keeps every node's source
 * position, and checked against schema tables (pf_key) that are also the source of the deck
 * documentation. Every error names file:line:column and the key. */
#include "core/core.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <yaml.h>

#include "core/deck_impl.h"

void pf_deck_node_free(pf_node *n) {
  if (!n) return;
  for (int i = 0; i < n->n; i++) {
    pf_deck_node_free(n->items[i]);
    if (n->keys) free(n->keys[i]);
  }
  free(n->items);
  free(n->keys);
  free(n->key_line);
  free(n->key_col);
  free(n->text);
  free(n);
}

/* What the YAML-to-tree conversion carries along. */
typedef struct {
  const char *path; /* kept by the deck: every node points to it */
  yaml_document_t *doc;
  long budget; /* nodes left: aliases can make a small file expand exponentially */
} convert_ctx;

static int convert(convert_ctx *cx, yaml_node_t *y, int depth, pf_node **out);

static int convert_map(convert_ctx *cx, yaml_node_t *y, int depth, pf_node *n) {
  const char *path = cx->path;
  yaml_document_t *doc = cx->doc;
  int count = (int)(y->data.mapping.pairs.top - y->data.mapping.pairs.start);
  PF_MALLOC(n->items, count);
  PF_MALLOC(n->keys, count);
  PF_MALLOC(n->key_line, count);
  PF_MALLOC(n->key_col, count);
  for (int i = 0; i < count; i++) {
    yaml_node_pair_t *pr = &y->data.mapping.pairs.start[i];
    yaml_node_t *k = yaml_document_get_node(doc, pr->key);
    int kl = (int)k->start_mark.line + 1, kc = (int)k->start_mark.column + 1;
    PF_CHECK(k->type == YAML_SCALAR_NODE, PF_ERR_INPUT, "%s:%d:%d: a mapping key must be a plain name",
             path, kl, kc);
    const char *key = (const char *)k->data.scalar.value;
    for (int j = 0; j < n->n; j++)
      PF_CHECK(strcmp(n->keys[j], key), PF_ERR_INPUT,
               "%s:%d:%d: key '%s' given twice (first at line %d)", path, kl, kc, key,
               n->key_line[j]);
    n->keys[i] = strdup(key);
    PF_CHECK(n->keys[i], PF_ERR_MEMORY, "out of memory");
    n->key_line[i] = kl;
    n->key_col[i] = kc;
    n->n = i + 1;
    PF_CALL(convert(cx, yaml_document_get_node(doc, pr->value), depth + 1, &n->items[i]));
  }
  return 0;
}

static int convert(convert_ctx *cx, yaml_node_t *y, int depth, pf_node **out) {
  const char *path = cx->path;
  PF_CHECK(depth < 64, PF_ERR_INPUT, "%s:%d:%d: nesting deeper than 64 levels", path,
           (int)y->start_mark.line + 1, (int)y->start_mark.column + 1);
  PF_CHECK(--cx->budget > 0, PF_ERR_INPUT, "%s:%d:%d: the deck expands to more than a million nodes "
           "(recursive YAML aliases?)", path, (int)y->start_mark.line + 1, (int)y->start_mark.column + 1);
  pf_node *n;
  PF_MALLOC(n, 1);
  *out = n;
  n->file = path;
  n->line = (int)y->start_mark.line + 1;
  n->col = (int)y->start_mark.column + 1;
  if (y->type == YAML_SCALAR_NODE) {
    n->kind = NODE_SCALAR;
    n->text = strdup((const char *)y->data.scalar.value);
    PF_CHECK(n->text, PF_ERR_MEMORY, "out of memory");
    n->quoted = y->data.scalar.style == YAML_SINGLE_QUOTED_SCALAR_STYLE ||
                y->data.scalar.style == YAML_DOUBLE_QUOTED_SCALAR_STYLE;
    return 0;
  }
  if (y->type == YAML_SEQUENCE_NODE) {
    n->kind = NODE_SEQ;
    int count = (int)(y->data.sequence.items.top - y->data.sequence.items.start);
    PF_MALLOC(n->items, count);
    for (int i = 0; i < count; i++) {
      n->n = i + 1;
      yaml_node_t *it = yaml_document_get_node(cx->doc, y->data.sequence.items.start[i]);
      PF_CALL(convert(cx, it, depth + 1, &n->items[i]));
    }
    return 0;
  }
  n->kind = NODE_MAP;
  return convert_map(cx, y, depth, n);
}

static int read_file(const char *path, char **text, size_t *len) {
  FILE *fp = fopen(path, "rb");
  PF_CHECK(fp, PF_ERR_INPUT, "cannot open deck '%s': %s", path, strerror(errno));
  struct stat st;
  if (fstat(fileno(fp), &st) == 0 && S_ISDIR(st.st_mode)) {
    fclose(fp);
    PF_CHECK(0, PF_ERR_INPUT, "the deck '%s' is a directory, not a file", path);
  }
  fseek(fp, 0, SEEK_END);
  long sz = ftell(fp);
  fseek(fp, 0, SEEK_SET);
  if (sz < 0) {
    fclose(fp);
    PF_CHECK(0, PF_ERR_INPUT, "cannot read deck '%s'", path);
  }
  char *buf = malloc((size_t)sz + 1);
  if (!buf) fclose(fp);
  PF_CHECK(buf, PF_ERR_MEMORY, "out of memory reading '%s'", path);
  size_t got = fread(buf, 1, (size_t)sz, fp);
  fclose(fp);
  buf[got] = '\0';
  *text = buf;
  *len = got;
  return 0;
}

/* The hint of a YAML syntax error on a line that holds a ${...}: in a flow mapping or list,
 * the braces of an unquoted ${...} are YAML's own. */
static const char *substitution_hint(const char *text, size_t len, int line) {
  const char *p = text, *end = text + len;
  for (int l = 1; l < line && p < end; l++) {
    p = memchr(p, '\n', (size_t)(end - p));
    if (!p) return "";
    p++;
  }
  const char *eol = memchr(p, '\n', (size_t)(end - p));
  const size_t n = (size_t)((eol ? eol : end) - p);
  for (size_t k = 0; k + 1 < n; k++)
    if (p[k] == '$' && p[k + 1] == '{')
      return " (a ${...} inside { } or [ ] must be quoted there: spacing: \"${dx}\")";
  return "";
}

/* One YAML document into a tree; a deck file's root must be a mapping (need_map), an override's
 * value may be anything. */
static int parse_text(const char *path, const char *text, size_t len, int need_map, pf_node **out) {
  yaml_parser_t parser;
  yaml_document_t doc;
  PF_CHECK(yaml_parser_initialize(&parser), PF_ERR_MEMORY, "libyaml: cannot initialize");
  yaml_parser_set_input_string(&parser, (const unsigned char *)text, len);
  if (!yaml_parser_load(&parser, &doc)) {
    int line = (int)parser.problem_mark.line + 1, col = (int)parser.problem_mark.column + 1;
    char prob[512];
    snprintf(prob, sizeof prob, "%s%s%s", parser.problem ? parser.problem : "syntax error",
             parser.context ? " " : "", parser.context ? parser.context : "");
    yaml_parser_delete(&parser);
    PF_CHECK(0, PF_ERR_INPUT, "%s:%d:%d: YAML syntax error: %s%s", path, line, col, prob,
             substitution_hint(text, len, line));
  }
  yaml_node_t *root = yaml_document_get_root_node(&doc);
  int ierr = 0;
  yaml_document_t next;
  if (root && yaml_parser_load(&parser, &next)) {
    yaml_node_t *nroot = yaml_document_get_root_node(&next);
    if (nroot)
      ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                            "%s:%d:%d: a second YAML document; a deck is one document", path,
                            (int)nroot->start_mark.line + 1, (int)nroot->start_mark.column + 1);
    yaml_document_delete(&next);
  }
  if (ierr) (void)0;
  else if (!root) ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__, "%s: the deck is empty", path);
  else if (need_map && root->type != YAML_MAPPING_NODE)
    ierr = pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__,
                          "%s:%d:%d: the deck must be a mapping of keys (title:, bodies:, ...)",
                          path, (int)root->start_mark.line + 1, (int)root->start_mark.column + 1);
  else {
    convert_ctx cx = {path, &doc, 1000000};
    ierr = convert(&cx, root, 0, out);
  }
  yaml_document_delete(&doc);
  yaml_parser_delete(&parser);
  return ierr;
}

const char *pf_deck_keep(pf_deck *d, const char *text) {
  char **grown = realloc(d->names, sizeof *grown * (size_t)(d->nnames + 1));
  if (!grown) return NULL;
  d->names = grown;
  return (d->names[d->nnames] = strdup(text)) ? d->names[d->nnames++] : NULL;
}

int pf_deck_parse_file(pf_deck *d, const char *path, pf_node **root) {
  *root = NULL;
  const char *kept = pf_deck_keep(d, path);
  PF_CHECK(kept, PF_ERR_MEMORY, "out of memory");
  char *text = NULL;
  size_t len = 0;
  PF_CALL(read_file(path, &text, &len));
  int ierr = parse_text(kept, text, len, 1, root);
  free(text);
  return ierr;
}

static void forget_lines(pf_node *n) {
  n->line = n->col = 0;
  for (int i = 0; i < n->n; i++) {
    forget_lines(n->items[i]);
    if (n->key_line) n->key_line[i] = n->key_col[i] = 0;
  }
}

int pf_deck_parse_value(pf_deck *d, const char *origin, const char *text, pf_node **value) {
  *value = NULL;
  const char *kept = pf_deck_keep(d, origin);
  PF_CHECK(kept, PF_ERR_MEMORY, "out of memory");
  PF_CALL(parse_text(kept, text, strlen(text), 0, value));
  forget_lines(*value);
  return 0;
}

int pf_deck_load(const char *path, pf_deck **deck) { return pf_deck_load_with(path, NULL, 0, deck); }

/* The deck of the file path, or of text (not NULL) standing for that file. */
static int load(const char *path, const char *text, const char *const *sets, int nsets, pf_deck **deck) {
  *deck = NULL;
  pf_deck *d = calloc(1, sizeof *d);
  PF_CHECK(d, PF_ERR_MEMORY, "out of memory");
  d->path = strdup(path);
  const char *kept = d->path && text ? pf_deck_keep(d, path) : NULL;
  int ierr = !d->path || (text && !kept) ? PF_ERR_MEMORY
             : text                     ? parse_text(kept, text, strlen(text), 1, &d->root)
                                        : pf_deck_parse_file(d, path, &d->root);
  if (!ierr) ierr = pf_deck_compose(d, sets, nsets);
  if (ierr) {
    pf_deck_destroy(&d);
    return ierr;
  }
  d->hash = pf_node_hash(d->root);
  *deck = d;
  return 0;
}

int pf_deck_load_with(const char *path, const char *const *sets, int nsets, pf_deck **deck) {
  return load(path, NULL, sets, nsets, deck);
}

int pf_deck_load_text(const char *path, const char *text, const char *const *sets, int nsets, pf_deck **deck) {
  return load(path, text, sets, nsets, deck);
}

int pf_deck_destroy(pf_deck **deck) {
  pf_deck *d = *deck;
  if (!d) return 0;
  pf_deck_node_free(d->root);
  for (int k = 0; k < d->nnames; k++) free(d->names[k]);
  for (int k = 0; k < d->nparams; k++) free(d->param_name[k]);
  free(d->names), free(d->param_name), free(d->param_value), free(d->included);
  free(d->path);
  PF_FREE(*deck);
  return 0;
}

const pf_node *pf_deck_root(const pf_deck *deck) { return deck->root; }
const char *pf_deck_path(const pf_deck *deck) { return deck->path; }
const char *pf_deck_included(const pf_deck *deck, int k) { return k < deck->nincluded ? deck->included[k] : NULL; }
uint64_t pf_deck_hash(const pf_deck *deck) { return deck->hash; }

const pf_node *pf_node_get(const pf_node *map, const char *key) {
  if (!map || map->kind != NODE_MAP) return NULL;
  for (int i = 0; i < map->n; i++)
    if (!strcmp(map->keys[i], key)) return map->items[i];
  return NULL;
}
int pf_node_count(const pf_node *n) { return n && n->kind != NODE_SCALAR ? n->n : 0; }
const pf_node *pf_node_item(const pf_node *seq, int i) {
  return seq && seq->kind == NODE_SEQ && i < seq->n ? seq->items[i] : NULL;
}
const pf_node *pf_node_map_item(const pf_node *map, int i, const char **key) {
  if (!map || map->kind != NODE_MAP || i >= map->n) return NULL;
  *key = map->keys[i];
  return map->items[i];
}
const char *pf_node_text(const pf_node *n) { return n && n->kind == NODE_SCALAR ? n->text : NULL; }
int pf_node_line(const pf_node *n) { return n ? n->line : 0; }
int pf_node_column(const pf_node *n) { return n ? n->col : 0; }

void pf_node_where(const pf_deck *d, const pf_node *n, char *out, size_t len) {
  const char *file = n && n->file ? n->file : d->path;
  if (n && n->line > 0) snprintf(out, len, "%s:%d:%d", file, n->line, n->col);
  else snprintf(out, len, "%s", file);
}

int pf_deck_error(const pf_deck *d, const pf_node *n, const char *key, const char *fmt, ...) {
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  char where[512];
  pf_node_where(d, n, where, sizeof where);
  return pf_error_raise(PF_ERR_INPUT, __FILE__, __LINE__, __func__, "%s: key '%s': %s", where, key, msg);
}

void pf_deck_warn(const pf_deck *d, const pf_node *n, const char *key, const char *fmt, ...) {
  if (pf_comm_rank() != 0) return;
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  char where[512];
  pf_node_where(d, n, where, sizeof where);
  fflush(stdout);
  fprintf(stderr, "perifem warning: %s: key '%s': %s\n", where, key, msg);
  fflush(stderr);
}

/* FNV-1a over a node's kind, keys and scalar text, depth first: equal for decks that say the
 * same thing however they are laid out or commented. */
static uint64_t hash_bytes(uint64_t h, const void *p, size_t n) {
  const unsigned char *c = p;
  for (size_t i = 0; i < n; i++) h = (h ^ c[i]) * 1099511628211ULL;
  return h;
}

static uint64_t hash_node(uint64_t h, const pf_node *n) {
  if (!n) return hash_bytes(h, "~", 1);
  h = hash_bytes(h, &n->kind, sizeof n->kind);
  if (n->kind == NODE_SCALAR) return hash_bytes(h, n->text, strlen(n->text) + 1);
  for (int i = 0; i < n->n; i++) {
    if (n->kind == NODE_MAP) h = hash_bytes(h, n->keys[i], strlen(n->keys[i]) + 1);
    h = hash_node(h, n->items[i]);
  }
  return h;
}

uint64_t pf_node_hash(const pf_node *n) { return hash_node(1469598103934665603ULL, n); }

void pf_deck_relative_path(const pf_deck *d, const char *name, char *out, size_t len) {
  const char *dp = pf_deck_path(d), *slash = strrchr(dp, '/');
  if (name[0] == '/' || !slash) snprintf(out, len, "%s", name);
  else snprintf(out, len, "%.*s/%s", (int)(slash - dp), dp, name);
}
