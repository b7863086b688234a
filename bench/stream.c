/* A STREAM-like memory bandwidth probe (McCalpin's triad, a[i] = b[i] + s c[i]) for the bench
 * table: one thread, arrays of 3 x 160 MB (far beyond the caches), the best of ten passes,
 * counting 24 bytes per element (two reads and one write; the write-allocate read is not
 * counted, as in STREAM).
 *
 *   cc -O3 -march=native bench/stream.c -o stream && ./stream      # prints "triad GB/s X"
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(void) {
  const size_t n = 20u * 1000u * 1000u;
  double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b), *c = malloc(n * sizeof *c);
  if (!a || !b || !c) {
    fprintf(stderr, "stream: out of memory\n");
    return 1;
  }
  for (size_t i = 0; i < n; i++) a[i] = 0.0, b[i] = 1.0, c[i] = 2.0;
  double best = 1e30, s = 3.0;
  for (int pass = 0; pass < 10; pass++) {
    double t0 = now();
    for (size_t i = 0; i < n; i++) a[i] = b[i] + s * c[i];
    double t = now() - t0;
    if (t < best) best = t;
    s = a[n / 2] > 0 ? 3.0 : 2.0; /* keeps the passes from being merged */
  }
  printf("triad GB/s %.2f\n", 24.0 * (double)n / best / 1e9);
  free(a), free(b), free(c);
  return 0;
}
