/* Opens a .dcrv through the C ABI and prints its counts and the centroid at t = 0.5. */
#include <dcurve.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char** argv) {
  char err[256];
  dcurve_decoder* d = NULL;
  if (argc != 2) return 2;
  if (dcurve_open_file(argv[1], &d, err, sizeof err) != 0) {
    fprintf(stderr, "%s\n", err);
    return 1;
  }
  uint32_t n = dcurve_vertex_count(d);
  float* xyz = (float*)malloc(sizeof(float) * 3 * n);
  dcurve_evaluate(d, 0.5, xyz);
  double c[3] = {0, 0, 0};
  for (uint32_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) c[a] += xyz[3 * i + a] / n;
  printf("vertices %u frames %u faces %u centroid %.6f %.6f %.6f\n", n, dcurve_frame_count(d), dcurve_face_count(d),
         c[0], c[1], c[2]);
  free(xyz);
  dcurve_close(d);
  return 0;
}
