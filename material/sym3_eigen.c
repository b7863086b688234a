/* The eigen-decomposition of PF_SYM3_LANES symmetric 3x3 matrices at once, one matrix per vector
 * lane: cyclic Jacobi (Golub & Van Loan 2013, Matrix Computations, 4th ed., sec. 8.5, Algorithms
 * 8.5.1 "sym.schur2" and 8.5.3 "cyclic Jacobi"). Each rotation J(p, q, theta) zeros a_pq with
 *   tht = (a_qq - a_pp) / (2 a_pq),  t = sign(tht) / (|tht| + sqrt(1 + tht^2)),
 *   c = 1/sqrt(1 + t^2),  s = t c,   a <- J^T a J,   V <- V J,
 * i.e. a_pp -= t a_pq, a_qq += t a_pq, a_rp, a_rq rotated by (c, s). On return
 * a_in = V diag(w) V^T, the columns of V orthonormal eigenvectors. Off-diagonal entries at most
 * 1e-22 |a|_F are set to zero instead of rotated (their effect on w is below round-off); a
 * matrix's sweeps stop when a sweep rotates nothing (quadratic convergence: a few sweeps).
 *
 * Every lane takes the operations the one-matrix algorithm takes, in the same order: a lane
 * whose matrix does not rotate keeps its entries (a select, not a branch), and the sweeps go on
 * while any lane rotates, which leaves a converged lane (all off-diagonal entries zero) as it
 * was. So each lane's bits are those of the matrix decomposed alone, and the divisions and
 * square roots of the lanes run in the vector units instead of one dependent chain each. */
#include "material/material_impl.h"

enum { L = PF_SYM3_LANES };

/* One rotation (p, q) of every lane; returns whether any lane rotated. */
static int rotate(double a[3][3][L], double V[3][3][L], const double tiny[L], int p, int q) {
  const int r = 3 - p - q;
  int any = 0;
#pragma omp simd reduction(| : any)
  for (int l = 0; l < L; l++) {
    const double apq = a[p][q][l];
    const int rot = (apq != 0.0) & !(fabs(apq) <= tiny[l]); /* (& not &&: no branch) */
    const double tht = (a[q][q][l] - a[p][p][l]) / (2.0 * apq);
    const double t_far = 0.5 / tht, t_near = (tht >= 0 ? 1.0 : -1.0) / (fabs(tht) + sqrt(1.0 + tht * tht));
    const double t = fabs(tht) > 1e150 ? t_far : t_near; /* (both formed: no branch in the lanes) */
    const double c = 1.0 / sqrt(1.0 + t * t), s = t * c;
    const double app = a[p][p][l] - t * apq, aqq = a[q][q][l] + t * apq;
    const double arp = a[r][p][l], arq = a[r][q][l];
    const double nrp = c * arp - s * arq, nrq = s * arp + c * arq;
    a[p][p][l] = rot ? app : a[p][p][l];
    a[q][q][l] = rot ? aqq : a[q][q][l];
    a[p][q][l] = a[q][p][l] = apq == 0.0 ? apq : 0.0; /* rotated away, or tiny */
    a[r][p][l] = a[p][r][l] = rot ? nrp : arp;
    a[r][q][l] = a[q][r][l] = rot ? nrq : arq;
    for (int i = 0; i < 3; i++) {
      const double vp = V[i][p][l], vq = V[i][q][l];
      const double np = c * vp - s * vq, nq = s * vp + c * vq;
      V[i][p][l] = rot ? np : vp;
      V[i][q][l] = rot ? nq : vq;
    }
    any |= rot;
  }
  return any;
}

void pf_sym3_eigen_lanes(double a[3][3][PF_SYM3_LANES], double w[3][PF_SYM3_LANES],
                         double V[3][3][PF_SYM3_LANES]) {
  _Alignas(64) double tiny[L];
  for (int l = 0; l < L; l++) {
    double fro = 0.0;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) fro += a[i][j][l] * a[i][j][l];
    tiny[l] = 1e-22 * sqrt(fro);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) V[i][j][l] = i == j ? 1.0 : 0.0;
  }
  static const int P[3] = {0, 0, 1}, Q[3] = {1, 2, 2};
  for (int sweep = 0; sweep < 50; sweep++) {
    int rotated = 0;
    for (int k = 0; k < 3; k++) rotated |= rotate(a, V, tiny, P[k], Q[k]);
    if (!rotated) break;
  }
  for (int i = 0; i < 3; i++)
    for (int l = 0; l < L; l++) w[i][l] = a[i][i][l];
}
