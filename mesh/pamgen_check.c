/* A Pamgen text checked before Pamgen sees it (its keywords: Pamgen's user manual, SAND2008-1933,
 * §3). Pamgen asserts on a text that stops inside a section, throws on a negative block count or
 * interval and divides by zero on "trisection blocks, 0"; each ends the process. The numbers that
 * count elements must be positive integers, and the text must end with its mesh type's "end" and
 * the mesh's "end". The element count is estimated per direction, as n x b ("nx = 10, bx = 2")
 * or as the sum of the blocks' intervals ("zblock 1 24.0e-3 interval 8"), and multiplied. */
#include "mesh/pamgen_guard.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define TOKEN_MAX 64

typedef struct {
  const char *p; /* the next character */
  int line;      /* the text's line of the last token */
  char tok[TOKEN_MAX];
} scanner;

/* The next token (separated by blanks, '=' or ','), or 0 at the end of the text. */
static int next(scanner *s) {
  while (*s->p && (isspace((unsigned char)*s->p) || *s->p == '=' || *s->p == ',')) {
    if (*s->p == '\n') s->line++;
    s->p++;
  }
  if (!*s->p) return 0;
  size_t n = 0;
  while (*s->p && !isspace((unsigned char)*s->p) && *s->p != '=' && *s->p != ',') {
    if (n + 1 < TOKEN_MAX) s->tok[n++] = *s->p;
    s->p++;
  }
  s->tok[n] = '\0';
  return 1;
}

static int is(const char *tok, const char *word) { return strcasecmp(tok, word) == 0; }

/* The direction a count or block keyword speaks of (0: x or r, 1: y or angle, 2: z), or -1. */
static int direction(const char *tok, const char *const words[3][3]) {
  for (int d = 0; d < 3; d++)
    for (int k = 0; k < 3 && words[d][k]; k++)
      if (is(tok, words[d][k])) return d;
  return -1;
}

static const char *const counts[3][3] = {{"nx", "nr", NULL}, {"ny", "ntheta", NULL}, {"nz", NULL}};
static const char *const blocks[3][3] = {{"bx", "br", NULL}, {"by", "btheta", NULL}, {"bz", NULL}};
static const char *const spans[3][3] = {{"xblock", "rblock", NULL}, {"yblock", "ablock", NULL}, {"zblock", NULL}};
static const char *const tallies[] = {"numx", "numr", "numy", "numa", "numz", "blocks"};

static int fail(char *msg, size_t len, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, len, fmt, ap);
  va_end(ap);
  return 1;
}

/* The token after a keyword that must be a positive integer: its value, or 0 with msg set. */
static double positive_integer(scanner *s, const char *key, char *msg, size_t len) {
  char *end = NULL;
  const int have = next(s);
  const double v = have ? strtod(s->tok, &end) : 0;
  if (have && end != s->tok && *end == '\0' && v >= 1 && v <= 2147483647.0 && v == floor(v)) return v;
  fail(msg, len, "Pamgen text line %d: '%s' takes a positive integer, not '%s'", s->line, key,
       have ? s->tok : "(the end of the text)");
  return 0;
}

int pf_pamgen_check(const char *text, double *elements, char *msg, size_t len) {
  scanner s = {text, 1, ""};
  double n[3] = {1, 1, 1}, b[3] = {1, 1, 1}, sum[3] = {0, 0, 0};
  int span = -1, ends = 0, last_end = 0, tokens = 0;
  char key[TOKEN_MAX];
  while (next(&s)) {
    tokens++;
    last_end = is(s.tok, "end") ? last_end + 1 : 0;
    ends += is(s.tok, "end");
    snprintf(key, sizeof key, "%s", s.tok);
    int d, counted = 0;
    for (size_t k = 0; k < sizeof tallies / sizeof tallies[0]; k++) counted |= is(key, tallies[k]);
    if ((d = direction(key, spans)) >= 0) span = d;
    if ((d = direction(key, counts)) >= 0 && !(n[d] = positive_integer(&s, key, msg, len))) return 1;
    if ((d = direction(key, blocks)) >= 0 && !(b[d] = positive_integer(&s, key, msg, len))) return 1;
    if (counted && !positive_integer(&s, key, msg, len)) return 1;
    if (is(key, "interval")) {
      const double v = positive_integer(&s, key, msg, len);
      if (!v) return 1;
      if (span >= 0) sum[span] += v;
    }
  }
  if (tokens == 0) return fail(msg, len, "the Pamgen text is empty");
  if (ends < 2 || last_end < 2)
    return fail(msg, len,
                "the Pamgen text stops inside a section: it must end with the 'end' of its mesh type and the "
                "'end' of 'mesh' "
                "(its last line, Pamgen text line %d, closes %d of them)",
                s.line, last_end);
  *elements = 1;
  for (int c = 0; c < 3; c++) *elements *= fmax(n[c] * b[c], sum[c]);
  return 0;
}
