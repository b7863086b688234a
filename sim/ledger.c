/* The ledger: accounts, their sums over the ranks, totals, the energy balance, the history's
 * columns and the checkpoint's records (sim/ledger.h). */
#include "sim/ledger.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int in_balance(const pf_account *a) { return a->sign != 0 && !(a->flags & PF_BOOK_NO_BALANCE); }
static int is_column(const pf_account *a) { return !(a->flags & PF_BOOK_HIDDEN); }
static int is_record(const pf_account *a) { return a->kind != PF_BOOK_STATE; }

int pf_ledger_open(pf_ledger *l, const char *name, const char *units, int ncomp, int sign, pf_book_kind kind,
                   int flags, int total, int *id) {
  for (int k = 0; k < l->n; k++)
    PF_CHECK(strcmp(l->a[k].name, name) || (flags & PF_BOOK_HIDDEN) || (l->a[k].flags & PF_BOOK_HIDDEN),
             PF_ERR_INPUT,
             "the history would have two columns named '%s' (a body's, condition's, rigid surface's, wall's or "
             "contact pair's columns are its name followed by _<quantity>, e.g. <body>_internal_energy): rename "
             "the body, condition (name:), surface, wall or pair",
             name);
  if (l->n == l->cap) {
    int cap = l->cap ? 2 * l->cap : 64;
    pf_account *a = realloc(l->a, sizeof *a * (size_t)cap);
    PF_CHECK(a, PF_ERR_MEMORY, "out of memory opening the account '%s'", name);
    l->a = a, l->cap = cap;
  }
  pf_account *a = &l->a[l->n];
  memset(a, 0, sizeof *a);
  snprintf(a->name, sizeof a->name, "%s", name);
  a->units = units, a->ncomp = ncomp, a->sign = sign, a->kind = kind, a->flags = flags, a->total = total;
  *id = l->n++;
  return 0;
}

int pf_ledger_open_error(pf_ledger *l) {
  return pf_ledger_open(l, "energy_error", "J", 1, 0, PF_BOOK_STATE, PF_BOOK_SHARED, -1, &l->error_id);
}

void pf_ledger_free(pf_ledger *l) {
  free(l->a), free(l->buf);
  memset(l, 0, sizeof *l);
}

void pf_ledger_book_centred(pf_ledger *l, int id, const double r_old[3], const double r_new[3], const double w[3]) {
  double x = 0;
  for (int c = 0; c < 3; c++) x -= 0.5 * (r_old[c] + r_new[c]) * w[c];
  l->a[id].local[0] += x;
}

void pf_ledger_book_impulse(pf_ledger *l, int id, const double r_old[3], const double r_new[3], double dt) {
  for (int c = 0; c < 3; c++) l->a[id].local[c] -= 0.5 * dt * (r_old[c] + r_new[c]);
}

void pf_ledger_keep(const pf_ledger *l, double *v) {
  for (int k = 0; k < l->n; k++) memcpy(&v[3 * k], l->a[k].local, sizeof l->a[k].local);
}

void pf_ledger_put_back(pf_ledger *l, const double *v) {
  for (int k = 0; k < l->n; k++) memcpy(l->a[k].local, &v[3 * k], sizeof l->a[k].local);
}

int pf_ledger_evaluate(pf_ledger *l, int first) {
  free(l->buf);
  PF_MALLOC(l->buf, 3 * (size_t)l->n + 1);
  int m = 0;
  for (int k = 0; k < l->n; k++)
    if (!(l->a[k].flags & PF_BOOK_SHARED))
      for (int c = 0; c < l->a[k].ncomp; c++) l->buf[m++] = l->a[k].local[c];
  PF_CHECK(MPI_Allreduce(MPI_IN_PLACE, l->buf, m, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD) == MPI_SUCCESS, PF_ERR_LIB,
           "MPI_Allreduce failed summing the ledger's %d accounts", l->n);
  m = 0;
  for (int k = 0; k < l->n; k++) {
    pf_account *a = &l->a[k];
    for (int c = 0; c < a->ncomp; c++) a->value[c] = a->flags & PF_BOOK_SHARED ? a->local[c] : l->buf[m++];
  }
  for (int k = 0; k < l->n; k++) /* totals: their parts added in the order they were opened */
    if (l->a[k].total >= 0) memset(l->a[l->a[k].total].value, 0, sizeof l->a[k].value);
  for (int k = 0; k < l->n; k++)
    if (l->a[k].total >= 0)
      for (int c = 0; c < l->a[k].ncomp; c++) l->a[l->a[k].total].value[c] += l->a[k].value[c];
  const double balance = pf_ledger_balance(l);
  if (first && !l->have_e0) l->e0 = balance, l->have_e0 = 1;
  l->a[l->error_id].value[0] = l->a[l->error_id].local[0] = balance - l->e0;
  return 0;
}

