#include "encoder/io/gltf_writer.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>

#include "codec/common/error.h"
#include "encoder/io/json_depth.h"

namespace dcurve {
namespace {

using Json = nlohmann::ordered_json;

// Far below the 4 GiB a GLB chunk can hold, and what a decode may reasonably write.
constexpr uint64_t kMaxGltfBytes = uint64_t(1) << 30;
// The longest text a double takes in the JSON: stands for every bound while the size of the
// JSON is reserved, so the real bounds always fit.
constexpr double kLongestNumber = -2.2250738585072014e-308;
constexpr size_t kFlushBytes = size_t(3) << 18;  // a multiple of 3: base64 flushes whole groups
constexpr char kDataUri[] = "data:application/octet-stream;base64,";
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963, kFloat = 5126, kUnsignedInt = 5125;

// JSON text with bytes that are not UTF-8 (names from the file) as U+FFFD: a glTF is UTF-8,
// and nlohmann's dump would throw on them.
std::string json_text(const Json& j) { return j.dump(-1, ' ', false, Json::error_handler_t::replace); }

// `object`'s text without its closing brace, so members can follow it.
std::string open_object(const Json& object) {
  std::string text = json_text(object);
  text.pop_back();
  return text;
}

uint64_t base64_bytes(uint64_t bytes) { return (bytes + 2) / 3 * 4; }
uint64_t padded4(uint64_t n) { return (n + 3) & ~uint64_t(3); }

void append_base64(const uint8_t* p, size_t size, std::string* out) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (size_t i = 0; i < size; i += 3) {
    const uint32_t n = uint32_t(p[i]) << 16 | (i + 1 < size ? uint32_t(p[i + 1]) << 8 : 0) | (i + 2 < size ? p[i + 2] : 0);
    out->push_back(kAlphabet[n >> 18 & 63]);
    out->push_back(kAlphabet[n >> 12 & 63]);
    out->push_back(i + 1 < size ? kAlphabet[n >> 6 & 63] : '=');
    out->push_back(i + 2 < size ? kAlphabet[n & 63] : '=');
  }
}

void store_u32(uint8_t* p, uint32_t v) { std::memcpy(p, &v, 4); }  // little-endian targets, as GLB

}  // namespace

// The byte layout of the one buffer: where each part starts.
struct GltfLayout {
  uint64_t indices = 0, statics, base, targets, times, weights, end;
  GltfLayout(uint32_t vertices, size_t face_ids, uint32_t frame_count, uint64_t static_bytes, bool normals) {
    const uint64_t frames = frame_count ? frame_count : 1, frame_bytes = (normals ? 24 : 12) * uint64_t(vertices);
    statics = 4 * uint64_t(face_ids);
    base = statics + static_bytes;
    targets = base + frame_bytes;
    times = targets + frame_bytes * (frames - 1);
    weights = times + (frames > 1 ? 4 * frames : 0);  // one frame: no animation
    end = weights + 4 * uint64_t(frames) * (frames - 1);
  }
};

namespace {

Json view(uint64_t offset, uint64_t length, int target, uint32_t stride = 12) {
  Json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}};
  // Vertex attributes state their stride: the validator requires it when several accessors
  // (the morph targets) share a view.
  if (target == kArrayBuffer) v["byteStride"] = stride;
  if (target) v["target"] = target;
  return v;
}

Json accessor(int view, uint64_t offset, uint64_t count, const char* type, int component) {
  return {{"bufferView", view}, {"byteOffset", offset}, {"componentType", component}, {"count", count}, {"type", type}};
}

Json position_accessor(int view, uint64_t offset, uint32_t count, const std::array<float, 6>& b, bool placeholders) {
  Json a = accessor(view, offset, count, "VEC3", kFloat);
  a["min"] = Json::array();
  a["max"] = Json::array();
  for (int k = 0; k < 3; ++k) {
    a["min"].push_back(placeholders ? kLongestNumber : double(b[k]));
    a["max"].push_back(placeholders ? kLongestNumber : double(b[3 + k]));
  }
  return a;
}

const char* const kTypeNames[] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};

// The static attributes' views and accessors, named in the primitive.
void add_static_attributes(const GltfScene& scene, uint64_t offset, uint32_t vertices, Json* views, Json* accessors,
                           Json* primitive) {
  for (const GltfScene::Attribute& a : scene.attributes) {
    const uint64_t bytes = 4 * uint64_t(a.components) * vertices;
    views->push_back(view(offset, bytes, kArrayBuffer, 4 * a.components));
    accessors->push_back(accessor(int(views->size() - 1), 0, vertices, kTypeNames[a.components], kFloat));
    (*primitive)["attributes"][a.name] = accessors->size() - 1;
    offset += bytes;
  }
}

