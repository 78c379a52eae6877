// dcurve itself, through the public encoder and the runtime decoder. The file is what a
// user ships: its own connectivity section included (reported apart).
#include "bench/baselines.h"
#include "codec/decompress/container_reader.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "encoder/rate/plan_report.h"

namespace dcurve::bench {

bool bench_dcurve(const BenchContext& ctx, MethodResult* r, std::string* error) {
  EncodeOptions opt;
  opt.tolerance = ctx.tolerance;
  opt.effort = ctx.dcurve_effort;
  std::vector<uint8_t> file;
  EncodeReport rep;
  const auto start = std::chrono::steady_clock::now();
  if (!encode_animation(ctx.anim, opt, &file, &rep, error)) return false;
  r->encode_seconds = seconds_since(start);

  const uint32_t F = uint32_t(ctx.anim.frames.size());
  std::vector<std::vector<float>> decoded(F, std::vector<float>(size_t(ctx.anim.vertex_count) * 3));
  auto decode_all = [&]() {
    auto dec = Decoder::open_memory(file.data(), file.size(), error);
    if (!dec || dec->vertex_count() != ctx.anim.vertex_count || dec->frame_count() != F) return false;
    for (uint32_t f = 0; f < F; ++f) dec->evaluate_frame(f, decoded[f].data());
    return true;
  };
  if (!decode_all()) return false;
  set_measures(ctx, decoded, file.size(), rep.connectivity_bytes, r);
  r->decode_vertices_per_second = decode_rate(ctx, decode_all);
  r->settings = "curves=" + std::to_string(rep.curves.curves) + " segments=" + std::to_string(rep.segments) +
                (rep.low_rank_components ? " low_rank=" + std::to_string(rep.low_rank_components) + " (" +
                                               std::to_string(rep.low_rank_bytes) + " B)"
                                         : std::string(" low_rank=off")) +
                " own connectivity section" +
                (ctx.dcurve_effort != EncodeOptions().effort ? " effort=" + std::to_string(ctx.dcurve_effort) : "");
  Model model;
  std::string ignored;  // the decoder accepted the file above; a failure here only drops the note
  if (read_container(file.data(), file.size(), &model, &ignored)) {
    const std::string predictors = predictor_use_text(predictor_use(model));
    if (!predictors.empty()) r->settings += "; predictors per frame and axis: " + predictors;
  }
  return true;
}

}  // namespace dcurve::bench
