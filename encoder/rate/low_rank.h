// Principal components of an animation on the residual grid, and their quantization into a
// file's low-rank model (codec/common/low_rank.h, format_spec/dcrv.md section 10).
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/model.h"
#include "codec/common/predictors.h"
#include "encoder/rate/coded_residual.h"

namespace dcurve {

// The origin of the components: the frame average (classic PCA), or a frame of the input.
constexpr uint32_t kMeanAnchor = UINT32_MAX;

// X = mean + sum_k weights[k] (x) amplitudes[k], all in grid units: frame f, coordinate i
// (= v * 3 + axis) is mean[i] + sum_k weights[k][f] * amplitudes[k][i]. Weights have unit
// RMS over the frames; amplitudes carry the component's size. Components by falling energy.
// `mean` is the anchor's values: the frame average, or frame `anchor`'s (integers).
struct GridComponents {
  std::vector<double> mean;                    // n
  std::vector<std::vector<double>> weights;    // K x F
  std::vector<std::vector<double>> amplitudes; // K x n
  uint32_t anchor = kMeanAnchor;
  // Empty, or the frame poses the components are posed by (LowRankModel::poses): the values
  // above are then those of the frames carried into a common pose (encoder/rate/frame_poses.h),
  // and quantize_low_rank stores the poses with the model.
  std::vector<int32_t> poses;
  int32_t pose_centre[3] = {0, 0, 0};
};

// PCA of the grid values q (frame-major, F frames of n values) through the F x F Gram matrix
// (cheap when F is small next to n), keeping at most max_components components with
// non-negligible energy. anchor: kMeanAnchor centres on the frame average; a frame index
// (< F) takes the components of the differences to that frame instead, which the frame
// itself then predicts exactly. Deterministic.
GridComponents grid_components(const std::vector<int32_t>& q, uint32_t F, size_t n, uint32_t max_components,
                               uint32_t anchor = kMeanAnchor);

// Bytes of `values` (V * 3 grid values) coded as an LRNK basis payload's pseudo-frame 0
// alone, as quantize_low_rank codes it: with the spatial mode that codes it smallest.
// traversal (may be null): build_traversal(model), when the caller has it already.
size_t anchor_bytes(const Model& model, std::vector<int32_t> values, int threads,
                    const Traversal* traversal = nullptr);

// Basis vectors quantize_low_rank has chosen for one GridComponents and model, by basis step
// and mean shift: a vector's coded values and spatial mode depend on those, the mean and its
// own amplitudes only, not on how many components follow, so a screening over component
// counts chooses each vector once. Opaque to callers; bound to the first components and
// model it is used with.
struct BasisMemo {
  struct Entry {
    double basis_step = 0;
    uint32_t mean_shift = 0;
    SpatialMode mean_mode = SpatialMode::Off;
    std::vector<SpatialMode> modes;  // of the components chosen so far, in order
    std::vector<int32_t> values;     // their values, V * 3 each
  };
  std::vector<Entry> entries;
};

// Quantizes the first K components (K <= pca.weights.size()) into model->low_rank: basis
// values on a step of basis_step grid units, the mean on 2^-mean_shift grid units, the
// coefficients fine enough that their rounding moves a prediction by at most basis_step;
// codes the mean and basis with the residual coder (model's faces or curves give the
// neighbours) on up to `threads` threads (0: all cores; the bytes never depend on it).
// q (may be null) are the grid values the coefficients are refitted to: the input's, or with
// poses the posed frames the components were taken from.
// memo (may be null; the same pca and model on every call) makes the result no different,
// only faster, and so does traversal (may be null: build_traversal(*model), when the caller
// has it already). basis (may be null) receives what the basis payload codes: the values,
// mean then the K basis vectors, n each (what a decoder decodes, for low_rank_frame), and
// with Range coding its plan (Fast: none).
// False when a value would leave the format's ranges.
// coding: the residual coder of format 3 (Range), or the fast payload of format 4 (Fast: each
// pseudo-frame through the fast traversal, values snapped for it; memo and traversal unused).
enum class BasisCoding { Range, Fast };
bool quantize_low_rank(const GridComponents& pca, uint32_t K, double basis_step, uint32_t mean_shift, int threads,
                       Model* model, const std::vector<int32_t>* q = nullptr, BasisMemo* memo = nullptr,
                       const Traversal* traversal = nullptr, CodedPayload* basis = nullptr,
                       BasisCoding coding = BasisCoding::Range);

// The fast payload (format 4) of the mean and basis vectors `values` (mean, then the basis
// vectors, V * 3 each): each pseudo-frame from itself alone through the fast traversal (kind
// None with the spatial flag), with the flag that codes it smallest: none (parallelograms),
// smooth (means) or, for a basis vector, Fit over the mean's shape. With `exact` (the basis
// vectors' amplitudes in basis steps, K * V * 3), each vector is snapped for every kind tried
// (within 0.75 of its amplitude, nearest the kind's prediction) and *values keeps the chosen
// values; with `exact` empty the values stay as they are.
std::vector<uint8_t> code_mean_and_basis_fast(const Model& model, std::vector<int32_t>* values,
                                              const std::vector<double>& exact);

// The Model predictor of frames 0 .. F - 1 (frame-major, n = V * 3 values each) from the
// values a basis payload codes (mean_and_basis as quantize_low_rank returns them): what a
// decoder computes after decoding that payload, without decoding it.
std::vector<int32_t> low_rank_prediction(const LowRankModel& lr, const std::vector<int32_t>& mean_and_basis, uint32_t F,
                                         size_t n);

}  // namespace dcurve
