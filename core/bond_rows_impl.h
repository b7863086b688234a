/* Private to core/: what the bond rows (core/bond_rows.c) and their field registry
 * (core/bond_fields.c) share. */
#ifndef PF_BOND_ROWS_IMPL_H
#define PF_BOND_ROWS_IMPL_H

#include "core/core.h"

/* Bonds in the rows (0 before pf_bond_rows_init). */
static inline int64_t pf_bond_rows_nbonds(const pf_bond_rows *r) { return r->offset ? r->offset[r->n] : 0; }
/* Set components [c0, ncomp) of bonds [first, first + count) of f to its init. */
void pf_bond_field_fill(pf_bond_field *f, int64_t first, int64_t count, int c0);
/* A new row of count bonds whose neighbours and fields the caller writes, every one (a
 * migration's records: core/migrate.c); its first bond is *at. */
int pf_bond_rows_append_unset(pf_bond_rows *r, pf_int count, int64_t *at);

#endif
