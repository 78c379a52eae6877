#include "bench/inbetween_bench.h"

#include <cmath>
#include <cstdio>

#include "codec/common/error.h"
#include "codec/common/inbetween.h"
#include "decoder/dcurve.hpp"
#include "encoder/metrics.h"

namespace dcurve::bench {
namespace {

Animation even_frames(const Animation& anim) {
  Animation even = anim;
  even.frames.clear();
  for (size_t f = 0; f < anim.frames.size(); f += 2) even.frames.push_back(anim.frames[f]);
  even.frame_rate = anim.frame_rate / 2;
  return even;
}

// Held-out frame 2k + 1 lies between even frames k and k + 1: frame coordinate k + 1/2.
uint32_t held_out_count(const Animation& anim) { return uint32_t((anim.frames.size() - 1) / 2); }

// Sum over vertices of the squared distance between a and b.
double squared_distance(const float* a, const std::vector<float>& b) {
  double sum = 0;
  for (size_t i = 0; i < b.size(); ++i) {
    const double e = double(a[i]) - double(b[i]);
    sum += e * e;
  }
  return sum;
}

double rmse(double squared_sum, const Animation& anim, uint32_t held_out) {
  return std::sqrt(squared_sum / (double(held_out) * anim.vertex_count)) / bbox_diagonal(anim.frames[0]);
}

// RMSE of `cursor` against the true frames: at the held-out times and odd frames (odd), or
// at the stored times and even frames, whose coding error every in-between rule starts from.
bool decoded_rmse(Cursor& cursor, const Animation& anim, bool odd, double* out, std::string* error) {
  const uint32_t even_count = uint32_t((anim.frames.size() + 1) / 2);
  const uint32_t count = odd ? held_out_count(anim) : even_count;
  std::vector<float> xyz(size_t(anim.vertex_count) * 3);
  double sum = 0;
  for (uint32_t k = 0; k < count; ++k) {
    Error e;
    if (!cursor.evaluate((k + (odd ? 0.5 : 0.0)) / double(even_count - 1), xyz.data(), &e)) return fail(error, e.message);
    sum += squared_distance(xyz.data(), anim.frames[2 * k + (odd ? 1 : 0)]);
  }
  *out = rmse(sum, anim, count);
  return true;
}

bool measure_file(const Animation& anim, const Animation& even, const EncodeOptions& options, InbetweenFile* file,
                  std::string* error) {
  std::vector<uint8_t> bytes;
  EncodeReport report;
  if (!encode_animation(even, options, &bytes, &report, error)) return false;
  auto decoder = Decoder::open_memory(bytes.data(), bytes.size(), error);
  if (!decoder) return false;
  file->present = true;
  file->bytes = bytes.size();
  file->recorded = Inbetween(int(decoder->interpolation()));
  file->settings = "segments=" + std::to_string(report.segments) + " motions_kept=" +
                   std::to_string(report.motions_kept) + " low_rank=" + std::to_string(report.low_rank_components);
  for (uint8_t r = 0; r < kInbetweenCount; ++r) {
    auto cursor = decoder->make_cursor();
    cursor->set_interpolation(Interpolation(r));
    if (!decoded_rmse(*cursor, anim, true, &file->rmse[r], error)) return false;
  }
  file->rmse_recorded = file->rmse[uint8_t(file->recorded)];
  return decoded_rmse(*decoder->make_cursor(), anim, false, &file->rmse_stored, error);
}

// Each rule through the true even frames, with the formulas the decoder uses.
void true_frame_rmse(const Animation& anim, double out[kInbetweenCount]) {
  const uint32_t held_out = held_out_count(anim), last = uint32_t((anim.frames.size() + 1) / 2) - 1;
  const size_t n = size_t(anim.vertex_count) * 3;
  for (uint8_t r = 0; r < kInbetweenCount; ++r) {
    double sum = 0;
    std::vector<float> xyz(n);
    for (uint32_t k = 0; k < held_out; ++k) {
      double weight[kInbetweenStencil];
      inbetween_weights(Inbetween(r), 0, last, k, 0.5, weight);
      std::vector<double> p(n, 0.0);
      for (int s = 0; s < kInbetweenStencil; ++s) {
        if (weight[s] == 0.0) continue;
        const std::vector<float>& even = anim.frames[2 * size_t(int(k) + kInbetweenStencilFirst + s)];
        for (size_t i = 0; i < n; ++i) p[i] += weight[s] * double(even[i]);
      }
      for (size_t i = 0; i < n; ++i) xyz[i] = float(p[i]);
      sum += squared_distance(xyz.data(), anim.frames[2 * k + 1]);
    }
    out[r] = rmse(sum, anim, held_out);
  }
}

nlohmann::json file_json(const InbetweenFile& f) {
  if (!f.present) return nullptr;
  nlohmann::json j = {{"bytes", f.bytes},       {"recorded", inbetween_name(f.recorded)},
                      {"rmse_recorded", f.rmse_recorded}, {"rmse_stored", f.rmse_stored},
                      {"settings", f.settings}};
  for (uint8_t r = 0; r < kInbetweenCount; ++r) j["rmse"][inbetween_name(Inbetween(r))] = f.rmse[r];
  return j;
}

}  // namespace

bool run_inbetween_bench(const std::string& name, const Animation& anim, const EncodeOptions& options, bool with_pde,
                         InbetweenResult* result, std::string* error) {
  if (anim.frames.size() < 3) return fail(error, name + ": needs at least 3 frames to hold one out");
  *result = InbetweenResult{};
  result->input = name;
  result->vertices = anim.vertex_count;
  result->frames = uint32_t(anim.frames.size());
  result->held_out = held_out_count(anim);
  const Animation even = even_frames(anim);
  if (!measure_file(anim, even, options, &result->plain, error)) return false;
  if (with_pde) {
    EncodeOptions pde = options;
    pde.model = ModelChoice::Pde;
    pde.low_rank = 0;
    pde.keep_all_motions = true;
    if (!measure_file(anim, even, pde, &result->pde, error)) return false;
  }
  true_frame_rmse(anim, result->true_rmse);
  return true;
}

std::string inbetween_table(const std::vector<InbetweenResult>& results) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "%-18s %9s %-11s %9s %9s %9s %9s %9s %6s | %9s %9s %9s %9s | %9s %9s %9s\n",
                "input", "bytes", "recorded", "stored", "file", "linear", "c-rom", "herm4", "x cr", "pde.B", "pde.file",
                "pde.lin", "x cr", "true.lin", "true.cr", "true.h4");
  out += line;
  for (const InbetweenResult& r : results) {
    const double cr = r.true_rmse[uint8_t(Inbetween::CatmullRom)];
    std::snprintf(line, sizeof line, "%-18s %9llu %-11s %9.3g %9.3g %9.3g %9.3g %9.3g %6.2f | ", r.input.c_str(),
                  (unsigned long long)r.plain.bytes, inbetween_name(r.plain.recorded), r.plain.rmse_stored,
                  r.plain.rmse_recorded,
                  r.plain.rmse[0], r.plain.rmse[1], r.plain.rmse[2], r.plain.rmse_recorded / cr);
    out += line;
    if (r.pde.present)
      std::snprintf(line, sizeof line, "%9llu %9.3g %9.3g %9.2f | ", (unsigned long long)r.pde.bytes,
                    r.pde.rmse_recorded, r.pde.rmse[0], r.pde.rmse_recorded / cr);
    else
      std::snprintf(line, sizeof line, "%9s %9s %9s %9s | ", "-", "-", "-", "-");
    out += line;
    std::snprintf(line, sizeof line, "%9.3g %9.3g %9.3g\n", r.true_rmse[0], r.true_rmse[1], r.true_rmse[2]);
    out += line;
  }
  out += "RMSE at the held-out odd frames, fractions of L; even frames encoded. stored: RMSE of the decoded even "
         "frames (the coding error the rules start from); file: the rule the file records; x cr: file / Catmull-Rom "
         "through the true even frames (true.cr).\n";
  return out;
}

nlohmann::json inbetween_json(const std::vector<InbetweenResult>& results) {
  nlohmann::json all = nlohmann::json::array();
  for (const InbetweenResult& r : results) {
    nlohmann::json j = {{"input", r.input}, {"vertices", r.vertices}, {"frames", r.frames}, {"held_out", r.held_out},
                        {"file", file_json(r.plain)}, {"pde_file", file_json(r.pde)}};
    for (uint8_t k = 0; k < kInbetweenCount; ++k) j["true_rmse"][inbetween_name(Inbetween(k))] = r.true_rmse[k];
    all.push_back(j);
  }
  return all;
}

}  // namespace dcurve::bench
