/* Expressions of position and time from the deck (initial velocities, prescribed motions),
 * compiled and evaluated by muparser through its C API; the deck's parameters (core/deck_compose.c)
 * are constants in every expression. */
#include "core/core.h"
#include "core/deck_impl.h"

#include <muParserDLL.h>
#include <math.h>
#include <stdlib.h>

struct pf_expr {
  muParserHandle_t parser;
  double x, y, z, t;            /* the variables the parser reads */
  double var[PF_EXPR_MAXVARS]; /* and the extra ones */
  int nvars;
  const pf_deck *d;    /* where it was given (for pf_expr_check_finite's error) */
  const pf_node *node;
  const char *key;
};

int pf_expr_create(const char *text, const pf_deck *d, const pf_node *n, const char *key,
                   pf_expr **out) {
  return pf_expr_create_vars(text, d, n, key, NULL, 0, out);
}

int pf_expr_create_vars(const char *text, const pf_deck *d, const pf_node *n, const char *key,
                        const char *const *names, int nnames, pf_expr **out) {
  *out = NULL;
  PF_CHECK(nnames >= 0 && nnames <= PF_EXPR_MAXVARS, PF_ERR_RUN, "%d expression variables", nnames);
  pf_expr *e;
  PF_MALLOC(e, 1);
  e->parser = mupCreate(muBASETYPE_FLOAT);
  if (!e->parser) {
    free(e);
    PF_CHECK(0, PF_ERR_MEMORY, "muparser: cannot create a parser");
  }
  mupDefineVar(e->parser, "x", &e->x);
  mupDefineVar(e->parser, "y", &e->y);
  mupDefineVar(e->parser, "z", &e->z);
  mupDefineVar(e->parser, "t", &e->t);
  for (int k = 0; k < nnames; k++) mupDefineVar(e->parser, names[k], &e->var[k]);
  for (int k = 0; d && k < d->nparams; k++) mupDefineConst(e->parser, d->param_name[k], d->param_value[k]);
  e->nvars = nnames;
  e->d = d, e->node = n, e->key = key;
  mupSetExpr(e->parser, text);
  (void)mupEval(e->parser); /* compiles; syntax and unknown names show up here */
  if (mupError(e->parser)) {
    int ierr = pf_deck_error(d, n, key, "bad expression '%s': %s (at character %d)", text,
                             mupGetErrorMsg(e->parser), (int)mupGetErrorPos(e->parser) + 1);
    pf_expr_destroy(&e);
    return ierr;
  }
  *out = e;
  return 0;
}

/* The deck's parameters as constants. */
static int define_parameters(muParserHandle_t p, const pf_deck *d, const pf_node *n, const char *key) {
  for (int k = 0; k < d->nparams; k++) mupDefineConst(p, d->param_name[k], d->param_value[k]);
  if (mupError(p)) return pf_deck_error(d, n, key, "parameter names: %s", mupGetErrorMsg(p));
  return 0;
}

int pf_expr_constant(const pf_deck *d, const pf_node *n, const char *key, const char *text, double *v) {
  muParserHandle_t p = mupCreate(muBASETYPE_FLOAT);
  PF_CHECK(p, PF_ERR_MEMORY, "muparser: cannot create a parser");
  int ierr = define_parameters(p, d, n, key);
  if (!ierr) {
    mupSetExpr(p, text);
    *v = mupEval(p);
    if (mupError(p))
      ierr = pf_deck_error(d, n, key, "bad expression '%s': %s (at character %d; the names known here are the "
                           "parameters given above)", text, mupGetErrorMsg(p), (int)mupGetErrorPos(p) + 1);
    else if (!isfinite(*v))
      ierr = pf_deck_error(d, n, key, "the expression '%s' is not finite (%g)", text, *v);
  }
  mupRelease(p);
  return ierr;
}

int pf_expr_destroy(pf_expr **e) {
  if (!*e) return 0;
  mupRelease((*e)->parser);
  PF_FREE(*e);
  return 0;
}

double pf_expr_eval_vars(pf_expr *e, double x, double y, double z, double t, const double *vars) {
  for (int k = 0; k < e->nvars; k++) e->var[k] = vars[k];
  return pf_expr_eval(e, x, y, z, t);
}

double pf_expr_eval(pf_expr *e, double x, double y, double z, double t) {
  e->x = x;
  e->y = y;
  e->z = z;
  e->t = t;
  return mupEval(e->parser);
}

int pf_expr_check_finite(pf_expr *e, const double *X, pf_int n, double t_end, int nt) {
  static const double origin[3] = {0, 0, 0};
  if (!X) X = origin, n = 1;
  if (!(t_end >= 0 && isfinite(t_end))) t_end = 0;
  if (nt < 1) nt = 1;
  /* every position at every time while that is cheap (1e5 evaluations); beyond it, every
   * position at the first and last times and the first position at every time */
  const int all = (double)n * (nt + 1) <= 1e5;
  double bad = INFINITY;
  for (int k = 0; k <= nt && !(bad < INFINITY); k++) {
    const double t = k == nt ? t_end : t_end * k / nt;
    const pf_int np = all || k == 0 || k == nt ? n : (n > 0);
    for (pf_int i = 0; i < np; i++)
      if (!isfinite(pf_expr_eval(e, X[3 * i], X[3 * i + 1], X[3 * i + 2], t))) {
        bad = t;
        break;
      }
  }
  bad = pf_min_all(bad); /* the earliest over the ranks, so that every rank refuses */
  if (!(bad < INFINITY)) return 0;
  return pf_deck_error(e->d, e->node, e->key,
                       "the expression is not finite at t = %g s (checked before the first step at %d times over "
                       "[0, %g] s, at the points it acts on)",
                       bad, nt + 1, t_end);
}

int pf_expr3_create(const pf_deck *d, const pf_node *map, const char *key, pf_expr *e[3]) {
  e[0] = e[1] = e[2] = NULL;
  const pf_node *v = pf_node_get(map, key);
  PF_CHECK(v && pf_node_count(v) == 3, PF_ERR_INPUT, "%s: key '%s' needs three expressions",
           pf_deck_path(d), key);
  for (int c = 0; c < 3; c++) {
    const pf_node *it = pf_node_item(v, c);
    int ierr = pf_expr_create(pf_node_text(it), d, it, key, &e[c]);
    if (ierr) {
      pf_expr3_destroy(e);
      return ierr;
    }
  }
  return 0;
}

void pf_expr3_destroy(pf_expr *e[3]) {
  for (int c = 0; c < 3; c++) pf_expr_destroy(&e[c]);
}