uint64_t images_bytes(const GltfScene& scene) {
  uint64_t bytes = 0;
  for (const MaterialImage& image : scene.images) bytes += padded4(image.bytes.size());
  return bytes;
}

// The materials and textures as stored, each image a bufferView of the buffer (after the
// static attributes, 4-byte aligned).
void add_materials(const GltfScene& scene, uint64_t offset, Json* doc, Json* views) {
  // Too deep to copy and dump without overflowing the stack: fits() refuses the output.
  if (!check_json_depth(scene.materials_json.data(), scene.materials_json.size(), kMaxJsonDepth, nullptr)) return;
  const Json m = Json::parse(scene.materials_json, nullptr, false);
  if (!m.is_object()) return;
  for (const char* key : {"extensionsUsed", "extensionsRequired", "materials", "textures", "samplers"})
    if (m.contains(key) && m[key].is_array() && !m[key].empty()) (*doc)[key] = m[key];
  const Json& images = m.contains("images") && m["images"].is_array() ? m["images"] : Json::array();
  Json out = Json::array();
  for (size_t i = 0; i < scene.images.size(); ++i) {
    views->push_back(view(offset, scene.images[i].bytes.size(), 0));
    Json image = {{"bufferView", views->size() - 1}, {"mimeType", scene.images[i].mime_type}};
    if (i < images.size() && images[i].is_object() && images[i].contains("name")) image["name"] = images[i]["name"];
    out.push_back(image);
    offset += padded4(scene.images[i].bytes.size());
  }
  if (!out.empty()) (*doc)["images"] = out;
}

// One primitive per face group with triangles (its slice of the index buffer, its material),
// or `primitive` alone without groups. An empty group (consecutive `usemtl` lines) gets none:
// an indices accessor of count 0 is invalid glTF.
Json group_primitives(const GltfScene& scene, const Json& primitive, int index_view, size_t materials, Json* accessors) {
  Json out = Json::array();
  uint64_t first = 0;
  for (size_t g = 0; g < scene.group_faces.size(); ++g) {
    if (scene.group_faces[g] == 0) continue;
    Json p = primitive;
    accessors->push_back(accessor(index_view, 12 * first, 3 * uint64_t(scene.group_faces[g]), "SCALAR", kUnsignedInt));
    p["indices"] = accessors->size() - 1;
    if (scene.group_materials[g] >= 0 && size_t(scene.group_materials[g]) < materials) p["material"] = scene.group_materials[g];
    out.push_back(p);
    first += scene.group_faces[g];
  }
  return out.empty() ? Json::array({primitive}) : out;
}

// The mesh as text, each primitive listing the morph targets `targets` (text; none when empty).
std::string mesh_text(const Json& mesh, const Json& primitives, const std::string& targets) {
  std::string text = open_object(mesh) + ",\"primitives\":[";
  for (size_t i = 0; i < primitives.size(); ++i) {
    if (i > 0) text += ',';
    text += targets.empty() ? json_text(primitives[i]) : open_object(primitives[i]) + ",\"targets\":[" + targets + "]}";
  }
  return text + "]}";
}

// The node showing the mesh: the input's name and world transform.
Json mesh_node(const Placement& p) {
  Json node = {{"mesh", 0}};
  if (!p.node_name.empty()) node["name"] = p.node_name;
  if (p.has_matrix) node["matrix"] = std::vector<double>(p.matrix, p.matrix + 16);
  return node;
}

}  // namespace

GltfWriter::GltfWriter(uint32_t vertex_count, std::vector<uint32_t> faces, uint32_t frame_count, double frame_rate,
                       bool binary, GltfScene scene)
    : vertex_count_(vertex_count), frame_count_(frame_count), frame_rate_(frame_rate > 0 ? frame_rate : 30.0),
      binary_(binary), faces_(std::move(faces)), scene_(std::move(scene)) {}

uint64_t GltfWriter::static_bytes() const {
  uint64_t bytes = 0;
  for (const GltfScene::Attribute& a : scene_.attributes) bytes += 4 * uint64_t(a.components) * vertex_count_;
  return bytes + images_bytes(scene_);
}

uint64_t GltfWriter::buffer_bytes() const {
  return GltfLayout(vertex_count_, faces_.size(), frame_count_, static_bytes(), scene_.normals).end;
}

