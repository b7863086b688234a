/* CalculiX on a structured hexahedral grid (calculix_grid.h). The input follows the ccx 2.20
 * manual: *NODE, *ELEMENT (C3D8 node order: the bottom face counter-clockwise seen from above,
 * then the top face), *NSET, *MATERIAL / *ELASTIC (E, nu), *SOLID SECTION, *BOUNDARY (node set,
 * first dof, last dof, value), a linear *STATIC step, and *NODE PRINT with TOTALS=ONLY, whose
 * "total force (fx,fy,fz) for set NAME" lines in the .dat file give the reactions. */
#include "calculix_grid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *SETS[3][2] = {{"X0", "X1"}, {"Y0", "Y1"}, {"Z0", "Z1"}};

const char *pf_test_ccx_path(void) {
  static char path[4096];
  const char *env = getenv("CCX");
  if (env && env[0]) return access(env, X_OK) == 0 ? env : NULL;
  const char *p = getenv("PATH");
  for (const char *s = p ? p : "/usr/bin:/bin"; *s;) {
    size_t len = strcspn(s, ":");
    snprintf(path, sizeof path, "%.*s/ccx", (int)len, s);
    if (len && access(path, X_OK) == 0) return path;
    s += len + (s[len] == ':');
  }
  return NULL;
}

static int node_id(const pf_test_ccx_grid *g, int i, int j, int k) {
  return 1 + i + (g->n[0] + 1) * (j + (g->n[1] + 1) * k);
}

static void write_mesh(FILE *f, const pf_test_ccx_grid *g) {
  fprintf(f, "*NODE\n");
  for (int k = 0; k <= g->n[2]; k++)
    for (int j = 0; j <= g->n[1]; j++)
      for (int i = 0; i <= g->n[0]; i++)
        fprintf(f, "%d, %.12g, %.12g, %.12g\n", node_id(g, i, j, k), i * g->h[0], j * g->h[1], k * g->h[2]);
  for (int m = 0; m < 2; m++) {
    fprintf(f, "*ELEMENT, TYPE=%s, ELSET=%s\n", g->type, m ? "PHASEB" : "PHASEA");
    for (int k = 0; k < g->n[2]; k++)
      for (int j = 0; j < g->n[1]; j++)
        for (int i = 0; i < g->n[0]; i++) {
          int e = i + g->n[0] * (j + g->n[1] * k);
          if (!g->in_b[e] != !m) continue;
          fprintf(f, "%d, %d, %d, %d, %d, %d, %d, %d, %d\n", e + 1, node_id(g, i, j, k), node_id(g, i + 1, j, k),
                  node_id(g, i + 1, j + 1, k), node_id(g, i, j + 1, k), node_id(g, i, j, k + 1),
                  node_id(g, i + 1, j, k + 1), node_id(g, i + 1, j + 1, k + 1), node_id(g, i, j + 1, k + 1));
        }
  }
}

/* The node sets X0, X1, Y0, Y1, Z0, Z1: the nodes of each face. */
static void write_sets(FILE *f, const pf_test_ccx_grid *g) {
  for (int a = 0; a < 3; a++)
    for (int s = 0; s < 2; s++) {
      fprintf(f, "*NSET, NSET=%s\n", SETS[a][s]);
      for (int k = 0; k <= g->n[2]; k++)
        for (int j = 0; j <= g->n[1]; j++)
          for (int i = 0; i <= g->n[0]; i++) {
            const int ijk[3] = {i, j, k};
            if (ijk[a] == (s ? g->n[a] : 0)) fprintf(f, "%d\n", node_id(g, i, j, k));
          }
    }
}

static int write_input(const pf_test_ccx_grid *g, const char *path) {
  FILE *f = fopen(path, "w");
  if (!f) return fprintf(stderr, "cannot write %s\n", path), -1;
  fprintf(f, "** written by tests/common/calculix_grid.c\n");
  write_mesh(f, g);
  write_sets(f, g);
  fprintf(f, "*MATERIAL, NAME=MATA\n*ELASTIC\n%.12g, %.12g\n", g->E_a, g->nu_a);
  fprintf(f, "*MATERIAL, NAME=MATB\n*ELASTIC\n%.12g, %.12g\n", g->E_b, g->nu_b);
  fprintf(f, "*SOLID SECTION, ELSET=PHASEA, MATERIAL=MATA\n*SOLID SECTION, ELSET=PHASEB, MATERIAL=MATB\n");
  fprintf(f, "*STEP\n*STATIC\n*BOUNDARY\n");
  for (int a = 0; a < 3; a++)
    fprintf(f, "%s, %d, %d, 0\n%s, %d, %d, %.12g\n", SETS[a][0], a + 1, a + 1, SETS[a][1], a + 1, a + 1, g->disp[a]);
  for (int a = 0; a < 3; a++) fprintf(f, "*NODE PRINT, NSET=%s, TOTALS=ONLY\nRF\n", SETS[a][1]);
  fprintf(f, "*END STEP\n");
  return fclose(f) ? -1 : 0;
}

/* The reaction along axis a of the set SETS[a][1] from the .dat file. */
static int read_totals(const char *path, double F[3]) {
  FILE *f = fopen(path, "r");
  if (!f) return fprintf(stderr, "ccx wrote no %s\n", path), -1;
  char line[512];
  int found = 0;
  while (fgets(line, sizeof line, f))
    for (int a = 0; a < 3; a++) {
      char key[64];
      snprintf(key, sizeof key, "for set %s ", SETS[a][1]);
      if (!strstr(line, "total force") || !strstr(line, key)) continue;
      double v[3];
      while (fgets(line, sizeof line, f) && sscanf(line, "%lf %lf %lf", &v[0], &v[1], &v[2]) != 3) {
      }
      F[a] = v[a], found |= 1 << a;
      break;
    }
  fclose(f);
  if (found != 7) return fprintf(stderr, "%s: no reaction totals for every far face\n", path), -1;
  return 0;
}

int pf_test_ccx_grid_solve(const pf_test_ccx_grid *g, const char *dir, const char *name, double F[3]) {
  const char *ccx = pf_test_ccx_path();
  char path[4096], cmd[8192];
  snprintf(path, sizeof path, "%s/%s.inp", dir, name);
  if (!ccx || write_input(g, path)) return -1;
  /* one thread: ccx reads OMP_NUM_THREADS and CCX_NPROC_STIFFNESS */
  snprintf(cmd, sizeof cmd, "cd '%s' && OMP_NUM_THREADS=1 CCX_NPROC_STIFFNESS=1 '%s' -i '%s' > '%s.log' 2>&1", dir,
           ccx, name, name);
  if (system(cmd) != 0) return fprintf(stderr, "ccx failed: see %s/%s.log\n", dir, name), -1;
  snprintf(path, sizeof path, "%s/%s.dat", dir, name);
  return read_totals(path, F);
}

unsigned char *pf_test_fibre_map(int n, double a, double r, double *vf) {
  unsigned char *in = calloc((size_t)n * n, 1);
  if (!in) return NULL;
  const double h = a / n;
  long count = 0;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++)
      count += in[i + n * j] = hypot((i + 0.5) * h - a / 2, (j + 0.5) * h - a / 2) <= r;
  *vf = (double)count / ((double)n * n);
  return in;
}
