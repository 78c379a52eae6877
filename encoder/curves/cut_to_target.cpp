#include "encoder/curves/cut_to_target.h"

#include <algorithm>
#include <cmath>

#include "encoder/curves/link_paths.h"

namespace dcurve {
namespace curves_detail {
namespace {

double piece_cost(uint32_t size, double inner_bends) {
  return 1.0 + (size < 4 ? kShortCurvePenalty : 0.0) + inner_bends;
}

// Appends the cheapest split of the open sequence v into pieces of at most `target` points.
// Dynamic programming over cut positions: best[j] is the cheapest split of v[0, j).
void split_open(const std::vector<uint32_t>& v, const std::vector<float>& xyz, uint32_t target, double bend_weight,
                Curves* out) {
  const size_t n = v.size();
  std::vector<double> bend_prefix(n + 1, 0.0);  // bend_prefix[m + 1] = sum of bends at 0..m
  for (size_t m = 0; m < n; ++m)
    bend_prefix[m + 1] = bend_prefix[m] + (m >= 1 && m + 1 < n ? bend_cost(xyz, v[m - 1], v[m], v[m + 1], bend_weight) : 0.0);
  std::vector<double> best(n + 1, HUGE_VAL);
  std::vector<size_t> from(n + 1, 0);
  best[0] = 0.0;
  for (size_t j = 1; j <= n; ++j) {
    const size_t first = j > target ? j - target : 0;
    for (size_t i = first; i < j; ++i) {
      // Interior vertices of the piece [i, j) are i + 1 .. j - 2; its ends carry no bend.
      const double inner = j >= i + 3 ? bend_prefix[j - 1] - bend_prefix[i + 1] : 0.0;
      const double cost = best[i] + piece_cost(uint32_t(j - i), inner);
      if (cost < best[j] - 1e-12) {
        best[j] = cost;
        from[j] = i;
      }
    }
  }
  std::vector<size_t> cuts;
  for (size_t j = n; j > 0; j = from[j]) cuts.push_back(j);
  std::reverse(cuts.begin(), cuts.end());
  size_t start = 0;
  for (size_t end : cuts) {
    out->vertices.insert(out->vertices.end(), v.begin() + start, v.begin() + end);
    out->offsets.push_back(uint32_t(out->vertices.size()));
    out->closed.push_back(0);
    start = end;
  }
}

}  // namespace

double bend_cost(const std::vector<float>& xyz, uint32_t a, uint32_t b, uint32_t c, double bend_weight) {
  return bend_weight * (1.0 - turn_cosine(xyz, a, b, c));
}

Curves cut_to_target(const Curves& runs, const std::vector<float>& xyz, uint32_t target, double bend_weight) {
  Curves out;
  out.vertices.reserve(runs.vertices.size());
  out.offsets.assign(1, 0);
  std::vector<uint32_t> v;
  for (uint32_t c = 0; c < runs.curve_count(); ++c) {
    const uint32_t begin = runs.offsets[c], n = runs.offsets[c + 1] - begin;
    v.assign(runs.vertices.begin() + begin, runs.vertices.begin() + begin + n);
    if (runs.closed[c] && n <= target) {
      out.vertices.insert(out.vertices.end(), v.begin(), v.end());
      out.offsets.push_back(uint32_t(out.vertices.size()));
      out.closed.push_back(1);
      continue;
    }
    if (runs.closed[c]) {
      // Open the cycle where cutting removes the most bend (sum of 1 - cos): rotate that vertex to the front.
      auto at = [&](size_t k) { return v[k % n]; };  // callers add n, so k never wraps below 0
      size_t best = 0;
      double best_gain = -1.0;
      for (size_t i = 0; i < n; ++i) {
        const double gain = 2.0 - turn_cosine(xyz, at(i + n - 2), at(i + n - 1), at(i)) -
                            turn_cosine(xyz, at(i + n - 1), at(i), at(i + 1));
        if (gain > best_gain) {
          best_gain = gain;
          best = i;
        }
      }
      std::rotate(v.begin(), v.begin() + best, v.end());
    }
    split_open(v, xyz, target, bend_weight, &out);
  }
  return out;
}

}  // namespace curves_detail
}  // namespace dcurve