double pf_ledger_balance(const pf_ledger *l) {
  double s = 0;
  for (int k = 0; k < l->n; k++)
    if (in_balance(&l->a[k])) s += l->a[k].sign * l->a[k].value[0];
  return s;
}

int pf_ledger_columns(const pf_ledger *l) {
  int n = 0;
  for (int k = 0; k < l->n; k++)
    if (is_column(&l->a[k])) n += l->a[k].ncomp;
  return n;
}

/* The account and component of column k. */
static const pf_account *column_at(const pf_ledger *l, int k, int *comp) {
  for (int j = 0; j < l->n; j++) {
    if (!is_column(&l->a[j])) continue;
    if (k < l->a[j].ncomp) return *comp = k, &l->a[j];
    k -= l->a[j].ncomp;
  }
  return NULL;
}

void pf_ledger_column(const pf_ledger *l, int k, char *buf, size_t len, const char **units) {
  int c = 0;
  const pf_account *a = column_at(l, k, &c);
  if (!a) {
    snprintf(buf, len, "?"), *units = "";
    return;
  }
  if (a->ncomp == 1) snprintf(buf, len, "%s", a->name);
  else snprintf(buf, len, "%s_%c", a->name, 'x' + c);
  *units = a->units;
}

void pf_ledger_values(const pf_ledger *l, double *v) {
  for (int k = 0; k < l->n; k++)
    if (is_column(&l->a[k]))
      for (int c = 0; c < l->a[k].ncomp; c++) *v++ = l->a[k].value[c];
}

int pf_ledger_find_column(const pf_ledger *l, const char *name) {
  char buf[160];
  const char *units;
  for (int k = 0; k < pf_ledger_columns(l); k++) {
    pf_ledger_column(l, k, buf, sizeof buf, &units);
    if (!strcmp(buf, name)) return k;
  }
  return -1;
}

int pf_ledger_records(const pf_ledger *l) {
  int n = 1; /* the initial energy */
  for (int k = 0; k < l->n; k++)
    if (is_record(&l->a[k])) n += l->a[k].ncomp;
  return n;
}

void pf_ledger_record_names(const pf_ledger *l, char (*names)[96]) {
  for (int k = 0; k < l->n; k++) {
    const pf_account *a = &l->a[k];
    if (!is_record(a)) continue;
    for (int c = 0; c < a->ncomp; c++)
      if (a->ncomp == 1) snprintf(*names++, 96, "ledger:%.80s", a->name);
      else snprintf(*names++, 96, "ledger:%.78s_%c", a->name, 'x' + c);
  }
  snprintf(*names, 96, "ledger:initial_energy");
}

int pf_ledger_record_values(pf_ledger *l, double *v) {
  double *first = v;
  for (int k = 0; k < l->n; k++) {
    const pf_account *a = &l->a[k];
    if (!is_record(a)) continue;
    for (int c = 0; c < a->ncomp; c++) *v++ = a->local[c];
  }
  *v = l->e0;
  int m = (int)(v - first), ierr = 0;
  double *sum; /* the summed accounts over the ranks; shared ones as they are */
  PF_MALLOC(sum, m + 1);
  memcpy(sum, first, sizeof(double) * (size_t)m);
  ierr = MPI_Allreduce(MPI_IN_PLACE, sum, m, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD) != MPI_SUCCESS;
  v = first;
  for (int k = 0, j = 0; k < l->n && !ierr; k++) {
    const pf_account *a = &l->a[k];
    if (!is_record(a)) continue;
    for (int c = 0; c < a->ncomp; c++, j++)
      if (!(a->flags & PF_BOOK_SHARED)) v[j] = sum[j];
  }
  free(sum);
  PF_CHECK(!ierr, PF_ERR_LIB, "MPI_Allreduce failed summing the ledger's records");
  return 0;
}

void pf_ledger_restore(pf_ledger *l, const double *v) {
  const int root = pf_comm_rank() == 0;
  for (int k = 0; k < l->n; k++) {
    pf_account *a = &l->a[k];
    if (!is_record(a)) continue;
    for (int c = 0; c < a->ncomp; c++, v++) a->local[c] = a->flags & PF_BOOK_SHARED || root ? *v : 0.0;
  }
  l->e0 = *v, l->have_e0 = 1;
}