// The morph targets' accessors and the primitive's list of them, as JSON text: thousands of
// frames as a JSON tree would take many times their text, and the writer's memory must not
// grow with the clip beyond a few numbers per frame.
struct TargetText {
  std::string accessors, targets;
};

TargetText GltfWriter::target_text(int view_index, uint64_t first_accessor, bool placeholders) const {
  const uint64_t position_bytes = 12 * uint64_t(vertex_count_);
  const uint64_t frame_bytes = scene_.normals ? 2 * position_bytes : position_bytes;
  TargetText text;
  uint64_t next = first_accessor;
  for (uint32_t t = 1; t < frame_count_; ++t) {
    const auto b = t < bounds_.size() ? bounds_[t] : std::array<float, 6>{};
    const char* comma = t > 1 ? "," : "";
    text.accessors += comma + position_accessor(view_index, (t - 1) * frame_bytes, vertex_count_, b, placeholders).dump();
    text.targets += std::string(comma) + "{\"POSITION\":" + std::to_string(next++);
    if (scene_.normals) {
      text.accessors += "," + accessor(view_index, (t - 1) * frame_bytes + position_bytes, vertex_count_, "VEC3", kFloat).dump();
      text.targets += ",\"NORMAL\":" + std::to_string(next++);
    }
    text.targets += "}";
  }
  return text;
}

namespace {

// The weights animation: key i at the input's first key time + i / fps turns target i - 1
// fully on (key 0: none). `first` and `last`: the first and last key times.
void add_weights_animation(const GltfLayout& at, uint32_t frame_count, float first, float last, bool placeholders,
                           Json* doc, Json* mesh, Json* views, Json* accessors) {
  views->push_back(view(at.times, at.weights - at.times, 0));
  Json times = accessor(int(views->size() - 1), 0, frame_count, "SCALAR", kFloat);
  times["min"] = {placeholders ? kLongestNumber : double(first)};
  times["max"] = {placeholders ? kLongestNumber : double(last)};
  accessors->push_back(times);
  views->push_back(view(at.weights, at.end - at.weights, 0));
  accessors->push_back(accessor(int(views->size() - 1), 0, uint64_t(frame_count) * (frame_count - 1), "SCALAR", kFloat));
  Json sampler = {{"input", accessors->size() - 2}, {"output", accessors->size() - 1}, {"interpolation", "LINEAR"}};
  Json channel = {{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}};
  (*doc)["animations"] = Json::array({{{"name", "frames"}, {"samplers", {sampler}}, {"channels", {channel}}}});
  (*mesh)["weights"] = std::vector<double>(frame_count - 1, 0.0);
}

}  // namespace

// Accessors and views in the buffer's order: indices, static attributes, frame 0, the targets,
// times, weights (the targets' accessors last, joined in as text).
std::string GltfWriter::json(bool placeholders) const {
  const GltfLayout at(vertex_count_, faces_.size(), frame_count_, static_bytes(), scene_.normals);
  const uint64_t position_bytes = 12 * uint64_t(vertex_count_);
  const uint64_t frame_bytes = scene_.normals ? 2 * position_bytes : position_bytes;
  Json views = Json::array(), accessors = Json::array();
  Json primitive = {{"attributes", Json::object()}, {"mode", faces_.empty() ? 0 : 4}};
  if (!faces_.empty()) {
    views.push_back(view(at.indices, at.statics - at.indices, kElementArrayBuffer));
    accessors.push_back(accessor(int(views.size() - 1), 0, faces_.size(), "SCALAR", kUnsignedInt));
    primitive["indices"] = accessors.size() - 1;
  }
  add_static_attributes(scene_, at.statics, vertex_count_, &views, &accessors, &primitive);
  Json doc = {{"asset", {{"version", "2.0"}, {"generator", "dcurve"}}}};
  add_materials(scene_, at.base - images_bytes(scene_), &doc, &views);
  views.push_back(view(at.base, frame_bytes, kArrayBuffer));
  accessors.push_back(position_accessor(int(views.size() - 1), 0, vertex_count_, bounds_.empty() ? std::array<float, 6>{} : bounds_[0], placeholders));
  primitive["attributes"]["POSITION"] = accessors.size() - 1;
  if (scene_.normals) {
    accessors.push_back(accessor(int(views.size() - 1), position_bytes, vertex_count_, "VEC3", kFloat));
    primitive["attributes"]["NORMAL"] = accessors.size() - 1;
  }
  Json mesh = {{"name", scene_.placement.mesh_name.empty() ? "dcurve" : scene_.placement.mesh_name}};
  const size_t materials = doc.contains("materials") ? doc["materials"].size() : 0;
  const Json primitives = group_primitives(scene_, primitive, faces_.empty() ? -1 : 0, materials, &accessors);
  TargetText targets;
  if (frame_count_ > 1) {
    add_weights_animation(at, frame_count_, key_time(0), key_time(frame_count_ - 1), placeholders, &doc, &mesh, &views,
                          &accessors);
    // The targets' accessors last: their indices follow from the count of those before.
    views.push_back(view(at.targets, at.times - at.targets, kArrayBuffer));
    targets = target_text(int(views.size() - 1), accessors.size(), placeholders);
  }
  doc["bufferViews"] = views;
  Json tail = {{"nodes", Json::array({mesh_node(scene_.placement)})}, {"scenes", Json::array({{{"nodes", {0}}}})}, {"scene", 0}};
  if (binary_) tail["buffers"] = Json::array({{{"byteLength", at.end}}});
  // Joined as text in one pass, the targets' text at known places: nothing a material or
  // name holds is searched for, and the time stays linear in the primitives.
  std::string accessor_text = json_text(accessors);
  accessor_text.pop_back();
  if (!targets.accessors.empty()) accessor_text += "," + targets.accessors;
  return open_object(doc) + ",\"accessors\":" + accessor_text + "],\"meshes\":[" +
         mesh_text(mesh, primitives, targets.targets) + "]," + json_text(tail).substr(1);
}

