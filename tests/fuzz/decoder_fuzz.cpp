// libFuzzer entry: any bytes -> Decoder::open_memory, and when a file opens, evaluate it at
// frames and between them, with normals. A crash, sanitizer report or leak is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dcurve.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string error;
  auto dec = dcurve::Decoder::open_memory(data, size, &error);
  if (!dec) {
    if (error.empty()) __builtin_trap();  // every rejection must say why
    return 0;
  }
  std::vector<float> xyz(size_t(dec->vertex_count()) * 3), normals(xyz.size());
  for (double t : {0.0, 0.37, 0.5, 1.0, -3.0, 7.0}) dec->evaluate(t, xyz.data());
  dec->evaluate_frame(dec->frame_count() - 1, xyz.data());
  dec->compute_normals(xyz.data(), normals.data());
  return 0;
}
