#include "encoder/rate/plan_report.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "codec/common/fast_residual.h"
#include "codec/common/residual.h"
#include "codec/decompress/model_prediction.h"
#include "codec/decompress/residual_decoder.h"

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
  // A fast payload (format 4) has one kind per frame and none of the choices reported here.
  if (!(m.residual.step > 0) || (!m.residual.payload.empty() && m.residual.payload[0] == fast_residual::kPayloadVersion))
    return nullptr;
  std::vector<int32_t> prediction;
  ResidualOptions options;
  std::string err;
  if (has_model_prediction(m)) {
    if (!model_grid_prediction(m, UINT64_MAX, &prediction, &err)) return nullptr;
    options.model_prediction = &prediction;
  }
  ResidualPlan plan;
  if (!decode_predictor_plan(m, &plan, &err, options, true)) return nullptr;
  static const char* kinds[] = {"none", "reference", "linear", "model", "motion"};
  static const char* spatial[] = {"off", "mean", "parallelogram", "blend", "geometric", "fit"};
  static_assert(sizeof(spatial) / sizeof(spatial[0]) == kSpatialModeCount, "a name per spatial mode");
  auto count = [](nlohmann::json& j, const std::string& key) { j[key] = j.value(key, 0) + 1; };
  auto kind_name = [&](const PredictorChoice& c) {
    return size_t(c.kind) < kPredictorKindCount ? kinds[size_t(c.kind)] : "other";
  };
  // kind, spatial: each frame's first candidate, per axis; cluster_kind: what every
  // (frame, cluster, axis) actually uses.
  nlohmann::json k = nlohmann::json::object(), sp = nlohmann::json::object(), ck = nlohmann::json::object();
  uint64_t candidates = 0, clustered_frames = 0, motion_maps = 0;
  bool time_order = true;
  uint32_t cluster_size = 0;
  std::vector<uint32_t> stream_bytes(m.meta.frame_count, 0);  // by frame
  uint32_t position = 0;
  for (const CodedFrame& coded : coded_frames(plan)) {
    const FramePredictors& fp = *coded.predictors;
    const uint32_t clusters = cluster_count(m.meta.vertex_count, coded.chunk->cluster_size);
    time_order = time_order && coded.frame == position++;
    cluster_size = std::max(cluster_size, std::min(coded.chunk->cluster_size, m.meta.vertex_count));
    const uint32_t local = uint32_t(coded.predictors - coded.chunk->frames.data());
    if (local < coded.chunk->stream_bytes.size()) stream_bytes[coded.frame] = coded.chunk->stream_bytes[local];
    for (const PredictorChoice& c : fp.candidates[0]) {
      count(k, kind_name(c));
      count(sp, size_t(c.spatial) < kSpatialModeCount ? spatial[size_t(c.spatial)] : "other");
    }
    candidates += fp.candidates.size();
    clustered_frames += fp.candidates.size() > 1;
    for (uint32_t cl = 0; cl < clusters; ++cl) {
      const auto& used = fp.candidates[fp.cluster_candidate.empty() ? 0 : fp.cluster_candidate[cl]];
      bool motion = false;
      for (const PredictorChoice& c : used) {
        count(ck, kind_name(c));
        motion = motion || c.kind == PredictorKind::Motion;
      }
      motion_maps += motion;
    }
  }
  return {{"kind", k},
          {"spatial", sp},
          {"coding_order", time_order ? "time" : "hierarchical"},
          {"cluster_size", cluster_size},
          {"clusters", cluster_count(m.meta.vertex_count, std::max(cluster_size, 1u))},
          {"chunk_frames", plan.chunk_frames},
          {"chunks", plan.chunks.size()},
          {"candidates", candidates},
          {"clustered_frames", clustered_frames},
          {"cluster_kind", ck},
          {"motion_transforms", motion_maps},
          {"frame_stream_bytes", stream_bytes}};
}

std::string predictor_use_text(const nlohmann::json& use) {
  if (use.is_null()) return "";
  std::string text = counts_text(use["kind"]) + "; " + counts_text(use["spatial"]) + "; " +
                     use["coding_order"].get<std::string>() + " order";
  if (use["clustered_frames"].get<uint64_t>() > 0)
    text += "; per cluster of " + std::to_string(use["cluster_size"].get<uint64_t>()) +
            " vertices: " + counts_text(use["cluster_kind"]) + " (" +
            std::to_string(use["motion_transforms"].get<uint64_t>()) + " motion maps)";
  return text;
}

}  // namespace dcurve