float GltfWriter::key_time(uint32_t frame) const {
  return float(scene_.placement.start_time + frame / frame_rate_);
}

uint64_t GltfWriter::file_bytes(uint32_t vertex_count, size_t face_ids, uint32_t frame_count, bool binary,
                                const GltfScene& scene) {
  return GltfWriter(vertex_count, std::vector<uint32_t>(face_ids), frame_count, 30, binary, scene).expected_bytes();
}

uint64_t GltfWriter::expected_bytes() const {
  const uint64_t buffer = buffer_bytes();
  // Past the limit on the buffer alone: no need to build a JSON of millions of targets.
  if (buffer > kMaxGltfBytes) return binary_ ? buffer : base64_bytes(buffer);
  const uint64_t json = this->json(true).size();
  if (binary_) return 12 + 8 + padded4(json) + 8 + buffer;
  // {"buffers":[{"byteLength":N,"uri":"data:...,BASE64"}], then the JSON after its "{"
  return std::strlen("{\"buffers\":[{\"byteLength\":,\"uri\":\"") + std::to_string(buffer).size() +
         std::strlen(kDataUri) + base64_bytes(buffer) + std::strlen("\"}],") + json - 1;
}

bool GltfWriter::check_size(uint32_t vertex_count, size_t face_ids, uint32_t frame_count, bool binary,
                            std::string* error, const GltfScene& scene) {
  return GltfWriter(vertex_count, std::vector<uint32_t>(face_ids), frame_count, 30, binary, scene).fits(error);
}

bool GltfWriter::fits(std::string* error) const {
  std::string deep;
  if (!check_json_depth(scene_.materials_json.data(), scene_.materials_json.size(), kMaxJsonDepth, &deep))
    return fail(error, "its materials (MATL): " + deep);
  const uint64_t bytes = expected_bytes();
  if (bytes > kMaxGltfBytes)
    return fail(error, std::to_string(frame_count_) + " frames of " + std::to_string(vertex_count_) + " vertices need " +
                           std::to_string(bytes >> 20) + " MiB as glTF morph targets" +
                           (binary_ ? "" : " in base64") +
                           ", more than the 1024 MiB dcurve writes: ask for fewer --frames, or write .pc2/.mdd or a folder");
  return true;
}

