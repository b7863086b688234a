/* Pamgen behind a guard: its input checked before meshing (mesh/pamgen_check.c), its
 * exceptions caught (mesh/pamgen_create.cpp). Private to mesh/. */
#ifndef PF_MESH_PAMGEN_GUARD_H
#define PF_MESH_PAMGEN_GUARD_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The status pf_pamgen_create returns when Pamgen threw: none of Pamgen's own (0 to 3). */
#define PF_PAMGEN_THREW (-1)

/* Create_Pamgen_Mesh(text, 3-D, rank 0 of 1 processor): Pamgen's status, or PF_PAMGEN_THREW
 * with the exception's message in what[len]. */
long long pf_pamgen_create(const char *text, char *what, size_t len);

/* What Pamgen would not survive, found in its text before meshing: an unfinished text (its
 * parser asserts), block counts, intervals and element counts per block that are not positive
 * integers (it throws, or divides by zero). 0, with the estimated number of elements in
 * *elements; or non-zero with the reason in msg[len]. */
int pf_pamgen_check(const char *text, double *elements, char *msg, size_t len);

#ifdef __cplusplus
}
#endif

#endif
