#include "encoder/rate/fast_grid.h"

#include <cstddef>
#include <cstdint>
#include <vector>

#include "encoder/rate/fast_low_rank.h"

namespace dcurve {
namespace {
// Low-rank trials of one choose_fast_low_rank, as most inputs run it: six counts, the two
// beside the best, two basis steps.
constexpr uint64_t kForecastCountTrials = 10;

// *out = base on `grid` with the low-rank model and fast payload choose_fast_low_rank keeps
// for `anim` (whose frames base's metadata counts); *bytes (may be null) its whole file.
bool fast_model_on(const Animation& anim, const Model& base, const ResidualLayer& grid,
                   const FastLayerOptions& options, Model* out, size_t* bytes, std::string* error) {
  *out = base;
  out->meta.frame_count = uint32_t(anim.frames.size());
  out->residual = grid;
  std::vector<int32_t> rounded;
  return quantize_to_grid(anim, grid, &rounded, error) &&
         choose_fast_low_rank(out, anim.frames, rounded, options, error, bytes);
}
}  // namespace

bool choose_fast_grid(const Animation& anim, const Model& base, double max_distance, double refinement,
                      GridSearch search, const FastLayerOptions& options, Model* out, std::string* error) {
  if (refinement > 0) return fast_model_on(anim, base, make_grid(anim, max_distance, refinement), options, out, nullptr, error);
  std::vector<Model> trials(kGridTrialSlots);
  const GridChoice choice = choose_grid(
      anim, max_distance, options.threads,
      [&](const ResidualLayer& grid, const Animation& part, size_t slot, int threads) -> size_t {
        FastLayerOptions o = options;
        o.threads = threads;
        size_t trial_bytes = 0;
        return fast_model_on(part, base, grid, o, &trials[slot], &trial_bytes, nullptr) ? trial_bytes : SIZE_MAX;
      },
      search);
  if (choice.whole) {
    *out = std::move(trials[choice.slot]);
    return true;
  }
  return fast_model_on(anim, base, choice.grid, options, out, nullptr, error);
}

uint64_t forecast_fast_grid_frames(const Animation& anim, bool fixed_grid, GridSearch search) {
  const uint64_t F = anim.frames.size(), part = grid_trial_frames(uint32_t(F), anim.vertex_count);
  const uint64_t grids = fixed_grid ? 0 : search == GridSearch::Walk ? 4 : 2;
  const uint64_t whole = fixed_grid || part < F ? F : 0;
  return kForecastCountTrials * (grids * part + whole);
}

}  // namespace dcurve
