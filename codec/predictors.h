// Predictors of the residual layer: what encoder and decoder both compute from values
// already decoded, so that only the prediction error is coded. format_spec/residual.md
// documents each predictor; the ids below are written to files and never change meaning.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/model.h"

namespace dcurve {

// Base prediction of frame f, per vertex and axis, from earlier frames.
enum class PredictorKind : uint8_t {
  None = 0,         // zero: only useful with neighbour correction (frame 0: spatial prediction)
  Reference = 1,    // q[f - d][v]: d = 1 is the plain temporal delta; larger d reuses a past pose
  SecondOrder = 2,  // 2 q[f-1][v] - q[f-2][v]: constant velocity
  Model = 3,        // a grid prediction the caller supplies (the PDE motion model, evaluated
                    // on the grid by the integrator); both sides must supply the same values
};
constexpr uint8_t kPredictorKindCount = 4;

// The predictor of one (frame, axis).
struct PredictorChoice {
  PredictorKind kind = PredictorKind::Reference;
  uint32_t ref_distance = 1;  // Reference only: 1 <= d <= f
  // Adds the rounded mean of the already-decoded neighbours' errors of the base prediction
  // (Dynapack-style): motion shared by a neighbourhood is predicted, only its variation is coded.
  bool neighbours = true;
};

// Order in which vertices are decoded within a frame and, for each position, the
// neighbours that come earlier in that order (the ones a decoder already knows).
struct Traversal {
  std::vector<uint32_t> order;       // V vertex ids
  std::vector<uint32_t> nb_offsets;  // V + 1; position i's earlier neighbours: nb[nb_offsets[i], nb_offsets[i+1])
  std::vector<uint32_t> nb;          // vertex ids
  bool from_faces = false;
};

// Builds the traversal: breadth-first over the mesh edges when `model.faces` is present
// (each component from its lowest vertex id), else along the curves (a vertex's earlier
// neighbour is the previous vertex of its curve). Needs a validated model.
Traversal build_traversal(const Model& model);

// Extra inputs to the residual layer that are not in the payload.
struct ResidualOptions {
  // Model predictor values, frame-major ((f * V + v) * 3 + axis), grid units; null when
  // the file has no motion model. Must be bit-identical on encoder and decoder.
  const std::vector<int32_t>* model_prediction = nullptr;
};

// Whether `c` can be used for frame f (refers only to earlier frames and supplied data).
bool predictor_usable(const PredictorChoice& c, uint32_t f, const ResidualOptions& options);

// Writes the base prediction of frame f, axis a for every vertex into base[v] (grid units).
// q holds at least frames [0, f) frame-major with V vertices; the choice must be usable.
void base_prediction(const PredictorChoice& c, uint32_t f, int axis, uint32_t V, const int32_t* q,
                     const ResidualOptions& options, int64_t* base);

// Rounded mean of (qf[n*3+axis] - base[n]) over the earlier neighbours of traversal
// position `pos`; 0 when it has none. qf is frame f's values (earlier positions decoded).
inline int64_t neighbour_correction(const Traversal& t, uint32_t pos, int axis, const int32_t* qf,
                                    const int64_t* base) {
  const uint32_t begin = t.nb_offsets[pos], end = t.nb_offsets[pos + 1];
  if (begin == end) return 0;
  int64_t sum = 0;
  for (uint32_t k = begin; k < end; ++k) {
    const uint32_t n = t.nb[k];
    sum += int64_t(qf[size_t(n) * 3 + size_t(axis)]) - base[n];
  }
  // floor((2 sum + count) / (2 count)): round half up, identical on every platform.
  const int64_t count = int64_t(end - begin), num = 2 * sum + count, den = 2 * count;
  return num >= 0 ? num / den : -((-num + den - 1) / den);
}

}  // namespace dcurve
