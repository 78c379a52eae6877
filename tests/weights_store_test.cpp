// The encoder's store of spatial weight tables (encoder/rate/weights_store.h): it must hand
// out exactly the tables spatial_weights computes, keyed by mesh, mode and geometry values,
// within its byte budget, from any thread, and a residual walk that draws on it must code
// the same bytes as one that does not.
#include <gtest/gtest.h>

#include <random>
#include <thread>
#include <vector>

#include "codec/common/predictors.h"
#include "codec/common/residual.h"
#include "codec/compress/residual_encoder.h"
#include "codec/decompress/residual_decoder.h"
#include "encoder/rate/weights_store.h"
#include "test_models.h"

namespace dcurve {
namespace {

using testing::grid;
using testing::sheet_model;

// The traversal a walk drawing on `source` gets: fingerprinted, so its tables can be shared.
Traversal shared_traversal(const Model& m, SpatialWeightsSource* source) {
  ResidualOptions options;
  options.weights_source = source;
  Traversal owned;
  traversal_for(m, options, &owned);
  return owned;
}

TEST(SpatialWeightsStore, ReusesOnlyTablesOfTheSameMeshModeAndValues) {
  const Model m = sheet_model(9, 3);
  SpatialWeightsStore store;
  const Traversal t = shared_traversal(m, &store);
  ASSERT_NE(t.fingerprint, 0u);
  const std::vector<int32_t> q = grid(m.meta.vertex_count, 3);
  const int32_t* f1 = q.data() + t.order.size() * 3;
  // A traversal nobody fingerprinted (a decoder's): its tables are solved, never shared.
  const Traversal plain = build_traversal(m);
  ASSERT_EQ(plain.fingerprint, 0u);
  for (int i = 0; i < 2; ++i)
    EXPECT_EQ(*store.weights(plain, f1, SpatialMode::Fit), spatial_weights(plain, f1, SpatialMode::Fit));
  EXPECT_EQ(store.computed() + store.reused(), 0u);
  for (SpatialMode mode : {SpatialMode::Fit, SpatialMode::Geometric}) {
    const auto first = store.weights(t, f1, mode);
    EXPECT_EQ(*first, spatial_weights(t, f1, mode));
    EXPECT_EQ(store.weights(t, f1, mode), first);  // the same table, not solved again
  }
  EXPECT_EQ(store.computed(), 2u);
  EXPECT_EQ(store.reused(), 2u);
  // One value moved: another table.
  std::vector<int32_t> moved(f1, f1 + t.order.size() * 3);
  moved[7] += 40;
  EXPECT_EQ(*store.weights(t, moved.data(), SpatialMode::Fit), spatial_weights(t, moved.data(), SpatialMode::Fit));
  EXPECT_EQ(store.computed(), 3u);
  // Another mesh of the same vertices (one quad fewer): its own table, though the values
  // are the same.
  Model other = m;
  other.faces.resize(other.faces.size() - 6);
  const Traversal u = shared_traversal(other, &store);
  ASSERT_NE(u.fingerprint, t.fingerprint);
  EXPECT_EQ(*store.weights(u, f1, SpatialMode::Fit), spatial_weights(u, f1, SpatialMode::Fit));
  EXPECT_EQ(store.computed(), 4u);
  EXPECT_EQ(store.reused(), 2u);
}

TEST(SpatialWeightsStore, DropsTheLeastRecentlyUsedBeyondItsBudget) {
  const Model m = sheet_model(9, 4);
  const std::vector<int32_t> q = grid(m.meta.vertex_count, 4);
  const Traversal sized = build_traversal(m);
  const size_t n = sized.order.size() * 3;
  // Room for about two Fit entries (table and key values).
  const size_t entry = (spatial_weights(sized, q.data(), SpatialMode::Fit).size() + n) * sizeof(int32_t);
  SpatialWeightsStore store(2 * entry + entry / 2);
  const Traversal t = shared_traversal(m, &store);
  auto ask = [&](uint32_t f) {
    const int32_t* qf = q.data() + f * n;
    const auto w = store.weights(t, qf, SpatialMode::Fit);
    EXPECT_EQ(*w, spatial_weights(t, qf, SpatialMode::Fit)) << "frame " << f;
    return w;
  };
  const auto held = ask(0);
  ask(1);
  ask(0);  // frame 0 most recent again
  ask(2);  // drops frame 1
  EXPECT_EQ(store.computed(), 3u);
  ask(0);
  EXPECT_EQ(store.computed(), 3u);
  ask(1);  // dropped before: solved again
  EXPECT_EQ(store.computed(), 4u);
  ask(3);
  ask(2);  // dropped by frames 1 and 3
  EXPECT_EQ(store.computed(), 6u);
  // A table a caller still holds stays valid once dropped.
  EXPECT_EQ(*held, spatial_weights(t, q.data(), SpatialMode::Fit));
}

TEST(SpatialWeightsStore, ServesThreadsAtOnce) {
  const Model m = sheet_model(12, 4);
  const std::vector<int32_t> q = grid(m.meta.vertex_count, 4);
  SpatialWeightsStore store;
  const Traversal t = shared_traversal(m, &store);
  const size_t n = t.order.size() * 3;
  std::vector<std::thread> threads;
  std::vector<int> wrong(4, 0);
  for (int k = 0; k < 4; ++k)
    threads.emplace_back([&, k] {
      for (int i = 0; i < 40; ++i) {
        const uint32_t f = uint32_t(i + k) % 4;
        const SpatialMode mode = (i + k) % 3 ? SpatialMode::Fit : SpatialMode::Geometric;
        wrong[size_t(k)] += *store.weights(t, q.data() + f * n, mode) != spatial_weights(t, q.data() + f * n, mode);
      }
    });
  for (std::thread& th : threads) th.join();
  EXPECT_EQ(wrong, std::vector<int>(4, 0));
  EXPECT_EQ(store.computed() + store.reused(), 160u);
  EXPECT_LE(store.computed(), 8u * 4);  // 8 distinct tables, each solved at most once per thread
}

TEST(SpatialWeightsStore, AWalkDrawingOnItCodesTheSameBytes) {
  const uint32_t F = 5;
  Model m = sheet_model(10, F);
  std::vector<int32_t> q = grid(m.meta.vertex_count, F);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> jitter(-3, 3);
  for (int32_t& x : q) x += jitter(rng);
  // Every frame after the first predicts with Fit on one axis and Geometric on the others,
  // each from a different earlier geometry frame.
  std::vector<PredictorChoice> choices;
  for (uint32_t f = 0; f < F; ++f)
    for (int a = 0; a < 3; ++a) {
      if (f == 0) {
        choices.push_back({PredictorKind::None, 0, 0, SpatialMode::Parallelogram, 0});
        continue;
      }
      const SpatialMode mode = a == 0 ? SpatialMode::Fit : SpatialMode::Geometric;
      choices.push_back({PredictorKind::Reference, f - 1, 0, mode, uint32_t(a) % f});
    }
  std::vector<uint32_t> order(F);
  for (uint32_t f = 0; f < F; ++f) order[f] = f;
  const PredictorPlan plan = uniform_plan(order, choices);
  const std::vector<uint8_t> plain = encode_residuals(m, q, &plan);
  ASSERT_FALSE(plain.empty());
  SpatialWeightsStore store;
  ResidualOptions with;
  with.weights_source = &store;
  EXPECT_EQ(encode_residuals(m, q, &plan, with), plain);
  const size_t solved = store.computed();
  EXPECT_GT(solved, 0u);
  EXPECT_EQ(encode_residuals(m, q, &plan, with), plain);
  EXPECT_EQ(store.computed(), solved);  // the second walk solved nothing
  EXPECT_GT(store.reused(), 0u);
  m.residual.payload = plain;
  std::vector<int32_t> back;
  std::string err;
  ASSERT_TRUE(decode_residuals(m, &back, &err, with)) << err;
  EXPECT_EQ(back, q);
}

}  // namespace
}  // namespace dcurve
