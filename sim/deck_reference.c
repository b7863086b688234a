/* The reference of every deck key, printed as Markdown from the same pf_key tables the deck
 * loader checks (perifem --deck-keys; docs/deck_keys.md is its output, and a test compares
 * the two, so the documentation cannot drift from the loader). */
#include "contact/contact.h"
#include "sim/sim.h"
#include "sim/body.h"
#include "material/material.h"
#include "pd/pd.h"

#include <stdio.h>
#include <string.h>

enum { MAX_SECTIONS = 96 };

typedef struct {
  const pf_key *table;
  char path[160];    /* where the mapping sits in a deck */
  const char *note;  /* which of the tables for that place, or "" */
} section;

typedef struct {
  section s[MAX_SECTIONS];
  int n;
} sections;

static const char *short_type(pf_key_type t) {
  static const char *names[] = {"real", "integer", "bool", "string", "vec3", "expr3", "expr",
                                "mapping", "list", "list of strings", "named mappings", "mat3"};
  return names[t];
}

/* Text into a table cell: '|' escaped. */
static void cell(FILE *out, const char *text) {
  for (const char *c = text; c && *c; c++) {
    if (*c == '|') fputc('\\', out);
    fputc(*c, out);
  }
}

/* The section that documents table t, or -1. */
static int find(const sections *all, const pf_key *t) {
  for (int k = 0; k < all->n; k++)
    if (all->s[k].table == t) return k;
  return -1;
}

/* Register t under path (a table met again is documented once, where first met). */
static void collect(sections *all, const pf_key *t, const char *path, const char *note) {
  if (find(all, t) >= 0 || all->n == MAX_SECTIONS) return;
  section *s = &all->s[all->n++];
  s->table = t;
  s->note = note;
  snprintf(s->path, sizeof s->path, "%s", path);
}

/* Breadth first: the tables nested in the registered ones. */
static void collect_nested(sections *all) {
  for (int k = 0; k < all->n; k++)
    for (const pf_key *r = all->s[k].table; r->name; r++) {
      if (!r->sub) continue;
      char path[160];
      const char *base = all->s[k].path;
      snprintf(path, sizeof path, "%s%s%s%s", base, *base ? "." : "", r->name, r->type == PF_KEY_LIST ? "[i]" : "");
      collect(all, r->sub, path, all->s[k].note);
    }
}

static void heading(FILE *out, const section *s) {
  fprintf(out, "`%s`%s%s%s", *s->path ? s->path : "(top level)", *s->note ? " (" : "", s->note, *s->note ? ")" : "");
}

static void print_section(FILE *out, const sections *all, int k) {
  fprintf(out, "\n## %d. ", k + 1);
  heading(out, &all->s[k]);
  fputs("\n\n", out);
  fprintf(out, "| key | type | required / default | units | meaning |\n| --- | --- | --- | --- | --- |\n");
  for (const pf_key *r = all->s[k].table; r->name; r++) {
    int sub = r->sub ? find(all, r->sub) : -1;
    fprintf(out, "| `%s` | %s | ", r->name, short_type(r->type));
    if (r->required) fputs("**required**", out);
    else if (!r->default_value && r->type == PF_KEY_MAP && sub >= 0) fprintf(out, "the defaults of §%d", sub + 1);
    else if (r->default_value && *r->default_value) fputc('`', out), cell(out, r->default_value), fputc('`', out);
    else if (r->default_value) fputs("`\"\"`", out);
    else fputs("none", out);
    fputs(" | ", out);
    cell(out, r->units);
    fputs(" | ", out);
    cell(out, r->doc);
    if (sub >= 0) fprintf(out, " (§%d)", sub + 1);
    fputs(" |\n", out);
  }
}

int pf_deck_reference(FILE *out) {
  sections all = {.n = 0};
  collect(&all, pf_deck_keys, "", "");
  collect(&all, pf_pd_material_keys, "materials.<name>", "peridynamic model");
  collect(&all, pf_material_keys, "materials.<name>", "continuum model: FE bodies and correspondence");
  static char note[16][64]; /* (collect keeps the pointer) */
  for (int k = 0; k < pf_body_kind_count() && k < 16; k++) {
    if (!pf_body_kind_first_of_type(k)) continue;
    snprintf(note[k], sizeof note[k], "type: %s", pf_body_kind_at(k)->type);
    collect(&all, pf_body_kind_at(k)->keys(), "bodies[i]", note[k]);
  }
  collect_nested(&all);
  fprintf(out, "# Deck keys\n\n"
               "Every key the deck loader accepts, with its type, default and SI units. This page is the\n"
               "output of `perifem --deck-keys`, printed from the tables the loader checks a deck against;\n"
               "the test `regression/docs_in_sync` fails when the two differ (regenerate with\n"
               "`build/perifem --deck-keys > docs/deck_keys.md`). How the keys fit together, with\n"
               "examples: [deck_guide.md](deck_guide.md).\n\n"
               "Types: real (an unquoted finite number), integer, bool (`true/false`, `yes/no`, `on/off`),\n"
               "string, vec3 (`[a, b, c]` of reals), expr3 (three expressions in `x, y, z, t`), expr (a\n"
               "real or an expression in `x, y, z`), mapping, list (a sequence of mappings), list of\n"
               "strings, named mappings (a mapping whose keys are your own names), mat3 (three rows\n"
               "`[[a, b, c], [d, e, f], [g, h, i]]` of reals).\n\n"
               "Sections:\n\n");
  for (int k = 0; k < all.n; k++) {
    fprintf(out, "%d. ", k + 1);
    heading(out, &all.s[k]);
    fputc('\n', out);
  }
  for (int k = 0; k < all.n; k++) print_section(out, &all, k);
  return ferror(out) ? PF_ERR_RUN : 0;
}
