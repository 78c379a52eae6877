#include "encoder/rate/plan_report.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "codec/residual.h"
#include "decoder/model_prediction.h"

namespace dcurve {
namespace {

// "a 3, b 1", most used first.
std::string counts_text(const nlohmann::json& counts) {
  std::vector<std::pair<uint64_t, std::string>> items;
  for (auto it = counts.begin(); it != counts.end(); ++it) items.emplace_back(it.value().get<uint64_t>(), it.key());
  std::sort(items.begin(), items.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::string out;
  for (const auto& [n, name] : items) out += (out.empty() ? "" : ", ") + name + " " + std::to_string(n);
  return out;
}

}  // namespace

nlohmann::json predictor_use(const Model& m) {
  if (!(m.residual.step > 0)) return nullptr;
  std::vector<int32_t> prediction;
  ResidualOptions options;
  std::string err;
  if (has_model_prediction(m)) {
    if (!model_grid_prediction(m, UINT64_MAX, &prediction, &err)) return nullptr;
    options.model_prediction = &prediction;
  }
  PredictorPlan plan;
  if (!decode_predictor_plan(m, &plan, &err, options)) return nullptr;
  static const char* kinds[] = {"none", "reference", "linear", "model"};
  static const char* spatial[] = {"off", "mean", "parallelogram", "blend"};
  nlohmann::json k = nlohmann::json::object(), sp = nlohmann::json::object();
  for (const PredictorChoice& c : plan.choices) {
    const std::string kn = size_t(c.kind) < 4 ? kinds[size_t(c.kind)] : "other";
    const std::string sn = size_t(c.spatial) < 4 ? spatial[size_t(c.spatial)] : "other";
    k[kn] = k.value(kn, 0) + 1;
    sp[sn] = sp.value(sn, 0) + 1;
  }
  bool time_order = true;
  for (size_t i = 0; i < plan.order.size(); ++i) time_order = time_order && plan.order[i] == i;
  return {{"kind", k}, {"spatial", sp}, {"coding_order", time_order ? "time" : "hierarchical"}};
}

std::string predictor_use_text(const nlohmann::json& use) {
  if (use.is_null()) return "";
  return counts_text(use["kind"]) + "; " + counts_text(use["spatial"]) + "; " +
         use["coding_order"].get<std::string>() + " order";
}

}  // namespace dcurve
