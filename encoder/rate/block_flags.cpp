#include "encoder/rate/block_flags.h"

#include <vector>

#include "codec/common/error.h"
#include "codec/common/residual.h"
#include "codec/compress/residual_encoder.h"
#include "codec/decompress/model_prediction.h"
#include "codec/decompress/residual_decoder.h"
#include "encoder/rate/motion_costs.h"

namespace dcurve {
namespace {

// *payload (of `model`'s frames, coding `values` by `plan`) recoded with block flags, kept as
// `when` says.
bool recode(const Model& model, const std::vector<int32_t>& values, const ResidualPlan& plan,
            const ResidualOptions& options, BlockFlagUse when, std::vector<uint8_t>* payload, std::string* error) {
  ResidualOptions flagged = options;
  flagged.zero_block_flags = true;
  std::vector<uint8_t> recoded = encode_residuals(model, values, plan, flagged);
  if (recoded.empty()) return fail(error, "internal error: a residual plan does not code again");
  if (when == BlockFlagUse::Always || recoded.size() < payload->size()) payload->swap(recoded);
  return true;
}

// As above for a payload whose plan and values are known only from its bytes.
bool decode_and_recode(const Model& model, const ResidualOptions& options, BlockFlagUse when,
                       std::vector<uint8_t>* payload, std::string* error) {
  std::vector<int32_t> q;
  ResidualPlan plan;
  if (!decode_residuals(model, &q, error, options, &plan)) return false;
  return recode(model, q, plan, options, when, payload, error);
}

}  // namespace

bool use_block_flags(Model* model, BlockFlagUse when, std::string* error, const CodedResidual* coded) {
  // The basis first: the RESI's Model prediction comes from its decoded values, which the
  // recoding leaves as they are.
  if (model->low_rank.components > 0) {
    const Model basis = low_rank_basis_model(*model);
    std::vector<uint8_t>* payload = &model->low_rank.basis_payload;
    if (coded && !coded->basis.plan.chunks.empty() ? !recode(basis, coded->basis.values, coded->basis.plan, {}, when, payload, error)
                                                   : !decode_and_recode(basis, {}, when, payload, error))
      return false;
  }
  if (model->residual.payload.empty()) return true;
  if (coded) {
    ResidualOptions options;
    if (!coded->prediction.empty()) options.model_prediction = &coded->prediction;
    return recode(*model, coded->resi.values, coded->resi.plan, options, when, &model->residual.payload, error);
  }
  // The prediction a decoder makes: from the PDE coefficients as the file stores them,
  // which differ from the in-memory ones in the last bits (a rounding that moved one grid
  // value made the recoded payload's checksum fail on a sheet encode).
  std::vector<int32_t> prediction;
  if (!stored_model_prediction(*model, &prediction, error)) return false;
  ResidualOptions options;
  if (!prediction.empty()) options.model_prediction = &prediction;
  return decode_and_recode(*model, options, when, &model->residual.payload, error);
}

}  // namespace dcurve
