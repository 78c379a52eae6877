/* The native side of the web tests and benchmark, through the C API (decoder/dcurve.h):
 *   dcurve_web_native positions FILE T...   one line per t: t, then vertex_count * 3 floats
 *   dcurve_web_native bench FILE [PASSES]   median ms per frame of playing every frame in
 *                                           order through a fresh cursor (open not timed)
 *   dcurve_web_native status-names          one line per code from -1 to 7: code, then its
 *                                           dcurve_status_name
 * web/test/viewer.browser.test.mjs compares the page's positions with the first,
 * web/bench.mjs the browser's per-frame time with the second, web/test/status.test.mjs the
 * wasm's status names with the third. Exit status 1 with a message on a bad file. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dcurve.h"

static unsigned char* read_file(const char* path, size_t* size) {
  FILE* f = fopen(path, "rb");
  if (!f) return NULL;
  unsigned char* data = NULL;
  if (fseek(f, 0, SEEK_END) == 0) {
    long n = ftell(f);
    data = n >= 0 ? malloc((size_t)n + 1) : NULL;
    *size = (size_t)n;
    if (data && (fseek(f, 0, SEEK_SET) != 0 || fread(data, 1, *size, f) != *size)) {
      free(data);
      data = NULL;
    }
  }
  fclose(f);
  return data;
}

static double now_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int compare_doubles(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

static int print_positions(dcurve_cursor* c, float* xyz, uint32_t values, int count, char** times, char* err) {
  for (int i = 0; i < count; ++i) {
    double t = atof(times[i]);
    if (dcurve_cursor_evaluate(c, t, xyz, err, 256)) return 1;
    printf("%.9g", t);
    for (uint32_t k = 0; k < values; ++k) printf(" %.9g", xyz[k]);
    printf("\n");
  }
  return 0;
}

/* One pass: a fresh cursor plays every frame in order; returns its ms per frame, < 0 on error. */
static double play_once(dcurve_decoder* d, float* xyz, char* err) {
  dcurve_cursor* c;
  if (dcurve_cursor_create(d, &c)) return -1;
  uint32_t frames = dcurve_frame_count(d);
  double start = now_ms();
  for (uint32_t f = 0; f < frames; ++f)
    if (dcurve_cursor_evaluate_frame(c, f, xyz, err, 256)) {
      dcurve_cursor_destroy(c);
      return -1;
    }
  double ms = (now_ms() - start) / (frames ? frames : 1);
  dcurve_cursor_destroy(c);
  return ms;
}

static int bench(dcurve_decoder* d, float* xyz, int passes, char* err) {
  double* ms = malloc(sizeof(double) * (size_t)passes);
  if (!ms) return 1;
  for (int p = 0; p < passes; ++p)
    if ((ms[p] = play_once(d, xyz, err)) < 0) {
      free(ms);
      return 1;
    }
  qsort(ms, (size_t)passes, sizeof(double), compare_doubles);
  printf("{\"vertices\": %u, \"frames\": %u, \"passes\": %d, \"ms_per_frame\": %.6f}\n", dcurve_vertex_count(d),
         dcurve_frame_count(d), passes, ms[passes / 2]);
  free(ms);
  return 0;
}

int main(int argc, char** argv) {
  if (argc == 2 && !strcmp(argv[1], "status-names")) {
    for (int code = -1; code <= 7; ++code) printf("%d %s\n", code, dcurve_status_name(code));
    return 0;
  }
  if (argc < 3 || (strcmp(argv[1], "positions") && strcmp(argv[1], "bench"))) {
    fprintf(stderr, "usage: %s positions FILE T... | bench FILE [PASSES] | status-names\n", argv[0]);
    return 2;
  }
  size_t size = 0;
  unsigned char* data = read_file(argv[2], &size);
  if (!data) {
    fprintf(stderr, "dcurve_web_native: %s: cannot read\n", argv[2]);
    return 1;
  }
  char err[256] = "";
  dcurve_decoder* d = NULL;
  dcurve_cursor* c = NULL;
  int status = dcurve_open_memory(data, size, &d, err, sizeof err);
  free(data);
  float* xyz = status ? NULL : malloc(sizeof(float) * 3 * (dcurve_vertex_count(d) + 1));
  if (!status && xyz) {
    if (!strcmp(argv[1], "bench"))
      status = bench(d, xyz, argc > 3 ? atoi(argv[3]) > 0 ? atoi(argv[3]) : 1 : 5, err);
    else if (!(status = dcurve_cursor_create(d, &c)))
      status = print_positions(c, xyz, 3 * dcurve_vertex_count(d), argc - 3, argv + 3, err);
  }
  if (status) fprintf(stderr, "dcurve_web_native: %s: %s\n", argv[2], err[0] ? err : "failed");
  dcurve_cursor_destroy(c);
  dcurve_close(d);
  free(xyz);
  return status ? 1 : 0;
}
