#include "encoder/encoder.h"

#include <chrono>
#include <cmath>

#include "codec/container.h"
#include "codec/model.h"
#include "codec/residual.h"
#include "decoder/dcurve.hpp"
#include "encoder/rate/residual_plan.h"

namespace dcurve {
namespace {

bool fail(std::string* error, const std::string& msg) {
  if (error) *error = msg;
  return false;
}

// Every vertex its own one-point curve: the trivial partition, until curve extraction lands.
Curves singleton_curves(uint32_t V) {
  Curves c;
  c.vertices.resize(V);
  c.offsets.resize(V + 1);
  c.closed.assign(V, 0);
  c.u.assign(V, 0.f);
  for (uint32_t v = 0; v < V; ++v) { c.vertices[v] = v; c.offsets[v] = v; }
  c.offsets[V] = V;
  return c;
}

}  // namespace

bool encode_animation(const Animation& anim, const EncodeOptions& opt, std::vector<uint8_t>* out,
                      EncodeReport* report, std::string* error) {
  auto start = std::chrono::steady_clock::now();
  if (!validate_animation(anim, error)) return false;
  if (!(opt.tolerance > 0 && opt.tolerance <= 0.5)) return fail(error, "tolerance must be in (0, 0.5]");
  const double L = bbox_diagonal(anim.frames[0]);
  if (!(L > 0)) return fail(error, "rest pose has a zero bounding box (all vertices coincide)");

  const uint32_t V = anim.vertex_count, F = uint32_t(anim.frames.size());
  Model m;
  m.meta = {V, F, anim.frame_rate, opt.tolerance, L, ""};
  // The residual layer's neighbour structure may only use what the file will store.
  if (opt.connectivity) m.faces = anim.faces;
  m.curves = singleton_curves(V);

  // A cubic cell of side s has half-diagonal s*sqrt(3)/2: this step keeps every rounded
  // position within tolerance * L; the small margin absorbs float32 output rounding.
  ResidualLayer& r = m.residual;
  r.step = 2.0 * opt.tolerance * L / std::sqrt(3.0) * (1.0 - 1e-3);
  for (int a = 0; a < 3; ++a) {
    double lo = anim.frames[0][a];
    for (const auto& fr : anim.frames)
      for (size_t i = a; i < fr.size(); i += 3) lo = std::min(lo, double(fr[i]));
    r.origin[a] = lo;
  }
  std::vector<int32_t> q(size_t(F) * V * 3);
  for (uint32_t f = 0; f < F; ++f)
    for (size_t i = 0; i < size_t(V) * 3; ++i) {
      double g = std::nearbyint((double(anim.frames[f][i]) - r.origin[i % 3]) / r.step);
      if (g > INT32_MAX) return fail(error, "tolerance too small for the motion range (grid overflow)");
      q[f * size_t(V) * 3 + i] = int32_t(g);
    }
  const PredictorPlan plan = choose_plan_and_grid(m, anim.frames, opt.tolerance * L, &q);
  r.payload = encode_residuals(m, q, &plan);
  if (opt.progress) opt.progress(0.5);

  WriteOptions wo;
  wo.connectivity = opt.connectivity;
  *out = write_container(m, wo);

  // Closed loop: decode what was written with the runtime decoder and measure.
  std::string derr;
  auto dec = Decoder::open_memory(out->data(), out->size(), &derr);
  if (!dec) return fail(error, "internal error: written file does not decode: " + derr);
  std::vector<std::vector<float>> decoded(F, std::vector<float>(size_t(V) * 3));
  for (uint32_t f = 0; f < F; ++f) dec->evaluate_frame(f, decoded[f].data());
  EncodeReport rep;
  rep.error = measure_error(anim, decoded);
  if (rep.error.max_error > opt.tolerance)
    return fail(error, "internal error: decoded max error " + std::to_string(rep.error.max_error) +
                           " exceeds the tolerance");
  std::vector<SectionInfo> sections;
  Model check;
  read_container(out->data(), out->size(), &check, nullptr, &sections);
  rep.bytes = out->size();
  for (const auto& s : sections)
    if (s.tag == "FACE") rep.connectivity_bytes += s.stored_bytes + 28;
  rep.motion_bytes = rep.bytes - rep.connectivity_bytes;
  rep.vertices = V;
  rep.frames = F;
  rep.curves = m.curves.curve_count();
  rep.segments = uint32_t(m.segments.size());
  rep.bpvf = 8.0 * double(rep.bytes) / (double(V) * F);
  rep.mean_points_per_curve = rep.median_points_per_curve = 1;
  rep.short_curve_vertex_fraction = 1;
  rep.encode_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (opt.progress) opt.progress(1.0);
  if (report) *report = rep;
  return true;
}

}  // namespace dcurve
