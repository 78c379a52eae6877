// libFuzzer entry: any bytes -> Decoder::open_memory, and when a file opens, evaluate it at
// frames and between them (through the decoder and through a cursor playing the first
// frames in order, then in-betweens under a cubic rule), with normals. A crash, sanitizer report, leak or failure without a
// message is a finding.
#include <algorithm>
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
  dcurve::Error e;
  for (double t : {0.0, 0.37, 0.5, 1.0, -3.0, 7.0})
    if (!dec->evaluate(t, xyz.data(), &e) && e.message.empty()) __builtin_trap();
  dec->evaluate_frame(dec->frame_count() - 1, xyz.data());
  auto cursor = dec->make_cursor();
  for (uint32_t f = 0; f < std::min<uint32_t>(dec->frame_count(), 40); ++f)
    if (!cursor->evaluate_frame(f, xyz.data(), &e) && e.message.empty()) __builtin_trap();
  // A cubic in-between rule reaches up to six frames in up to four chunks.
  cursor->set_interpolation(dcurve::Interpolation::Hermite4);
  for (double t : {0.37, 0.05, 0.93})
    if (!cursor->evaluate(t, xyz.data(), &e) && e.message.empty()) __builtin_trap();
  dec->compute_normals(xyz.data(), normals.data());
  return 0;
}
