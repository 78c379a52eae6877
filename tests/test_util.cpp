// The helpers of test_util.h that need the simulation (corpus/sim/scene.h, and with it Eigen
// and nlohmann/json): compiled once here rather than in every test file.
#include "test_util.h"

#include "corpus/sim/scene.h"

namespace dcurve::test {

Animation simulate_builtin(const std::string& name, uint32_t frames) {
  Scene scene;
  std::string err;
  if (!builtin_scene(name, &scene, &err)) throw std::runtime_error(err);
  scene.frames = frames;
  Animation anim;
  if (!simulate_scene(scene, &anim, {}, &err)) throw std::runtime_error(err);
  return anim;
}

}  // namespace dcurve::test
