// Estimates shared by the PDE motion model's rate control (motion_choice.h,
// motion_alternatives.h): what each grid value costs the residual coder, what a motion
// costs in the SEGS section, and the Model predictor as the file will store it.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "codec/common/model.h"
#include "codec/common/residual.h"
#include "encoder/rate/coded_residual.h"

namespace dcurve {

// What coding each grid value costs under a plan, and whether its predictor is the Model.
struct ValueCosts {
  std::vector<float> bits;        // (f * V + v) * 3 + axis
  std::vector<uint8_t> by_model;  // same index; 1 when the value's predictor kind is Model
  std::vector<double> class_bits; // bits of a residual's exponent class in this stream (smoothed)
  // Estimated bits of residual r under this stream's statistics: class bits plus mantissa.
  double residual_bits(int64_t r) const;
};

// Per-value bits of `q` coded under `plan` (complete, as from choose_plan_and_grid): the
// order-0 entropy of the value's exponent class over the whole stream plus its mantissa
// bits. The coder's contexts are ignored, so only differences between two plans of the
// same frames mean something.
bool value_costs(const Model& model, const std::vector<int32_t>& q, const ResidualPlan& plan,
                 const ResidualOptions& ro, ValueCosts* out, std::string* error);

// The same for the residual payload `baseline` carries (without a Model prediction), from
// what it codes as the encoder kept it.
bool coded_value_costs(const Model& baseline, const CodedPayload& coded, ValueCosts* out, std::string* error);

// Bytes the SEGS section stores for motion `m` beyond a Zero motion's single byte, before zstd.
double motion_record_bytes(const CurveMotion& m);

// SEGS stored bytes per raw byte as zstd leaves them for `model` (1 when uncompressed), as
// the writer reports it.
double segs_compression(const Model& model);

// Frames [first, last] whose Model prediction segment s of `model` gives: a boundary frame
// shared with the next segment belongs to the next one, as in the decoder.
std::pair<uint32_t, uint32_t> predicted_frames(const Model& model, size_t s);

// The Model predictor of every frame from `model` as a reader of its file gets it back: the
// curves' u in 16-bit fixed point as the container stores them (the in-memory u differ in
// the last bits; coefficients are stored exactly), grid units; empty when the model has no
// Model prediction.
bool stored_model_prediction(const Model& model, std::vector<int32_t>* prediction, std::string* error);

}  // namespace dcurve
