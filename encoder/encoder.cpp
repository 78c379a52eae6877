#include "encoder/encoder.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "codec/container.h"
#include "codec/error.h"
#include "codec/faces.h"
#include "codec/model.h"
#include "codec/residual.h"
#include "decoder/dcurve.hpp"
#include "decoder/model_prediction.h"
#include "encoder/curves/extract.h"
#include "encoder/curves/report.h"
#include "encoder/rate/grid.h"
#include "encoder/rate/low_rank_choice.h"
#include "encoder/rate/motion_model.h"
#include "encoder/rate/residual_plan.h"

namespace dcurve {
namespace {

// Every vertex its own one-point curve: always a valid partition, used when nothing reads
// the curves, or when extraction cannot handle the mesh (non-manifold input); the residual
// layer then predicts from faces.
Curves singleton_curves(uint32_t V) {
  Curves c;
  c.vertices.resize(V);
  c.offsets.resize(V + 1);
  c.closed.assign(V, 0);
  c.u.assign(V, 0.f);
  for (uint32_t v = 0; v < V; ++v) c.vertices[v] = c.offsets[v] = v;
  c.offsets[V] = V;
  return c;
}

// The input's face order or the face coder's traversal order, whichever gives the smaller
// FACE section (each with its best layout): traversal wins on irregular meshes (Compact
// codes it 2-4x smaller than the input order), a regular grid's own order can beat it.
// Comparing FACE sections, not whole files: the residual coder's neighbours also follow the
// face order, but coding the residual twice to find out would double the encoding time.
std::vector<uint32_t> smaller_face_order(const std::vector<uint32_t>& faces) {
  std::vector<uint32_t> trav = traversal_order(faces);
  return face_payload_bytes(trav) < face_payload_bytes(faces) ? trav : faces;
}

// How far the residual layer may move a grid value from the input: the tolerance, less what
// the decoder's float32 output can add (a few roundings of the largest coordinate).
double snap_distance(const Animation& anim, double max_distance) {
  double largest = 0;
  for (const auto& frame : anim.frames)
    for (float x : frame) largest = std::max(largest, double(std::fabs(x)));
  return max_distance - 4.0 * std::sqrt(3.0) * largest * std::ldexp(1.0, -24);
}

// Decodes `bytes` with the runtime decoder at every input frame time and measures it: the
// only error figure the encoder reports.
bool measure_decoded(const std::vector<uint8_t>& bytes, const Animation& anim, ErrorStats* stats,
                     std::string* error) {
  std::string derr;
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &derr);
  if (!dec) return fail(error, "internal error: written file does not decode: " + derr);
  const uint32_t F = uint32_t(anim.frames.size());
  std::vector<std::vector<float>> decoded(F, std::vector<float>(size_t(anim.vertex_count) * 3));
  for (uint32_t f = 0; f < F; ++f) dec->evaluate(F > 1 ? double(f) / (F - 1) : 0.0, decoded[f].data());
  *stats = measure_error(anim, decoded);
  return true;
}

}  // namespace

