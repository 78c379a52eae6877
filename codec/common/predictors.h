// Predictors of the residual layer: what encoder and decoder both compute from values
// already decoded, so that only the prediction error is coded. format_spec/residual.md
// documents each predictor; the ids below are written to files and never change meaning.
#pragma once
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "codec/common/model.h"

namespace dcurve {

// Base prediction of frame f, per vertex and axis, from frames decoded before it (frames
// are decoded in a coding order that need not be time order, see PredictorPlan).
enum class PredictorKind : uint8_t {
  None = 0,       // zero: only useful with a spatial correction (a frame predicted from itself)
  Reference = 1,  // q[r0][v]: r0 = f - 1 is the plain temporal delta; other r0 reuse a past pose
  Linear = 2,     // the line in time through (r0, q[r0][v]) and (r1, q[r1][v]), at f, rounded:
                  // r0 = f-1, r1 = f-2 is constant velocity; r0 < f < r1 interpolates
  Model = 3,      // a grid prediction the caller supplies (the PDE motion model, evaluated
                  // on the grid by the integrator); both sides must supply the same values
  Motion = 4,     // an affine map of q[r0][v], one per cluster of vertices, stored with the
                  // cluster (codec/common/motion_compensation.h): rigid parts, repeated poses that moved
};
constexpr uint8_t kPredictorKindCount = 5;

// Spatial correction added to the base prediction, from vertices of the same frame that
// are already decoded: the error the base prediction made on them is assumed to repeat.
enum class SpatialMode : uint8_t {
  Off = 0,
  Mean = 1,           // rounded mean of the earlier neighbours' errors (Dynapack-style)
  Parallelogram = 2,  // rounded mean over the vertex's decoded parallelograms (a, b, c) of
                      // err(a) + err(b) - err(c): exact for any affine motion of the patch;
                      // Mean where the vertex has no parallelogram
  Blend = 3,          // rounded mean of the Mean and Parallelogram corrections: less noise
                      // than Parallelogram, less bias than Mean on smooth deformation
  Geometric = 4,      // Parallelogram with each (a, b, c) weighted by where v lies against
                      // it in a decoded frame g: err(a) + alpha (err(b) - err(a)) + beta
                      // (err(c) - err(a)); exact for any affine motion of the patch on an
                      // irregular mesh, where Parallelogram assumes v = a + b - c
  Fit = 5,            // the least-squares affine function of position (in a decoded frame g)
                      // through the errors of up to 16 decoded vertices of the first two
                      // rings, evaluated at v: averages the rounding noise of smooth fields
                      // (low-rank basis vectors) over many points, where the others use three
};
constexpr uint8_t kSpatialModeCount = 6;

// Whether the mode's weights come from a geometry frame g (PredictorChoice::g).
inline bool uses_geometry(SpatialMode s) { return s == SpatialMode::Geometric || s == SpatialMode::Fit; }

// The predictor of one (frame, axis).
struct PredictorChoice {
  PredictorKind kind = PredictorKind::Reference;
  uint32_t r0 = 0, r1 = 0;  // reference frames: Reference and Motion use r0, Linear r0 and r1
  SpatialMode spatial = SpatialMode::Parallelogram;
  uint32_t g = 0;  // Geometric and Fit: the decoded frame whose shape gives the weights
};

// Linear references lie within this many frames of f and of each other, so the integer
// interpolation cannot overflow.
constexpr uint32_t kMaxLinearSpan = 65535;

// Order in which vertices are decoded within a frame and, for each position, the
// neighbours that come earlier in that order (the ones a decoder already knows).
struct Traversal {
  std::vector<uint32_t> order;       // V vertex ids
  std::vector<uint32_t> nb_offsets;  // V + 1; position i's earlier neighbours: nb[nb_offsets[i], nb_offsets[i+1])
  std::vector<uint32_t> nb;          // vertex ids
  // Position i's parallelograms: para[3 * k .. 3 * k + 2] = (a, b, c) for k in
  // [para_offsets[i], para_offsets[i+1]); all three decoded before position i.
  std::vector<uint32_t> para_offsets;
  std::vector<uint32_t> para;
  // Position i's Fit set: fit[fit_offsets[i] .. fit_offsets[i+1]), at most kMaxFitPoints
  // vertices decoded before position i: its earlier neighbours, then second-ring vertices.
  std::vector<uint32_t> fit_offsets;
  std::vector<uint32_t> fit;
  bool from_faces = false;
  // CRC-32C of the arrays above, set by traversal_for for walks that draw on a
  // SpatialWeightsSource: tells the source which mesh a table belongs to. 0: not computed
  // (build_traversal alone; such a traversal's tables are never shared).
  uint32_t fingerprint = 0;
};

// Vertices in one position's Fit set, at most.
constexpr uint32_t kMaxFitPoints = 16;

// Builds the traversal: breadth-first over the mesh edges when `model.faces` is present
// (each component from its lowest vertex id; parallelograms are a face (v, a, b) and the
// face across edge (a, b)), else along the curves (the earlier neighbour is the previous
// vertex of the curve, the parallelogram (p1, p1, p2) extrapolates linearly along it).
// Needs a validated model.
Traversal build_traversal(const Model& model);
// The earlier neighbours and Fit sets of `order` (a permutation of the V vertices) over the
// edges of `faces`, by the rules of build_traversal; no parallelograms. For spatial
// predictors over another vertex order (the fast traversal's Fit, codec/common/fast_fit.h).
Traversal neighbour_traversal(const std::vector<uint32_t>& faces, std::vector<uint32_t> order);

class SpatialWeightsSource;

// The Model predictor computed one frame at a time (a decoder that keeps no table of every
// frame): writes frame f's V * 3 values (walk-local frame id, grid units) into out.
struct FastTraversal;  // codec/common/fast_traversal.h

class ModelFrameSource {
 public:
  virtual ~ModelFrameSource() = default;
  virtual void frame(uint32_t f, int32_t* out) const = 0;
};

// Extra inputs to the residual layer that are not in the payload.
struct ResidualOptions {
  // Model predictor values, frame-major ((f * V + v) * 3 + axis), grid units; null when
  // the file has no motion model. Must be bit-identical on encoder and decoder.
  const std::vector<int32_t>* model_prediction = nullptr;
  // Alternative to model_prediction (used when that is null): the same values on demand.
  const ModelFrameSource* model_frames = nullptr;
  // build_traversal(model) of the model the call codes, when the caller reuses one across
  // calls (it depends only on V and the faces or curves); null: each call builds its own.
  const Traversal* traversal = nullptr;
  // fast_traversal of the model's faces for fast payloads (format 4), when the caller has it
  // already; null: each call derives its own.
  const FastTraversal* fast_traversal = nullptr;
  // Where walks get their spatial weight tables (null: each walk computes its own). Changes
  // no value, only how often the same table is computed.
  SpatialWeightsSource* weights_source = nullptr;
  // Whether the stream flags blocks whose residuals are all zero (payload version 4) or not
  // (version 3, as in files 3.0). Readers take it from the payload's version. Writers code
  // version 3 by default: the encoder's search measures its trials so (its choices were
  // tuned on that coder), and its last step recodes the chosen payloads with the flags
  // where that is smaller (encoder/rate/block_flags.h).
  bool zero_block_flags = false;
  // The payload is a low-rank basis (LRNK's K + 1 pseudo-frames): a fast payload's kinds may
  // carry the Fit flag there (format_spec/residual.md section 10.7), nowhere else.
  bool low_rank_basis = false;
};

// options.traversal when set, else build_traversal(model) stored in *owned, with its
// fingerprint when options.weights_source is set.
const Traversal& traversal_for(const Model& model, const ResidualOptions& options, Traversal* owned);

// Whether `c` can be used for frame f: its reference frames are decoded (decoded[r] != 0,
// decoded has frame_count entries) and distinct from f, Linear spans are bounded, supplied
// data is present.
bool predictor_usable(const PredictorChoice& c, uint32_t f, const std::vector<uint8_t>& decoded,
                      const ResidualOptions& options);

// Whether the kind predicts from frame r0 (its residuals give the temporal context).
inline bool has_reference(PredictorKind k) {
  return k == PredictorKind::Reference || k == PredictorKind::Linear || k == PredictorKind::Motion;
}

// Writes the base prediction of frame f, axis a for every vertex into base[v] (grid units).
// q is frame-major with V vertices and holds the referenced frames; the choice must be usable.
// Motion writes the untransformed reference values (its map is per cluster, applied by the caller).
void base_prediction(const PredictorChoice& c, uint32_t f, int axis, uint32_t V, const int32_t* q,
                     const ResidualOptions& options, int64_t* base);

namespace detail {
// floor((2 sum + count) / (2 count)): the mean rounded half up, identical on every platform.
inline int64_t rounded_mean(int64_t sum, int64_t count) {
  const int64_t num = 2 * sum + count, den = 2 * count;
  return num >= 0 ? num / den : -((-num + den - 1) / den);
}
}  // namespace detail

// Geometric weights are in 1/kGeometricUnit, within [-kGeometricLimit, kGeometricLimit].
constexpr int32_t kGeometricUnit = 256, kGeometricLimit = 1024;

// The Geometric weights (alpha, beta) of every parallelogram of t, in t.para's order
// (2 per triple), from the decoded values qg of the geometry frame (V vertices x 3).
// Integer arithmetic throughout (format_spec/residual.md), so every platform agrees.
std::vector<int32_t> geometric_weights(const Traversal& t, const int32_t* qg);

// Fit weights are in 1/kFitUnit, within [-kFitLimit, kFitLimit].
constexpr int64_t kFitUnit = 65536, kFitLimit = int64_t(1) << 20;

// The Fit weights of every position of t, in t.fit's order (one per entry; the first of each
// position's set is 0, as its error is the origin the others' differences are added to),
// from the decoded values qg of the geometry frame. Integer arithmetic throughout.
std::vector<int32_t> fit_weights(const Traversal& t, const int32_t* qg);

// The weight table of `mode` (geometric_weights or fit_weights) from qg; empty for the modes
// that use none.
std::vector<int32_t> spatial_weights(const Traversal& t, const int32_t* qg, SpatialMode mode);

// Weight tables shared beyond one walk: an encoder's trial walks meet the same decoded
// geometry frames again and again, so most tables they ask for are repeats. weights() must
// return exactly spatial_weights(t, qg, mode); it may be called from several threads at
// once.
class SpatialWeightsSource {
 public:
  virtual ~SpatialWeightsSource() = default;
  virtual std::shared_ptr<const std::vector<int32_t>> weights(const Traversal& t, const int32_t* qg,
                                                              SpatialMode mode) = 0;
};

// The weight tables of the last few geometry frames one walk used: a frame's candidates,
// and the next frames, mostly share them. Values of a frame must not change once asked for.
class SpatialWeightsCache {
 public:
  // source (may be null): asked for every table this cache does not hold.
  explicit SpatialWeightsCache(SpatialWeightsSource* source = nullptr) : source_(source) {}
  // Weights of `mode` (Geometric or Fit) of frame g of q (frame-major, V vertices); valid
  // until kCapacity other frames were asked for.
  const int32_t* get(const Traversal& t, const int32_t* q, uint32_t g, SpatialMode mode = SpatialMode::Geometric);
  // The weights of each axis of `choice` into out[0..2], null where an axis uses none.
  void for_choice(const Traversal& t, const int32_t* q, const PredictorChoice* choice, const int32_t* out[3]);

