// XPBD simulator speed on three sizes of the rope: the built-in "rope-small" (1.6 m, 4 cells
// across), the built-in "rope" (6.2 m, 8 across) and that rope re-gridded to 6 across. Each
// benchmark iteration simulates one frame with the scene's own substeps and iterations;
// TetGen runs once, untimed. Counters, from process CPU time (the solver is single-threaded,
// so a busy machine does not inflate them): ms per frame, ms per substep per 1000 tets.
// Reference: the 2022 paper reports 6.42 s for 100 frames (64 ms/frame) of a 15,389-vertex
// horse with the PositionBasedDynamics library.
#include <benchmark/benchmark.h>

#include <ctime>
#include <cstdio>

#include "corpus/sim/scene.h"
#include "corpus/sim/simulation.h"

namespace {

// across = 4: "rope-small"; 8: "rope"; otherwise "rope" re-gridded to `across` cells across
// its 8 cm section, substeps by the corpus rule (15 per cell across).
dcurve::Scene rope(int across) {
  dcurve::Scene s;
  std::string err;
  if (!dcurve::builtin_scene(across == 4 ? "rope-small" : "rope", &s, &err)) std::fprintf(stderr, "%s\n", err.c_str());
  if (across == 4 || across == 8) return s;
  const int along = across * 620 / 8;
  const double cell = 0.08 / across, length = cell * along;
  s.generator["size"] = {length, 0.08, 0.08};
  s.generator["divisions"] = {along, across, across};
  s.mesh_translate = {length / 2, 0, 0};
  s.tet_max_volume = cell * cell * cell;
  s.ground_height = -1.1 * length;
  s.substeps = 15 * across;
  return s;
}

void BM_RopeFrame(benchmark::State& state) {
  const dcurve::Scene scene = rope(int(state.range(0)));
  dcurve::SceneSimulation sim;
  std::string err;
  if (!sim.init(scene, &err)) {
    state.SkipWithError(err.c_str());
    return;
  }
  double seconds = 0;
  int frames = 0;
  for (auto _ : state) {
    const std::clock_t t0 = std::clock();
    if (!sim.advance_frame(&err)) {
      state.SkipWithError(err.c_str());
      return;
    }
    seconds += double(std::clock() - t0) / CLOCKS_PER_SEC;
    ++frames;
  }
  const double tets = double(sim.solver().tet_count());
  const double ms_frame = 1e3 * seconds / frames;
  state.counters["surface_vertices"] = sim.surface_vertex_count();
  state.counters["tets"] = tets;
  state.counters["substeps"] = scene.substeps;
  state.counters["iterations"] = scene.iterations;
  state.counters["ms_per_frame"] = ms_frame;
  state.counters["ms_per_substep_per_1k_tets"] = ms_frame / scene.substeps / (tets / 1000);
}
BENCHMARK(BM_RopeFrame)->Arg(4)->Iterations(30)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RopeFrame)->Arg(6)->Iterations(10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RopeFrame)->Arg(8)->Iterations(3)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
