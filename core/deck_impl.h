/* Private to core/deck*.c: the YAML tree with source positions. */
#ifndef PF_DECK_IMPL_H
#define PF_DECK_IMPL_H
#include "core/core.h"

typedef enum { NODE_SCALAR, NODE_SEQ, NODE_MAP } node_kind;

struct pf_node {
  node_kind kind;
  const char *file; /* the file it was read from (owned by the deck), or a --set override */
  int line, col;   /* 1-based; 0 for an override */
  char *text;      /* scalar text */
  int quoted;      /* scalar was quoted: a string, never a number */
  int n;           /* items (sequence) or pairs (mapping) */
  pf_node **items; /* sequence items, or mapping values */
  char **keys;     /* mapping keys */
  int *key_line, *key_col;
};

struct pf_deck {
  char *path;
  pf_node *root;
  uint64_t hash;
  char **names; /* the file names and --set texts the nodes point to */
  int nnames;
  const char **included; /* the included files, among names */
  int nincluded;
  /* parameters: (core/deck_compose.c), in the order given */
  char **param_name;
  double *param_value;
  int nparams;
};

/* core/deck.c, for core/deck_compose.c */
/* Read and convert one YAML file (a mapping) into a tree whose nodes name that file. */
int pf_deck_parse_file(pf_deck *d, const char *path, pf_node **root);
/* A value given as YAML text (an override): its nodes name origin, without a line. */
int pf_deck_parse_value(pf_deck *d, const char *origin, const char *text, pf_node **value);
/* A copy of text kept by the deck for as long as it lives (node file names). */
const char *pf_deck_keep(pf_deck *d, const char *text);
void pf_deck_node_free(pf_node *n);
/* Includes, --set overrides, parameters and their ${...} substitution, in that order. */
int pf_deck_compose(pf_deck *d, const char *const *sets, int nsets);

#endif
