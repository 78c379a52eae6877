#include "encoder/io/gltf_writer.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <sstream>

#include "codec/common/error.h"
#include "encoder/io/files.h"

namespace dcurve {
namespace {

// Far below the 4 GiB a GLB chunk can hold, and what a decode may reasonably hold in memory.
constexpr uint64_t kMaxGltfBytes = uint64_t(1) << 30;

// Appends `count` elements of `bytes` to the one buffer as a view and an accessor over it;
// returns the accessor's index. min/max are required for positions and animation inputs.
struct Builder {
  tinygltf::Model model;
  std::vector<unsigned char>& data() { return model.buffers[0].data; }

  int add_view(const void* src, size_t bytes, int target) {
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = data().size();
    v.byteLength = bytes;
    v.target = target;
    // Vertex attributes state their stride: the validator requires it when several
    // accessors (the morph targets) share a view.
    if (target == TINYGLTF_TARGET_ARRAY_BUFFER) v.byteStride = 12;
    const auto* p = static_cast<const unsigned char*>(src);
    data().insert(data().end(), p, p + bytes);
    model.bufferViews.push_back(v);
    return int(model.bufferViews.size() - 1);
  }

  int add_accessor(int view, size_t offset, size_t count, int type, int component, std::vector<double> min = {},
                   std::vector<double> max = {}) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.byteOffset = offset;
    a.count = count;
    a.type = type;
    a.componentType = component;
    a.minValues = std::move(min);
    a.maxValues = std::move(max);
    model.accessors.push_back(a);
    return int(model.accessors.size() - 1);
  }
};

void bounds(const float* xyz, size_t count, std::vector<double>* lo, std::vector<double>* hi) {
  lo->assign(3, 0.0);
  hi->assign(3, 0.0);
  for (size_t i = 0; i < count; ++i)
    for (int a = 0; a < 3; ++a) {
      const double x = xyz[3 * i + a];
      (*lo)[a] = i ? std::min((*lo)[a], x) : x;
      (*hi)[a] = i ? std::max((*hi)[a], x) : x;
    }
}

int add_positions(Builder* b, const float* xyz, uint32_t vertices, int view, size_t offset) {
  std::vector<double> lo, hi;
  bounds(xyz, vertices, &lo, &hi);
  return b->add_accessor(view, offset, vertices, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT, lo, hi);
}

// The weights animation: key i at i / fps turns target i - 1 fully on (key 0: none).
void add_weights_animation(Builder* b, uint32_t frames, double fps) {
  const size_t targets = frames - 1;
  std::vector<float> times(frames), weights(size_t(frames) * targets, 0.0f);
  for (uint32_t i = 0; i < frames; ++i) times[i] = float(i / fps);
  for (uint32_t i = 1; i < frames; ++i) weights[size_t(i) * targets + (i - 1)] = 1.0f;
  const int tv = b->add_view(times.data(), 4 * times.size(), 0);
  const int wv = b->add_view(weights.data(), 4 * weights.size(), 0);
  tinygltf::AnimationSampler s;
  s.input = b->add_accessor(tv, 0, frames, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_FLOAT, {times.front()}, {times.back()});
  s.output = b->add_accessor(wv, 0, weights.size(), TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_FLOAT);
  s.interpolation = "LINEAR";
  tinygltf::AnimationChannel c;
  c.sampler = 0;
  c.target_node = 0;
  c.target_path = "weights";
  tinygltf::Animation anim;
  anim.name = "frames";
  anim.samplers.push_back(s);
  anim.channels.push_back(c);
  b->model.animations.push_back(anim);
}

}  // namespace

GltfWriter::GltfWriter(uint32_t vertex_count, std::vector<uint32_t> faces, uint32_t frame_count, double frame_rate)
    : vertex_count_(vertex_count), frame_count_(frame_count), frame_rate_(frame_rate > 0 ? frame_rate : 30.0),
      faces_(std::move(faces)) {
  // Held whole (the file holds every frame): reserved once so growth never doubles it.
  if (frame_count > 1) targets_.reserve(size_t(frame_count - 1) * vertex_count * 3);
}

bool GltfWriter::check_size(uint32_t vertex_count, size_t face_ids, uint32_t frame_count, std::string* error) {
  const uint64_t n = frame_count;
  const uint64_t bytes = 4 * uint64_t(face_ids) + 12 * uint64_t(vertex_count) * n + 4 * n * n;
  if (bytes > kMaxGltfBytes)
    return fail(error, std::to_string(frame_count) + " frames of " + std::to_string(vertex_count) +
                           " vertices need " + std::to_string(bytes >> 20) +
                           " MiB as glTF morph targets, more than the 1024 MiB dcurve writes: ask for fewer --frames, "
                           "or write .pc2/.mdd or a folder");
  return true;
}

void GltfWriter::add_frame(const float* xyz) {
  const size_t values = size_t(vertex_count_) * 3;
  if (frames_added_++ == 0) {
    base_.assign(xyz, xyz + values);
    return;
  }
  for (size_t i = 0; i < values; ++i) targets_.push_back(xyz[i] - base_[i]);
}

bool GltfWriter::write(const std::string& path, std::string* error) const {
  if (frames_added_ != frame_count_ || frame_count_ == 0) return fail(error, path + ": frames missing for the glTF output");
  Builder b;
  b.model.asset.version = "2.0";
  b.model.asset.generator = "dcurve";
  b.model.buffers.emplace_back();
  tinygltf::Primitive prim;
  prim.mode = faces_.empty() ? TINYGLTF_MODE_POINTS : TINYGLTF_MODE_TRIANGLES;
  if (!faces_.empty()) {
    const int iv = b.add_view(faces_.data(), 4 * faces_.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    prim.indices = b.add_accessor(iv, 0, faces_.size(), TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  }
  const size_t frame_bytes = 12 * size_t(vertex_count_);
  prim.attributes["POSITION"] = add_positions(&b, base_.data(), vertex_count_,
                                              b.add_view(base_.data(), frame_bytes, TINYGLTF_TARGET_ARRAY_BUFFER), 0);
  tinygltf::Mesh mesh;
  mesh.name = "dcurve";
  if (frame_count_ > 1) {
    const int tv = b.add_view(targets_.data(), 4 * targets_.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
    for (uint32_t t = 0; t + 1 < frame_count_; ++t)
      prim.targets.push_back({{"POSITION", add_positions(&b, targets_.data() + t * size_t(vertex_count_) * 3,
                                                         vertex_count_, tv, t * frame_bytes)}});
    mesh.weights.assign(frame_count_ - 1, 0.0);
    add_weights_animation(&b, frame_count_, frame_rate_);
  }
  mesh.primitives.push_back(prim);
  b.model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  b.model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  b.model.scenes.push_back(scene);
  b.model.defaultScene = 0;
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  const bool binary = lowercase_extension(path) == ".glb";
  if (!writer.WriteGltfSceneToStream(&b.model, out, !binary, binary)) return fail(error, path + ": cannot build glTF");
  const std::string bytes = out.str();
  return write_file_atomic(path, bytes.data(), bytes.size(), error);
}

}  // namespace dcurve
