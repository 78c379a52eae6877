#include "codec/common/fast_fit.h"

namespace dcurve {

FastFit fast_fit(const std::vector<uint32_t>& faces, const FastTraversal& t, const int32_t* geometry) {
  const Traversal sets = neighbour_traversal(faces, t.order);
  const uint32_t V = uint32_t(t.order.size());
  std::vector<uint32_t> pos(V);
  for (uint32_t i = 0; i < V; ++i) pos[t.order[i]] = i;
  FastFit fit;
  fit.offsets = sets.fit_offsets;
  fit.refs.resize(sets.fit.size());
  for (size_t k = 0; k < sets.fit.size(); ++k) fit.refs[k] = pos[sets.fit[k]];
  fit.weights = fit_weights(sets, geometry);
  return fit;
}

}  // namespace dcurve
