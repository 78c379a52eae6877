// The content of a .dcrv file, in memory: what the encoder fills, the container serializes
// and the decoder evaluates. Plain data; every invariant is checked by codec/common/validate.h
// before a decoder trusts it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/render_mesh.h"

namespace dcurve {

// Which closed-form family a curve's motion uses (codec/common/basis.h defines the functions).
enum class Basis : uint8_t {
  Zero = 0,   // no motion model: the residual layer alone carries the positions
  Pde8 = 1,   // 2022 paper: 2 time x 4 space functions, 4 sign cases
  Pde32 = 2,  // 2024 paper: 4 time x 8 space functions
};

// How the decoder blends the stored frames' corrections between two frames
// (format_spec/dcrv.md section 13); the encoder records its choice in META (format 3.2).
enum class Inbetween : uint8_t {
  Linear = 0,      // linear blend of frames i and i + 1 (every file before 3.2)
  CatmullRom = 1,  // cubic Hermite, tangents (p[f+1] - p[f-1]) / 2
  Hermite4 = 2,    // cubic Hermite, tangents by fourth-order central differences
};
constexpr uint8_t kInbetweenCount = 3;

// What the model predicts.
enum class FitMode : uint8_t {
  Absolute = 0,      // positions themselves (the papers' mode)
  Displacement = 1,  // positions minus the rest pose (reconstructed frame 0)
};

struct Metadata {
  uint32_t vertex_count = 0;
  uint32_t frame_count = 0;   // input frames; frame f sits at t = f / (frame_count - 1)
  double frame_rate = 30.0;   // frames per second of the input, informative
  double tolerance = 1e-3;    // max error the encoder promised, as a fraction of `diag`
  double diag = 1.0;          // L: bounding-box diagonal of the rest pose (frame 0), model units
  std::string units;          // free text, e.g. "m"; may be empty
  Inbetween inbetween = Inbetween::Linear;  // the encoder's in-between rule
};

// A partition of all vertices into ordered curves.
struct Curves {
  std::vector<uint32_t> vertices;  // size vertex_count: vertex ids, curve after curve
  std::vector<uint32_t> offsets;   // size curve_count + 1; curve c is vertices[offsets[c], offsets[c+1])
  std::vector<uint8_t> closed;     // size curve_count; 1 when the last vertex joins the first
  std::vector<float> u;            // parallel to `vertices`: curve parameter in [0, 1], non-decreasing

  uint32_t curve_count() const { return offsets.empty() ? 0u : uint32_t(offsets.size() - 1); }
};

// Every vertex its own open one-point curve (u = 0), in vertex id order: what a file
// without a CURV section holds (format_spec/dcrv.md section 7), and what an encoder uses
// when nothing reads the curves.
Curves singleton_curves(uint32_t vertex_count);
bool is_singleton_curves(const Curves& c, uint32_t vertex_count);

// One curve's motion on one axis during one time segment.
struct CurveMotion {
  Basis basis = Basis::Zero;
  uint8_t basis_case = 0;    // sign case, 0..3 for Pde8, 0 for Pde32
  float time_param = 0.f;    // mu (Pde8) or alpha (Pde32), >= 0
  float space_param = 0.f;   // delta (Pde8) or r (Pde32), >= 0
  std::vector<float> coeffs; // basis term count entries (codec/common/basis.h gives the layout)
  // Every coefficient is k * 2^coeff_exponent for an integer |k| < 2^24: the file stores k
  // (quantize_coefficients in codec/compress/quantize.h), so a coarse exponent makes a small model.
  int8_t coeff_exponent = -24;
};

// Frames [first_frame, last_frame] share one fitted motion per curve and axis. Segments
// tile the frame range; adjacent segments share their boundary frame.
struct Segment {
  uint32_t first_frame = 0;
  uint32_t last_frame = 0;
  FitMode mode = FitMode::Absolute;
  std::vector<CurveMotion> motion;  // curve_count * 3 entries, index curve * 3 + axis
};

// Positions on a uniform grid, coded as integer residuals against per-frame predictions.
// Frame f, vertex v, axis a sits at origin[a] + step * q(f, v, a) for integers q that the
// residual layer reproduces exactly (codec/common/residual.h).
struct ResidualLayer {
  double step = 0.0;                 // grid spacing, model units, > 0
  double origin[3] = {0.0, 0.0, 0.0};
  // The coded residuals (format owned by codec/common/residual.h): header and chunk index, then
  // the chunks. A reader that leaves the chunks in the file holds the index alone here and
  // the chunks' byte count in external_bytes.
  std::vector<uint8_t> payload;
  uint64_t external_bytes = 0;
  // Frames per chunk (format_spec/residual.md): what the encoder plans and codes with, what
  // a reader found in the index. 0 while unset: one chunk of every frame.
  uint32_t chunk_frames = 0;
  uint64_t coded_bytes() const { return payload.size() + external_bytes; }
};

// A low-rank model of the residual grid (LRNK section, format_spec/dcrv.md section 10): the
// Model predictor of frame f is, per coordinate i = v * 3 + axis, in grid units,
//   round_shift(mean[i] * 2^(shift - mean_shift) + sum_k coeffs[f * K + k] * basis[k][i], shift).
// The mean and basis are stored as K + 1 pseudo-frames coded by the residual coder.
struct LowRankModel {
  uint32_t components = 0;   // K, 0 (no low-rank model) or 1..kMaxLowRankComponents
  uint32_t shift = 0;        // S, 0..kMaxLowRankShift
  uint32_t mean_shift = 0;   // the mean is stored in units of 2^-mean_shift grid steps, <= shift
  std::vector<int32_t> coeffs;         // frame_count * K, frame-major, |c| <= kMaxLowRankCoeff
  // Empty (all 0) or K values 0..shift: component k's coefficients are multiples of
  // 2^coeff_shifts[k] and stored divided by it (format 2.3). A component whose basis values
  // are small needs coarser coefficients for the same prediction error.
  std::vector<uint8_t> coeff_shifts;
  std::vector<uint8_t> basis_payload;  // residual-layer payload of the K + 1 pseudo-frames
  // Empty, or one pose per frame (format 2.5): frame_count * kLowRankPoseValues values, frame
  // f's at f * kLowRankPoseValues: a 3 x 3 matrix m (row-major, units of 2^-kLowRankPoseShift,
  // |m| <= kMaxLowRankPoseMatrix) then a translation t (grid units, |t| <= 2^30). The mean and
  // basis then describe the frames in a common pose, and frame f's prediction is
  // pose_centre + t + m (p - pose_centre) for the posed-space prediction p of each vertex
  // (codec/common/low_rank.h): a rotating or travelling body keeps few components.
  std::vector<int32_t> poses;
  int32_t pose_centre[3] = {0, 0, 0};  // grid units, |c| <= 2^30
};

struct Model {
  Metadata meta;
  std::vector<uint32_t> faces;  // 3 vertex ids per triangle; empty when connectivity is omitted
  Curves curves;
  std::vector<Segment> segments;
  ResidualLayer residual;
  LowRankModel low_rank;
  RenderMesh render;     // empty: render vertices are the vertices, no attributes (REND)
  Placement placement;   // (PLAC)
  MaterialSet materials; // what the render groups draw with (MATL)
};

}  // namespace dcurve
