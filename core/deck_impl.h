/* Private to core/deck*.c: the YAML tree with source positions. */
#ifndef PF_DECK_IMPL_H
#define PF_DECK_IMPL_H
#include "core/core.h"

typedef enum { NODE_SCALAR, NODE_SEQ, NODE_MAP } node_kind;

struct pf_node {
  node_kind kind;
  int line, col;   /* 1-based */
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
};

#endif
