// glTF 2.0 in (.gltf or .glb, read by tinygltf): one mesh (its triangle primitives joined,
// one face group and material per primitive) with morph targets and an animation of its
// weights becomes an animation whose frames are the weights' keyframes (base + sum of
// weight x target), at the frame rate of the key times. Seam copies are welded (weld.h), the
// attributes, materials (gltf_materials.h) and placement (gltf_placement.h) kept.
#pragma once
#include <string>

#include "encoder/io/frames.h"
#include "encoder/io/read_limits.h"

namespace dcurve {

// Whether `path` names a glTF file (.gltf or .glb, any case).
bool is_gltf_path(const std::string& path);

// Reads mesh `mesh_index` of the file (-1: the file must hold exactly one mesh). Refused
// with a message naming the file: no weights animation, several meshes, several weights
// channels, non-triangle primitives, unevenly spaced keys, data it cannot read (sparse
// accessors it cannot apply, quantized attributes) and the compression extensions
// KHR_draco_mesh_compression and EXT_meshopt_compression, which it does not decode. Buffers
// are read under the resource policy of gltf_resources.h; every array sized from the file's
// counts is checked against limits.max_memory before it is allocated.
bool read_gltf_animation(const std::string& path, int mesh_index, Animation* anim, std::string* error,
                         const ReadLimits& limits = ReadLimits());

}  // namespace dcurve