bool encode_animation(const Animation& anim, const EncodeOptions& opt, std::vector<uint8_t>* out,
                      EncodeReport* report, std::string* error) {
  auto start = std::chrono::steady_clock::now();
  auto progress = [&](double f) { if (opt.progress) opt.progress(f); };
  if (!validate_animation(anim, error)) return false;
  if (!(opt.tolerance > 0 && opt.tolerance <= 0.5)) return fail(error, "tolerance must be in (0, 0.5]");
  if (opt.segment_frames == 0) return fail(error, "segment length must be at least one frame");
  if (opt.curve_points < 2) return fail(error, "target curve length must be at least 2 points");
  if (opt.low_rank < -1 || opt.low_rank > 64) return fail(error, "low-rank setting must be -1 (auto), 0 (off) or 1..64");
  const double L = bbox_diagonal(anim.frames[0]);
  if (!(L > 0)) return fail(error, "rest pose has a zero bounding box (all vertices coincide)");

  const uint32_t V = anim.vertex_count, F = uint32_t(anim.frames.size());
  EncodeReport rep;
  Model m;
  m.meta = {V, F, anim.frame_rate, opt.tolerance, L, ""};
  // The residual layer predicts from mesh neighbours when the file stores faces, and from
  // curve neighbours otherwise: it must see exactly what the decoder will.
  if (opt.connectivity) m.faces = opt.exact_face_order ? anim.faces : smaller_face_order(anim.faces);

  // Curves carry the motion model and, in a file without faces, the residual layer's
  // neighbours; otherwise the decoder never reads them, and one-vertex curves cost a few
  // bytes where the extracted ones took 18 % of a horse-gallop file.
  if (opt.model == ModelChoice::None && opt.connectivity) {
    m.curves = singleton_curves(V);
  } else {
    CurveOptions co;
    co.target_points = opt.curve_points;
    std::string curve_error;
    if (!extract_curves(anim.frames[0], V, anim.faces, co, &m.curves, &curve_error)) {
      m.curves = singleton_curves(V);
      rep.curve_fallback = curve_error;
    }
  }
  progress(0.1);

  if (opt.model != ModelChoice::None) {
    MotionModelOptions mo;
    mo.basis = opt.model == ModelChoice::Pde32 ? Basis::Pde32 : Basis::Pde8;
    mo.segment_frames = opt.segment_frames;
    mo.threads = opt.threads;
    // A tenth of the tolerance: the residual layer absorbs it at the frames, and in-betweens
    // stay within a tenth of the tolerance of the unrounded fit.
    mo.coefficient_error = 0.1 * opt.tolerance * L;
    if (!fit_motion_model(anim, m.curves, anim.frames[0], mo, &m.segments, error)) return false;
  }
  progress(0.6);

  m.residual = choose_grid(m, anim, opt.tolerance * L, opt.threads);
  std::vector<int32_t> q, prediction;
  if (!quantize_to_grid(anim, m.residual, &q, error)) return false;
  const std::vector<int32_t> rounded = q;
  ResidualOptions ro;
  if (has_model_prediction(m)) {
    // The model's own frames on the grid: the residual layer's Model predictor, computed
    // by the decoder's code from the model as the file stores it (written and read back:
    // the in-memory model differs in the last bits), so both sides agree bit for bit.
    const std::vector<uint8_t> stored_bytes = write_container(m);
    Model stored;
    if (!read_container(stored_bytes.data(), stored_bytes.size(), &stored, error)) return false;
    if (!model_grid_prediction(stored, UINT64_MAX, &prediction, error)) return false;
    ro.model_prediction = &prediction;
  }
  const double snap = snap_distance(anim, opt.tolerance * L);
  ResidualPlanOptions po;
  po.threads = opt.threads;
  const PredictorPlan plan = choose_plan_and_grid(m, anim.frames, snap, &q, ro, po);
  m.residual.payload = encode_residuals(m, q, &plan, ro);
  if (m.residual.payload.empty()) return fail(error, "internal error: the residual plan is invalid");
  progress(0.75);

  WriteOptions wo;
  wo.connectivity = opt.connectivity;
  LowRankChoiceOptions lro;
  lro.components = opt.low_rank;
  if (!choose_low_rank(&m, anim.frames, rounded, snap, wo, lro, nullptr, error)) return false;
  progress(0.9);
  *out = write_container(m, wo);

  if (!measure_decoded(*out, anim, &rep.error, error)) return false;
  if (rep.error.max_error > opt.tolerance)
    return fail(error, "internal error: decoded max error " + std::to_string(rep.error.max_error) +
                           " exceeds the tolerance");
  rep.bytes = out->size();
  std::vector<SectionInfo> sections;
  Model written;
  if (!read_container(out->data(), out->size(), &written, error, &sections)) return false;
  rep.connectivity_bytes = connectivity_bytes(sections);
  rep.low_rank_components = m.low_rank.components;
  for (const SectionInfo& s : sections) {
    if (s.tag == "LRNK") rep.low_rank_bytes = s.stored_bytes + kSectionHeaderBytes;
    if (s.tag == "SEGS" && !m.segments.empty()) rep.model_bytes = s.raw_bytes;
  }
  rep.motion_bytes = rep.bytes - rep.connectivity_bytes;
  rep.vertices = V;
  rep.frames = F;
  rep.segments = uint32_t(m.segments.size());
  rep.bpvf = 8.0 * double(rep.bytes) / (double(V) * F);
  rep.curves = curve_report(m.curves, anim.frames[0]);
  rep.encode_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  progress(1.0);
  if (report) *report = rep;
  return true;
}

}  // namespace dcurve
