/* Pamgen behind its guard (mesh/pamgen_check.c, mesh/pamgen_create.cpp). Each text below ended
 * the process before the guard (Trilinos 13 Pamgen, Debian 12): a negative block count or
 * interval threw std::bad_array_new_length (SIGABRT), a text without its last "end" failed an
 * assertion in Pamgen's parser (SIGABRT), "trisection blocks, 0" divided by zero (SIGFPE), and
 * 3,000 x 3,000 x 4 elements ran out of time before memory. Checked here:
 *  - the check refuses each, naming the keyword, the text's line and the value;
 *  - the element estimate: n x b per direction for a rectilinear mesh (4 x 2 . 3 . 5 = 120), the
 *    sum of the blocks' intervals for a radial one (4 x 16 x 24 = 1536, against Pamgen's own
 *    count of that trisection cylinder: 1920, of which the core is the part the product misses);
 *  - the creation with an exception caught: the negative block count given to Pamgen directly
 *    returns PF_PAMGEN_THREW with the exception's name, and the process goes on. */
#include "test_common.h"

#include <create_inline_mesh.h>
#include <pamgen_im_exodusII.h>
#include <stdio.h>
#include <string.h>

#include "mesh/pamgen_guard.h"

static const char *box = "mesh\n  rectilinear\n    nx = 4\n    ny = 3\n    nz = 5\n"
                         "    bx = 2\n    by = 1\n    bz = 1\n    gmin = 0 0 0\n    gmax = 1 1 1\n"
                         "  end\nend\n";
static const char *cylinder = "mesh\n  radial trisection\n    trisection blocks, 4\n"
                              "    numz 1\n      zblock 1 24.0e-3 interval 24\n"
                              "    numr 2\n      rblock 1 1.5e-3 interval 2\n"
                              "      rblock 2 1.5e-3 interval 2\n"
                              "    numa 1\n      ablock 1 360 interval 16\n  end\nend\n";

/* text with the first occurrence of from replaced by to */
static void edit(const char *text, const char *from, const char *to, char *out, size_t len) {
  const char *at = strstr(text, from);
  PF_TEST_TRUE(at != NULL);
  if (!at) return;
  snprintf(out, len, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
}

static void refused(const char *text, const char *from, const char *to, const char *mention) {
  char t[1024], msg[512] = "";
  double n = 0;
  edit(text, from, to, t, sizeof t);
  PF_TEST_TRUE(pf_pamgen_check(t, &n, msg, sizeof msg) != 0);
  PF_TEST_TRUE(strstr(msg, mention) != NULL);
  if (!strstr(msg, mention)) printf("  '%s': %s\n", to, msg);
}

static void estimates(void) {
  char msg[512] = "";
  double n = 0;
  PF_TEST_OK(pf_pamgen_check(box, &n, msg, sizeof msg));
  PF_TEST_CLOSE(n, 120, 0, 0);
  PF_TEST_OK(pf_pamgen_check(cylinder, &n, msg, sizeof msg));
  PF_TEST_CLOSE(n, 4 * 16 * 24, 0, 0);
  PF_TEST_TRUE(pf_pamgen_check("", &n, msg, sizeof msg) != 0);
  /* Pamgen's own count of the cylinder, for the estimate's reading */
  char what[256] = "";
  PF_TEST_TRUE(pf_pamgen_create(cylinder, what, sizeof what) == ERROR_FREE_CREATION);
  char title[MAX_LINE_LENGTH + 1];
  int dim = 0, nodes = 0, elems = 0, blocks = 0, ns = 0, ss = 0;
  im_ex_get_init(0, title, &dim, &nodes, &elems, &blocks, &ns, &ss);
  PF_TEST_CLOSE(elems, 1920, 0, 0);
  Delete_Pamgen_Mesh();
}

static void refusals(void) {
  refused(box, "bx = 2", "bx = -1", "line 6: 'bx' takes a positive integer, not '-1'");
  refused(box, "nx = 4", "nx = 4.5", "'nx' takes a positive integer, not '4.5'");
  refused(box, "  end\nend\n", "  end\n", "stops inside a section");
  refused(cylinder, "interval 2\n", "interval -2\n", "line 7: 'interval' takes a positive integer");
  refused(cylinder, "blocks, 4", "blocks, 0", "'blocks' takes a positive integer, not '0'");
}

static void exception_caught(void) {
  char t[1024], what[256] = "";
  edit(box, "bx = 2", "bx = -1", t, sizeof t);
  PF_TEST_TRUE(pf_pamgen_create(t, what, sizeof what) == PF_PAMGEN_THREW);
  PF_TEST_TRUE(strstr(what, "bad_array_new_length") != NULL);
  printf("  Pamgen threw: %s\n", what);
}

int main(int argc, char **argv) {
  pf_test_init(&argc, &argv);
  estimates();
  refusals();
  exception_caught();
  return pf_test_finish();
}
