// Opens a .dcrv through the C++ API; exits non-zero unless evaluation matches the stored frame.
#include <dcurve.hpp>

#include <cstdio>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  std::string err;
  auto d = dcurve::Decoder::open_file(argv[1], &err);
  if (!d) {
    std::fprintf(stderr, "%s\n", err.c_str());
    return 1;
  }
  std::vector<float> a(3 * size_t(d->vertex_count())), b(a.size());
  d->evaluate(0.0, a.data());
  d->evaluate_frame(0, b.data());
  std::printf("vertices %u frames %u\n", d->vertex_count(), d->frame_count());
  return a == b ? 0 : 1;
}