 private:
  // A frame names at most 8 geometry frames (kMaxGeometryFrames, codec/common/residual.h), so a
  // walk computes each frame's tables once: decoding stays linear however clusters switch.
  static constexpr size_t kCapacity = 8;
  struct Entry {
    uint32_t g;
    std::shared_ptr<const std::vector<int32_t>> tables[2];  // Geometric, Fit: each when first asked for
  };
  std::vector<Entry> entries_;  // most recent last
  SpatialWeightsSource* source_;
};

// The spatial correction of traversal position `pos` on `axis`: see SpatialMode. qf is
// frame f's values (earlier positions decoded); base(u) the base prediction of vertex u on
// that axis under this position's predictor; weights the geometric_weights (Geometric) or
// fit_weights (Fit) of the choice's geometry frame (read by those two only).
template <class Base>
inline int64_t spatial_correction(SpatialMode mode, const Traversal& t, uint32_t pos, int axis, const int32_t* qf,
                                  const Base& base, const int32_t* weights = nullptr) {
  if (mode == SpatialMode::Off) return 0;
  auto err = [&](uint32_t n) { return int64_t(qf[size_t(n) * 3 + size_t(axis)]) - base(n); };
  if (mode == SpatialMode::Fit) {
    const uint32_t begin = t.fit_offsets[pos], end = t.fit_offsets[pos + 1];
    if (begin == end) return 0;
    const int64_t e0 = err(t.fit[begin]);
    // Differences clamped so the sum stays in int64 however large a base prediction is.
    constexpr int64_t kLimit = int64_t(1) << 36;
    int64_t sum = 0;
    for (uint32_t k = begin + 1; k < end; ++k) sum += weights[k] * std::clamp(err(t.fit[k]) - e0, -kLimit, kLimit);
    return e0 + detail::rounded_mean(sum, kFitUnit);
  }
  int64_t mean_sum = 0, para_sum = 0;
  const uint32_t nb_begin = t.nb_offsets[pos], nb_end = t.nb_offsets[pos + 1];
  for (uint32_t k = nb_begin; k < nb_end; ++k) mean_sum += err(t.nb[k]);
  const int64_t nb_count = int64_t(nb_end - nb_begin);
  const uint32_t p_begin = t.para_offsets[pos], p_end = t.para_offsets[pos + 1];
  const int64_t para_count = int64_t(p_end - p_begin);
  if (mode == SpatialMode::Mean || para_count == 0) return nb_count ? detail::rounded_mean(mean_sum, nb_count) : 0;
  if (mode == SpatialMode::Geometric) {
    for (uint32_t k = p_begin; k < p_end; ++k) {
      const int64_t ea = err(t.para[3 * size_t(k)]);
      para_sum += kGeometricUnit * ea + weights[2 * size_t(k)] * (err(t.para[3 * size_t(k) + 1]) - ea) +
                  weights[2 * size_t(k) + 1] * (err(t.para[3 * size_t(k) + 2]) - ea);
    }
    return detail::rounded_mean(para_sum, kGeometricUnit * para_count);
  }
  for (uint32_t k = p_begin; k < p_end; ++k)
    para_sum += err(t.para[3 * size_t(k)]) + err(t.para[3 * size_t(k) + 1]) - err(t.para[3 * size_t(k) + 2]);
  if (mode == SpatialMode::Parallelogram) return detail::rounded_mean(para_sum, para_count);
  // Blend: (mean_sum / nb_count + para_sum / para_count) / 2 as one rounding.
  return detail::rounded_mean(mean_sum * para_count + para_sum * nb_count, 2 * nb_count * para_count);
}

// Predictions (grid units) of the three axes of traversal position `pos`: base(u, a) is
// vertex u's base prediction on axis a, qf the frame's values decoded so far, weights[a]
// the geometric_weights of axis a's geometry frame (null when no axis is Geometric).
template <class Base>
inline void vertex_prediction(const PredictorChoice* choice, const Traversal& t, uint32_t pos, const int32_t* qf,
                              const Base& base, int64_t pred[3], const int32_t* const* weights = nullptr) {
  const uint32_t v = t.order[pos];
  for (int a = 0; a < 3; ++a) {
    auto ba = [&](uint32_t u) { return base(u, a); };
    // Off tested here, not only inside: most axes have no correction, and the call is not inlined.
    const SpatialMode mode = choice[a].spatial;
    pred[a] = ba(v) + (mode == SpatialMode::Off ? 0 : spatial_correction(mode, t, pos, a, qf, ba, weights ? weights[a] : nullptr));
  }
}

}  // namespace dcurve
