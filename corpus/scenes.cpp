#include "corpus/scenes.h"

#include <cmath>

namespace dcurve::corpus {
namespace {

using json = nlohmann::json;

json box_region(std::initializer_list<double> lo, std::initializer_list<double> hi) {
  return {{"box", {{"min", json(lo)}, {"max", json(hi)}}}};
}

// A square-section rubber rope lying along +x from the origin, its x = 0 end pinned,
// released to swing under gravity (the 2024 paper's cube-rope), with cells_across x
// cells_along square surface cells.
json rope(int cells_across, int cells_along, double section, int frames) {
  const double cell = section / cells_across, length = cell * cells_along;
  return {
      {"mesh",
       {{"generator", "box"},
        {"size", {length, section, section}},
        {"divisions", {cells_along, cells_across, cells_across}},
        {"translate", {length / 2, 0.0, 0.0}}}},
      {"tetgen", {{"quality", 2.0}, {"max_volume", cell * cell * cell}}},
      {"material", {{"density", 1100.0}, {"youngs_modulus", 1e6}, {"poisson_ratio", 0.3}, {"damping", 0.1}}},
      {"gravity", {0.0, -9.81, 0.0}},
      {"ground", {{"height", -1.1 * length}, {"friction", 0.5}}},
      {"pins", json::array({box_region({-1.0, -1.0, -1.0}, {1e-6, 1.0, 1.0})})},
      {"frames", frames},
      {"fps", 30.0},
      // Stable Neo-Hookean needs substeps that resolve the stiffest tet's oscillation,
      // which scales with 1 / (tet size); at fewer, the tets by the pin nearly collapse on
      // the first swing (min det F 0.01 at 10 per cell across, 0.2 at 15): see the README.
      {"substeps", 15 * cells_across},
      {"iterations", 2},
  };
}

json cantilever() {
  // 0.5 m x 0.1 m x 0.1 m rubber bar clamped at x = 0; linear beam theory puts the settled
  // tip sag near w L^4 / (8 E I) = 9 cm, so it sags visibly and oscillates before settling.
  return {
      {"mesh",
       {{"generator", "box"}, {"size", {0.5, 0.1, 0.1}}, {"divisions", {20, 4, 4}}, {"translate", {0.25, 0.0, 0.0}}}},
      {"tetgen", {{"quality", 2.0}, {"max_volume", 2e-5}}},
      {"material", {{"density", 1000.0}, {"youngs_modulus", 1e6}, {"poisson_ratio", 0.3}, {"damping", 1.0}}},
      {"gravity", {0.0, -9.81, 0.0}},
      {"ground", {{"height", -0.3}, {"friction", 0.5}}},
      {"pins", json::array({box_region({-1.0, -1.0, -1.0}, {1e-6, 1.0, 1.0})})},
      {"frames", 90},
      {"fps", 30.0},
      {"substeps", 40},
      {"iterations", 1},
  };
}

json neck() {
  // A soft tube standing on its clamped base; the top ring turns half a revolution while
  // it is pulled up and sideways over 2 s, then holds.
  const double pi = std::acos(-1.0);
  return {
      {"mesh",
       {{"generator", "tube"},
        {"inner_radius", 0.03},
        {"outer_radius", 0.05},
        {"length", 0.4},
        {"around", 24},
        {"along", 24}}},
      {"tetgen", {{"quality", 2.0}, {"max_volume", 1e-5}}},
      {"material", {{"density", 1000.0}, {"youngs_modulus", 3e5}, {"poisson_ratio", 0.4}, {"damping", 1.0}}},
      {"gravity", {0.0, -9.81, 0.0}},
      {"pins", json::array({box_region({-1.0, -1.0, -1.0}, {1.0, 1e-6, 1.0})})},
      {"handles",
       json::array({{{"region", box_region({-1.0, 0.4 - 1e-6, -1.0}, {1.0, 1.0, 1.0})},
                     {"velocity", {0.05, 0.05, 0.0}},
                     {"axis", {0.0, 1.0, 0.0}},
                     {"angular_velocity", pi / 2},
                     {"start", 0.0},
                     {"end", 2.0}}})},
      {"frames", 90},
      {"fps", 30.0},
      {"substeps", 40},
      {"iterations", 1},
  };
}

json blob() {
  // A soft, nearly incompressible jelly ball dropped from 0.35 m onto the ground.
  return {
      {"mesh", {{"generator", "sphere"}, {"radius", 0.15}, {"divisions", 10}, {"translate", {0.0, 0.5, 0.0}}}},
      {"tetgen", {{"quality", 2.0}, {"max_volume", 2e-5}}},
      {"material",
       {{"density", 1000.0},
        {"youngs_modulus", 5e4},
        {"poisson_ratio", 0.45},
        {"volume_compliance", 1e-6},
        {"damping", 0.5}}},
      {"gravity", {0.0, -9.81, 0.0}},
      {"ground", {{"height", 0.0}, {"friction", 0.8}}},
      {"frames", 60},
      {"fps", 30.0},
      {"substeps", 40},
      {"iterations", 1},
  };
}

json sheet() {
  // A 1 cm thick, 60 cm square rubber sheet hinged along one edge, swinging down from
  // horizontal. (Held by two small corner patches instead, the corner tets invert: all the
  // weight goes through a few tets.)
  return {
      {"mesh", {{"generator", "box"}, {"size", {0.6, 0.01, 0.6}}, {"divisions", {30, 1, 30}}}},
      {"tetgen", {{"quality", 2.0}}},
      {"material", {{"density", 1000.0}, {"youngs_modulus", 2e5}, {"poisson_ratio", 0.3}, {"damping", 0.5}}},
      {"gravity", {0.0, -9.81, 0.0}},
      {"ground", {{"height", -0.7}, {"friction", 0.5}}},
      {"pins", json::array({box_region({-1.0, -1.0, -1.0}, {1.0, 1.0, -0.28})})},
      {"frames", 90},
      {"fps", 30.0},
      {"substeps", 60},
      {"iterations", 1},
  };
}

}  // namespace

std::vector<std::string> builtin_scene_names() { return {"rope-small", "rope", "cantilever", "neck", "blob", "sheet"}; }

bool builtin_scene_json(const std::string& name, nlohmann::json* scene) {
  if (name == "rope-small")
    *scene = rope(4, 80, 0.08, 90);
  else if (name == "rope")
    *scene = rope(8, 620, 0.08, 100);
  else if (name == "cantilever")
    *scene = cantilever();
  else if (name == "neck")
    *scene = neck();
  else if (name == "blob")
    *scene = blob();
  else if (name == "sheet")
    *scene = sheet();
  else
    return false;
  (*scene)["name"] = name;
  return true;
}

}  // namespace dcurve::corpus