bool GltfWriter::open(const std::string& path, bool replace, std::string* error) {
  if (frame_count_ == 0) return fail(error, path + ": a glTF output needs at least one frame");
  // Checked on this writer: its attributes and images are not copied again.
  if (!fits(error)) return fail(error, path + ": " + *error);
  if (!out_.open(path, replace, error)) return false;
  const uint64_t buffer = buffer_bytes();
  std::string head;
  if (binary_) {
    json_room_ = padded4(json(true).size());
    std::vector<uint8_t> h(20);
    std::memcpy(h.data(), "glTF", 4);
    store_u32(&h[4], 2);
    store_u32(&h[8], uint32_t(12 + 8 + json_room_ + 8 + buffer));
    store_u32(&h[12], uint32_t(json_room_));
    std::memcpy(&h[16], "JSON", 4);
    head.assign(h.begin(), h.end());
    head.append(json_room_, ' ');  // filled in by finish()
    std::vector<uint8_t> bin(8);
    store_u32(&bin[0], uint32_t(buffer));
    std::memcpy(&bin[4], "BIN\0", 4);
    head.append(bin.begin(), bin.end());
  } else {
    head = "{\"buffers\":[{\"byteLength\":" + std::to_string(buffer) + ",\"uri\":\"" + kDataUri;
  }
  if (!out_.write(head.data(), head.size(), error) || !put(faces_.data(), 4 * faces_.size(), error)) return false;
  for (const GltfScene::Attribute& a : scene_.attributes)
    if (!put(a.values.data(), 4 * a.values.size(), error)) return false;
  for (const MaterialImage& image : scene_.images) {
    const uint8_t zeros[3] = {0, 0, 0};
    if (!put(image.bytes.data(), image.bytes.size(), error) ||
        !put(zeros, padded4(image.bytes.size()) - image.bytes.size(), error))
      return false;
  }
  return true;
}

bool GltfWriter::put(const void* data, size_t size, std::string* error) {
  const auto* p = static_cast<const uint8_t*>(data);
  pending_.insert(pending_.end(), p, p + size);
  return pending_.size() < kFlushBytes || flush(false, error);
}

// Writes the pending bytes (base64: all whole groups of 3, every byte when `last`).
bool GltfWriter::flush(bool last, std::string* error) {
  if (binary_) {
    const bool ok = out_.write(pending_.data(), pending_.size(), error);
    pending_.clear();
    return ok;
  }
  const size_t whole = last ? pending_.size() : pending_.size() / 3 * 3;
  std::string text;
  text.reserve(base64_bytes(whole));
  append_base64(pending_.data(), whole, &text);
  pending_.erase(pending_.begin(), pending_.begin() + whole);
  return out_.write(text.data(), text.size(), error);
}

bool GltfWriter::add_frame(const float* xyz, std::string* error, const float* normals) {
  if (frames_added_ >= frame_count_) return fail(error, out_.path() + ": more frames than the glTF output declares");
  const size_t values = size_t(vertex_count_) * 3;
  std::vector<float> target(xyz, xyz + values);
  if (scene_.normals) target.insert(target.end(), normals, normals + values);
  if (frames_added_++ == 0) base_ = target;
  else
    for (size_t i = 0; i < target.size(); ++i) target[i] -= base_[i];
  std::array<float, 6> b{};
  for (size_t i = 0; i < values; ++i) {
    const int a = int(i % 3);
    b[a] = i < 3 ? target[i] : std::min(b[a], target[i]);
    b[3 + a] = i < 3 ? target[i] : std::max(b[3 + a], target[i]);
  }
  bounds_.push_back(b);
  return put(target.data(), 4 * target.size(), error);
}

bool GltfWriter::write_animation_data(std::string* error) {
  if (frame_count_ < 2) return true;
  std::vector<float> row(frame_count_);
  for (uint32_t i = 0; i < frame_count_; ++i) row[i] = key_time(i);
  if (!put(row.data(), 4 * row.size(), error)) return false;
  row.assign(frame_count_ - 1, 0.0f);
  for (uint32_t i = 0; i < frame_count_; ++i) {  // key i: target i - 1 on
    if (i > 0) row[i - 1] = 1.0f;
    if (!put(row.data(), 4 * row.size(), error)) return false;
    if (i > 0) row[i - 1] = 0.0f;
  }
  return true;
}

bool GltfWriter::finish(std::string* error) {
  if (frames_added_ != frame_count_) return fail(error, out_.path() + ": frames missing for the glTF output");
  if (!write_animation_data(error) || !flush(true, error)) return false;
  std::string text = json(false);
  if (binary_) {
    if (text.size() > json_room_) return fail(error, out_.path() + ": internal error: the glTF JSON outgrew its room");
    text.resize(json_room_, ' ');
    if (!out_.write_at(20, text.data(), text.size(), error)) return false;
  } else {
    text = "\"}]," + text.substr(1);
    if (!out_.write(text.data(), text.size(), error)) return false;
  }
  if (out_.bytes_written() > kMaxGltfBytes) return fail(error, out_.path() + ": internal error: over the glTF size limit");
  return out_.commit(error);
}

}  // namespace dcurve
