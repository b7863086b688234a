/* The path to hand to the Exodus library for a file (core/exodus_path.c), for the modules that
 * call it (core's writer, mesh's readers and writer): p->use is the path itself, or for a long one
 * a short alias through a descriptor of its folder, which stays open until pf_exodus_path_end.
 * An error names the path and the limit. */
#ifndef PF_EXODUS_PATH_H
#define PF_EXODUS_PATH_H

typedef enum { PF_EXODUS_CREATE, PF_EXODUS_CREATE4, PF_EXODUS_OPEN } pf_exodus_call; /* (4: a netCDF-4 file) */
typedef struct {
  const char *use;
  char alias[320];
  int dirfd;
} pf_exodus_path;
int pf_exodus_path_begin(const char *path, pf_exodus_call call, pf_exodus_path *p);
void pf_exodus_path_end(pf_exodus_path *p);

#endif
