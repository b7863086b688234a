/* Influence functions omega(|xi|), chosen by name in the deck: constant, 1/|xi|, and the
 * Gaussian exp(-|xi|^2 / sigma^2) of Tupek et al. (2013), eq. 7. */
#include "pd/pd_impl.h"

#include <string.h>

#define PF_INFLUENCE_LIST(X)                                                                       \
  X("constant", PF_INFLUENCE_CONSTANT)                                                             \
  X("inverse_distance", PF_INFLUENCE_INVERSE_DISTANCE)                                             \
  X("gaussian", PF_INFLUENCE_GAUSSIAN)

int pf_pd_influence_by_name(const char *name, pf_influence_kind *kind) {
#define MATCH(str, id)                                                                             \
  if (!strcmp(name, str)) {                                                                        \
    *kind = id;                                                                                    \
    return 0;                                                                                      \
  }
  PF_INFLUENCE_LIST(MATCH)
#undef MATCH
  return PF_ERR_INPUT;
}

const char *pf_pd_influence_names(void) {
#define NAME(str, id) str " "
  return PF_INFLUENCE_LIST(NAME);
#undef NAME
}


/* 4 pi int_0^delta omega(r) r^p dr with 20-point Gauss-Legendre on 8 sub-intervals: exact for
 * polynomial integrands of the degrees used here, 1e-15 relative for the Gaussian. */
double pf_pd_influence_moment(const pf_influence *w, double delta, int p) {
  static const double x[10] = {0.0765265211334973, 0.2277858511416451, 0.3737060887154195,
                               0.5108670019508271, 0.6360536807265150, 0.7463319064601508,
                               0.8391169718222188, 0.9122344282513259, 0.9639719272779138,
                               0.9931285991850949};
  static const double wt[10] = {0.1527533871307258, 0.1491729864726037, 0.1420961093183820,
                                0.1316886384491766, 0.1181945319615184, 0.1019301198172404,
                                0.0832767415767048, 0.0626720483341091, 0.0406014298003869,
                                0.0176140071391521};
  const int nsub = 8;
  double sum = 0, hsub = delta / nsub;
  for (int s = 0; s < nsub; s++) {
    double mid = (s + 0.5) * hsub, half = 0.5 * hsub;
    for (int k = 0; k < 10; k++)
      for (int sign = -1; sign <= 1; sign += 2) {
        double r = mid + sign * half * x[k];
        sum += half * wt[k] * pf_pd_omega(w, r) * pow(r, p);
      }
  }
  return 4 * PF_PI * sum;
}
