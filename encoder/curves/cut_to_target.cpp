#include "encoder/curves/cut_to_target.h"

#include <algorithm>
#include <cmath>

#include "encoder/curves/link_paths.h"

namespace dcurve {
namespace curves_detail {
namespace {

// Appends the cheapest split of the open sequence v into pieces of at most `target` points.
// Dynamic programming over cut positions: best[j] is the cheapest split of v[0, j). A piece
// [i, j) of 4 or more points costs 1 + P[j-1] - P[i+1] (P: prefix sums of bends; its ends
// carry none), so the best such i minimizes best[i] - P[i+1] over a sliding window, which a
// monotone deque finds in O(1) amortized: O(n) whatever the target.
void split_open(const std::vector<uint32_t>& v, const std::vector<float>& xyz, uint32_t target, double bend_weight,
                Curves* out) {
  const size_t n = v.size();
  std::vector<double> prefix(n + 1, 0.0);  // prefix[m + 1] = sum of bends at 0..m
  for (size_t m = 0; m < n; ++m)
    prefix[m + 1] = prefix[m] + (m >= 1 && m + 1 < n ? bend_cost(xyz, v[m - 1], v[m], v[m + 1], bend_weight) : 0.0);
  std::vector<double> best(n + 1, HUGE_VAL);
  std::vector<size_t> from(n + 1, 0);
  std::vector<size_t> window(n + 1);  // deque of start candidates, keys increasing
  size_t head = 0, tail = 0;
  auto key = [&](size_t i) { return best[i] - prefix[i + 1]; };
  best[0] = 0.0;
  for (size_t j = 1; j <= n; ++j) {
    auto consider = [&](size_t i, double cost) {
      if (cost < best[j]) {
        best[j] = cost;
        from[j] = i;
      }
    };
    if (j >= 4 && target >= 4) {
      const size_t i = j - 4;
      while (tail > head && key(window[tail - 1]) >= key(i)) --tail;
      window[tail++] = i;
    }
    while (tail > head && window[head] + target < j) ++head;
    if (tail > head) consider(window[head], key(window[head]) + prefix[j - 1] + 1.0);
    // Short pieces (1 to 3 points) pay the penalty; a 3-point piece has one inner bend.
    for (size_t size = 1; size <= std::min<size_t>({3, j, target}); ++size) {
      const size_t i = j - size;
      const double inner = size == 3 ? prefix[j - 1] - prefix[i + 1] : 0.0;
      consider(i, best[i] + 1.0 + kShortCurvePenalty + inner);
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
