// Quantized temporal delta: positions rounded to the cubic grid whose half cell diagonal is
// the tolerance (step 2*E*L/sqrt(3)), each frame minus the previous, int32 little-endian,
// zstd. The strongest simple baseline of DESIGN.md sec. 6. The integers are laid out in the
// one of three orders that zstd packs smallest (a one-byte tag says which).
#include <cmath>

#include "bench/baselines.h"
#include "bench/zstd_blob.h"

namespace dcurve::bench {
namespace {

enum class Layout : uint8_t { kFrameMajor = 0, kAxisPlanes = 1, kBytePlanes = 2 };
const char* const kLayoutNames[] = {"frame-major xyz", "axis planes", "byte planes of axis planes"};
constexpr size_t kDeltaHeaderBytes = 1 + 4 * 8 + 2 * 4;  // layout, origin xyz + step, V and F

// deltas[(f * V + v) * 3 + a] rearranged per `layout`, as bytes.
std::vector<uint8_t> arrange(const std::vector<int32_t>& deltas, size_t VF, Layout layout) {
  std::vector<int32_t> order;
  if (layout == Layout::kFrameMajor) {
    order = deltas;
  } else {
    order.reserve(deltas.size());
    for (int a = 0; a < 3; ++a)
      for (size_t i = 0; i < VF; ++i) order.push_back(deltas[3 * i + a]);
  }
  std::vector<uint8_t> bytes;
  append_int32_le(order, &bytes);
  return layout == Layout::kBytePlanes ? to_byte_planes(bytes) : bytes;
}

std::vector<int32_t> unarrange(const std::vector<uint8_t>& bytes, size_t VF, Layout layout) {
  const size_t n = VF * 3;
  const std::vector<uint8_t> le = layout == Layout::kBytePlanes ? from_byte_planes(bytes) : bytes;
  std::vector<int32_t> order = read_int32_le(le.data(), n);
  if (layout == Layout::kFrameMajor) return order;
  std::vector<int32_t> deltas(n);
  for (int a = 0; a < 3; ++a)
    for (size_t i = 0; i < VF; ++i) deltas[3 * i + a] = order[a * VF + i];
  return deltas;
}

}  // namespace

bool bench_quantized_delta(const BenchContext& ctx, MethodResult* r, std::string* error) {
  const auto start = std::chrono::steady_clock::now();
  const auto& frames = ctx.anim.frames;
  const size_t F = frames.size(), V3 = size_t(ctx.anim.vertex_count) * 3, VF = F * ctx.anim.vertex_count;
  // The small margin absorbs float32 rounding of the decoded positions (as the encoder does).
  const double step = 2.0 * ctx.tolerance * ctx.diagonal / std::sqrt(3.0) * (1.0 - 1e-3);
  double origin[3];
  for (int a = 0; a < 3; ++a) {
    origin[a] = frames[0][a];
    for (const auto& fr : frames)
      for (size_t i = a; i < V3; i += 3) origin[a] = std::min(origin[a], double(fr[i]));
  }
  std::vector<int32_t> deltas(F * V3), prev(V3, 0);
  for (size_t f = 0; f < F; ++f)
    for (size_t i = 0; i < V3; ++i) {
      int32_t q;
      if (!quantize(frames[f][i] - origin[i % 3], step, &q)) {
        *error = "tolerance too small for the motion range (grid overflow)";
        return false;
      }
      deltas[f * V3 + i] = int32_t(uint32_t(q) - uint32_t(prev[i]));
      prev[i] = q;
    }
  // Candidates are ranked at the final level: lower levels rank these layouts differently.
  Layout layout = Layout::kFrameMajor;
  std::vector<uint8_t> blob;
  std::string sizes;  // every layout's payload, so the settings show what the choice won
  for (Layout l : {Layout::kFrameMajor, Layout::kAxisPlanes, Layout::kBytePlanes}) {
    const std::vector<uint8_t> bytes = arrange(deltas, VF, l);
    std::vector<uint8_t> packed = zstd_pack(bytes.data(), bytes.size());
    sizes += (sizes.empty() ? "" : "/") + std::to_string(packed.size());
    if (blob.empty() || packed.size() < blob.size()) {
      blob = std::move(packed);
      layout = l;
    }
  }
  r->encode_seconds = seconds_since(start);

  std::vector<std::vector<float>> decoded(F, std::vector<float>(V3));
  std::vector<uint8_t> bytes;
  auto decode_all = [&]() {
    if (!zstd_unpack(blob, F * V3 * 4, &bytes, error)) return false;
    const std::vector<int32_t> d = unarrange(bytes, VF, layout);
    std::vector<int32_t> q(V3, 0);
    for (size_t f = 0; f < F; ++f)
      for (size_t i = 0; i < V3; ++i) {
        q[i] = int32_t(uint32_t(q[i]) + uint32_t(d[f * V3 + i]));
        decoded[f][i] = float(origin[i % 3] + double(q[i]) * step);
      }
    return true;
  };
  if (!decode_all()) return false;
  set_measures(ctx, decoded, blob.size() + kDeltaHeaderBytes + ctx.connectivity_charge, ctx.connectivity_charge, r);
  r->decode_vertices_per_second = decode_rate(ctx, decode_all);
  char buf[256];
  std::snprintf(buf, sizeof buf, "grid step %.4g (2EL/sqrt3), %s, zstd %d (payload B frame-major/axis/byte planes %s)",
                step, kLayoutNames[int(layout)], kBaselineZstdLevel, sizes.c_str());
  r->settings = buf;
  return true;
}

}  // namespace dcurve::bench
