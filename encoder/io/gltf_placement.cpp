#include "encoder/io/gltf_placement.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "encoder/io/quoted_text.h"

namespace dcurve {
namespace {

using Matrix = std::array<double, 16>;  // column-major

constexpr Matrix kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Matrix multiply(const Matrix& a, const Matrix& b) {
  Matrix m{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      for (int k = 0; k < 4; ++k) m[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
  return m;
}

// glTF 2.0 section 3.5.3: a matrix, or T * R * S.
Matrix local_matrix(const tinygltf::Node& n) {
  Matrix m = kIdentity;
  if (n.matrix.size() == 16) {
    std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
    return m;
  }
  const double x = n.rotation.size() == 4 ? n.rotation[0] : 0, y = n.rotation.size() == 4 ? n.rotation[1] : 0,
               z = n.rotation.size() == 4 ? n.rotation[2] : 0, w = n.rotation.size() == 4 ? n.rotation[3] : 1;
  const Matrix rotation = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),     0,
                           2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),     0,
                           2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y), 0,
                           0,                       0,                       0,                       1};
  Matrix scale = kIdentity, translation = kIdentity;
  for (int a = 0; a < 3 && n.scale.size() == 3; ++a) scale[a * 5] = n.scale[a];
  for (int a = 0; a < 3 && n.translation.size() == 3; ++a) translation[12 + a] = n.translation[a];
  return multiply(translation, multiply(rotation, scale));
}

// Each node's parent, -1 for roots; false when a node has two parents or a child id is bad.
bool parents(const tinygltf::Model& model, std::vector<int>* parent) {
  parent->assign(model.nodes.size(), -1);
  for (size_t p = 0; p < model.nodes.size(); ++p)
    for (int c : model.nodes[p].children) {
      if (c < 0 || size_t(c) >= model.nodes.size() || (*parent)[c] != -1) return false;
      (*parent)[c] = int(p);
    }
  return true;
}

std::string channel_text(const tinygltf::Model& model, const tinygltf::Animation& anim, const tinygltf::AnimationChannel& ch) {
  std::string node = ch.target_node >= 0 && size_t(ch.target_node) < model.nodes.size()
                         ? "node '" + quote_file_text(model.nodes[ch.target_node].name, 40) + "'"
                         : "node " + std::to_string(ch.target_node);
  return "animation '" + quote_file_text(anim.name, 40) + "' (" + quote_file_text(ch.target_path, 20) + " of " + node + ")";
}

}  // namespace

Placement gltf_placement(const tinygltf::Model& model, int node, int mesh) {
  Placement p;
  if (mesh >= 0 && size_t(mesh) < model.meshes.size()) p.mesh_name = model.meshes[mesh].name;
  if (node < 0 || size_t(node) >= model.nodes.size()) return p;
  p.node_name = model.nodes[node].name;
  std::vector<int> parent;
  Matrix world = local_matrix(model.nodes[node]);
  if (parents(model, &parent)) {
    size_t steps = 0;  // a cycle would never reach a root
    for (int n = parent[node]; n >= 0 && steps < model.nodes.size(); n = parent[n], ++steps)
      world = multiply(local_matrix(model.nodes[n]), world);
  }
  const bool finite = std::all_of(world.begin(), world.end(), [](double x) { return std::isfinite(x); });
  p.has_matrix = finite && world != kIdentity;
  if (p.has_matrix) std::copy(world.begin(), world.end(), p.matrix);
  return p;
}

std::vector<std::string> gltf_dropped_animations(const tinygltf::Model& model, int kept_animation, int kept) {
  constexpr size_t kNamed = 8;  // a skeleton's hundreds of channels in one line each would bury the rest
  std::vector<std::string> notes;
  size_t dropped = 0;
  for (size_t a = 0; a < model.animations.size(); ++a)
    for (size_t c = 0; c < model.animations[a].channels.size(); ++c) {
      if (int(a) == kept_animation && int(c) == kept) continue;
      if (++dropped <= kNamed)
        notes.push_back(channel_text(model, model.animations[a], model.animations[a].channels[c]) +
                        " is not stored: dcurve keeps the mesh's vertex animation and the node's rest placement");
    }
  if (dropped > kNamed) notes.push_back("and " + std::to_string(dropped - kNamed) + " more animation channels not stored");
  return notes;
}

}  // namespace dcurve
