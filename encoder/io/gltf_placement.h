// Where a glTF places the animated mesh and what else it animates: the node's world
// transform and names are kept (PLAC), animations dcurve does not store are named to the user.
#pragma once
#include <string>
#include <vector>

#include "codec/common/render_mesh.h"

namespace tinygltf {
class Model;
}

namespace dcurve {

// The world transform (the node's and its parents', column-major), mesh and node names of
// node `node` showing mesh `mesh`. start_time is left to the caller (the first key's time).
// A node graph with a cycle or a node with two parents leaves the node's own transform.
Placement gltf_placement(const tinygltf::Model& model, int node, int mesh);

// One line per animation channel that moves a node (translation, rotation, scale) or drives
// weights other than channel `kept` of animation `kept_animation`: what dcurve does not keep.
std::vector<std::string> gltf_dropped_animations(const tinygltf::Model& model, int kept_animation, int kept);

}  // namespace dcurve
