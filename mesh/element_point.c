/* A solid element as one peridynamic point, the way Peridigm's Exodus discretization makes it:
 * the point sits at the element's centroid and carries the element's volume.
 *  - TET4: volume (b - a) . ((c - a) x (d - a)) / 6 of the nodes a, b, c, d in Exodus order,
 *    centroid the mean of the four nodes (exact for a tetrahedron);
 *  - HEX8: the six tetrahedra about the diagonal from node 1 to node 7 (Exodus numbering)
 *    listed below; the volume is their sum and the centroid their volume-weighted centroid.
 *    This is the exact volume and centroid of the solid when the hexahedron's faces are planar
 *    (a brick, a trapezoidal prism, any parallelepiped); for a warped face it is the polyhedron
 *    of the two triangles that diagonal cuts the face into, not the trilinear element of
 *    pf_mesh_hex_volume (a unit cube with node 7 moved by h along z: 1 + h/3 here, 1 + h/4
 *    trilinear). The centroid is not the mean of the eight nodes unless the hexahedron is a
 *    parallelepiped.
 * Peridigm refuses a tetrahedron of negative volume (an inverted element or nodes out of Exodus
 * order); so does the reader, from the least tetrahedron volume returned here.
 * Source: Peridigm, src/io/discretization/Peridigm_GeometryUtils.cpp (tetCentroidAndVolume,
 * hexCentroidAndVolume) as used by Peridigm_ExodusDiscretization.cpp; Parks, Littlewood,
 * Mitchell & Silling, Peridigm Users' Guide v1.0.0, SAND2012-7800 (2012), §"Discretizations".
 * Exodus node order: Schoof & Yarberry, SAND92-2137 (1994). */
#include "mesh/mesh.h"

/* Signed volume of the tetrahedron a, b, c, d: (b - a) . ((c - a) x (d - a)) / 6; positive when
 * b, c, d turn counter-clockwise seen from the side opposite d (Exodus TETRA4 order). */
static double tet_volume(const double a[3], const double b[3], const double c[3], const double d[3]) {
  double u[3], v[3], w[3];
  for (int i = 0; i < 3; i++) u[i] = b[i] - a[i], v[i] = c[i] - a[i], w[i] = d[i] - a[i];
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6.0;
}

double pf_mesh_tet_point(const double x[4][3], double c[3], double *vol) {
  for (int i = 0; i < 3; i++) c[i] = (x[0][i] + x[1][i] + x[2][i] + x[3][i]) * 0.25;
  *vol = tet_volume(x[0], x[1], x[2], x[3]);
  return *vol;
}

/* Peridigm's split of a hexahedron (Exodus nodes 0..7) into six tetrahedra, all sharing the
 * diagonal 0-6 (nodes 1 and 7 in the 1-based numbering), in Peridigm's order. */
static const int hex_tets[6][4] = {{3, 4, 6, 7}, {2, 3, 4, 6}, {0, 2, 3, 4},
                                   {2, 4, 5, 6}, {0, 2, 4, 5}, {0, 1, 2, 5}};

double pf_mesh_hex_point(const double x[8][3], double c[3], double *vol) {
  double least = 0, sum[3] = {0, 0, 0};
  *vol = 0;
  for (int t = 0; t < 6; t++) {
    const int *k = hex_tets[t];
    const double xt[4][3] = {{x[k[0]][0], x[k[0]][1], x[k[0]][2]}, {x[k[1]][0], x[k[1]][1], x[k[1]][2]},
                             {x[k[2]][0], x[k[2]][1], x[k[2]][2]}, {x[k[3]][0], x[k[3]][1], x[k[3]][2]}};
    double ct[3], vt;
    pf_mesh_tet_point(xt, ct, &vt);
    *vol += vt;
    for (int i = 0; i < 3; i++) sum[i] += ct[i] * vt;
    if (t == 0 || vt < least) least = vt;
  }
  for (int i = 0; i < 3; i++) c[i] = sum[i] / *vol;
  return least;
}
