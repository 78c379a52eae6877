// libFuzzer entry for the encoder's input readers (encoder/io): any bytes go through the
// reader a user's file of that kind would reach, the kind told by the first bytes as a file
// would be named: glTF binary ("glTF") or JSON ("{"), PC2 ("POINTCACHE2"), MDD (a "MDD:"
// prefix the harness strips: MDD has no magic), else OBJ, OFF or PLY (text or binary).
// A crash, sanitizer report, hang, a rejection without a message, or an accepted input that
// is inconsistent (another vertex count than the file declares, a frame of the wrong size, an
// index out of range, a coordinate that is not finite) is a finding.
// An OBJ is read with its corners (UVs, normals, usemtl groups) and turned into render
// vertices and groups, checked for consistency; its mtllib must never be opened: the scratch
// folder holds fifo.mtl, a FIFO that would hang the reader (a timeout is a finding).
// A glTF is written into asset/ of a scratch folder that also holds what its uris may name
// (asset/buf.bin, 100 bytes of a triangle animation) and what they must not read: a FIFO, a
// folder, a link to a file outside and that file (outside.bin, every float kOutsideMarker).
// An accepted animation holding kOutsideMarker read a file outside the asset's folder.
// The readers get a 256 MiB memory limit, within libFuzzer's own.
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "encoder/io/frames.h"
#include "encoder/io/gltf_reader.h"
#include "encoder/io/obj_corners.h"
#include "encoder/io/point_cache.h"

namespace {

enum class Kind { Mesh, Gltf, Pc2, Mdd };

struct Input {
  Kind kind = Kind::Mesh;
  std::string extension;
  std::string bytes;  // what the reader gets
};

std::string mesh_extension(const std::string& text) {
  if (text.rfind("ply", 0) == 0) return ".ply";
  std::istringstream s(text);
  std::string first;
  s >> first;
  return first.size() >= 3 && first.compare(first.size() - 3, 3, "OFF") == 0 ? ".off" : ".obj";
}

Input classify(const std::string& data) {
  if (data.rfind("glTF", 0) == 0) return {Kind::Gltf, ".glb", data};
  if (data.rfind("POINTCACHE2", 0) == 0) return {Kind::Pc2, ".pc2", data};
  if (data.rfind("MDD:", 0) == 0) return {Kind::Mdd, ".mdd", data.substr(4)};
  const size_t first = data.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && data[first] == '{') return {Kind::Gltf, ".gltf", data};
  return {Kind::Mesh, mesh_extension(data), data};
}

// The vertex count a mesh file declares, found independently of the readers: "v" records in
// OBJ, the line after OFF's keyword line, the vertex element of PLY; -1 when it cannot be
// told (no counts line).
long long declared_mesh_vertices(const std::string& text, const std::string& ext) {
  std::istringstream in(text);
  std::string line, word;
  long long count = ext == ".obj" ? 0 : -1;
  bool off_header_seen = false;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    if (!(s >> word) || word[0] == '#') continue;
    if (ext == ".obj") {
      count += word == "v";
    } else if (ext == ".ply") {
      if (word == "end_header") return count;
      std::string name;
      if (word == "element" && s >> name && name == "vertex" && !(s >> count)) return -1;
    } else if (!off_header_seen) {
      off_header_seen = true;  // the keyword's line; the counts follow on the next
    } else {
      return std::istringstream(line) >> count ? count : -1;
    }
  }
  return count;
}

uint32_t u32_at(const std::string& bytes, size_t offset, bool big_endian) {
  uint8_t b[4];
  std::memcpy(b, bytes.data() + offset, 4);
  return big_endian ? uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | b[3]
                    : uint32_t(b[3]) << 24 | uint32_t(b[2]) << 16 | uint32_t(b[1]) << 8 | b[0];
}

constexpr float kOutsideMarker = 31337.0f;
constexpr uint64_t kMaxMemory = uint64_t(256) << 20;

void write_file(const std::string& path, const void* data, size_t size) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || std::fwrite(data, 1, size, f) != size || std::fclose(f) != 0) std::abort();
}

// The companions of asset/input.gltf (see the top of the file).
void make_companions(const std::string& dir) {
  // The layout of tests/gltf_fixture.h: positions, one target, indices, key times, weights.
  const float pos_target[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const uint32_t ids[3] = {0, 1, 2};
  const float keys[4] = {0, 0.5f, 0, 1};
  uint8_t buf[100];
  std::memcpy(buf, pos_target, 72);
  std::memcpy(buf + 72, ids, 12);
  std::memcpy(buf + 84, keys, 16);
  if (mkdir((dir + "/asset").c_str(), 0700) != 0 || mkdir((dir + "/asset/dir.bin").c_str(), 0700) != 0 ||
      mkfifo((dir + "/asset/fifo.bin").c_str(), 0600) != 0 || mkfifo((dir + "/fifo.mtl").c_str(), 0600) != 0 ||
      symlink((dir + "/outside.bin").c_str(), (dir + "/asset/link.bin").c_str()) != 0)
    std::abort();
  write_file(dir + "/asset/buf.bin", buf, 100);
  std::vector<float> outside(25, kOutsideMarker);
  write_file(dir + "/outside.bin", outside.data(), 100);
}

const std::string& scratch_dir() {
  static const std::string dir = [] {
    char name[] = "/tmp/dcurve-reader-fuzz-XXXXXX";
    if (!mkdtemp(name)) std::abort();
    make_companions(name);
    return std::string(name);
  }();
  return dir;
}

std::string write_scratch(const Input& input) {
  const std::string path = scratch_dir() + (input.kind == Kind::Gltf ? "/asset/input" : "/input") + input.extension;
  write_file(path, input.bytes.data(), input.bytes.size());
  return path;
}

void check_positions(const std::vector<float>& xyz, size_t vertices) {
  if (vertices == 0 || xyz.size() != vertices * 3) __builtin_trap();
  for (float x : xyz)
    if (!std::isfinite(x)) __builtin_trap();
}

void check_faces(const std::vector<uint32_t>& faces, size_t vertices) {
  if (faces.size() % 3 != 0) __builtin_trap();
  for (uint32_t id : faces)
    if (id >= vertices) __builtin_trap();
}

void check_animation(const dcurve::Animation& anim) {
  if (anim.frames.empty()) __builtin_trap();
  for (const auto& frame : anim.frames) check_positions(frame, anim.vertex_count);
  check_faces(anim.faces, anim.vertex_count);
}

// An OBJ's render vertices and groups: every corner names a render vertex of its own
// triangle's vertex, every attribute value is finite, every triangle has a group.
void check_obj_render(const dcurve::Animation& anim) {
  const dcurve::AnimationRender& r = anim.render;
  if (r.empty()) return;
  if (r.corners.size() != anim.faces.size()) __builtin_trap();
  for (size_t k = 0; k < r.corners.size(); ++k)
    if (r.corners[k] >= r.source.size() || r.source[r.corners[k]] != anim.faces[k]) __builtin_trap();
  for (const auto& a : r.attributes) {
    if (a.values.size() != r.source.size() * a.components) __builtin_trap();
    for (float x : a.values)
      if (!std::isfinite(x)) __builtin_trap();
  }
  if (!r.groups.empty() && r.face_group.size() != anim.faces.size() / 3) __builtin_trap();
  for (uint32_t g : r.face_group)
    if (g >= r.groups.size()) __builtin_trap();
}

bool read_as_mesh(const Input& input, const std::string& path, std::string* error) {
  dcurve::Animation anim;
  std::vector<float> xyz;
  dcurve::ObjCorners corners;
  if (!dcurve::read_mesh(path, &xyz, &anim.faces, error, &corners)) return false;
  const size_t vertices = xyz.size() / 3;
  const long long declared = declared_mesh_vertices(input.bytes, input.extension);
  if (declared >= 0 && size_t(declared) != vertices) __builtin_trap();  // silent change of vertex count
  check_positions(xyz, vertices);
  check_faces(anim.faces, vertices);
  anim.vertex_count = uint32_t(vertices);
  if (!dcurve::obj_render(corners, &anim, error)) return false;
  check_obj_render(anim);
  return true;
}

bool read_as_gltf(const std::string& path, std::string* error) {
  dcurve::Animation anim;
  dcurve::ReadLimits limits;
  limits.max_memory = kMaxMemory;
  if (!dcurve::read_gltf_animation(path, -1, &anim, error, limits)) return false;
  check_animation(anim);
  for (const auto& frame : anim.frames)
    for (float x : frame)
      if (x == kOutsideMarker) __builtin_trap();  // read a file outside the asset's folder
  if (!(anim.frame_rate > 0) || !std::isfinite(anim.frame_rate)) __builtin_trap();
  return true;
}

// PC2: 12-byte signature, version, points, start, rate, samples; MDD: frames, points (big-endian).
bool read_as_point_cache(const Input& input, const std::string& path, std::string* error) {
  dcurve::Animation anim;
  dcurve::PointCacheInfo info;
  if (!dcurve::read_point_cache(path, &anim, &info, error, kMaxMemory)) return false;
  const bool mdd = input.kind == Kind::Mdd;
  if (input.bytes.size() < (mdd ? 8u : 32u)) __builtin_trap();  // accepted without a header
  const uint32_t points = u32_at(input.bytes, mdd ? 4 : 16, mdd);
  const uint32_t frames = u32_at(input.bytes, mdd ? 0 : 28, mdd);
  if (anim.vertex_count != points || anim.frames.size() != frames) __builtin_trap();
  for (const auto& frame : anim.frames) check_positions(frame, anim.vertex_count);
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const Input input = classify(std::string(reinterpret_cast<const char*>(data), size));
  const std::string path = write_scratch(input);
  std::string error;
  bool accepted = false;
  switch (input.kind) {
    case Kind::Mesh: accepted = read_as_mesh(input, path, &error); break;
    case Kind::Gltf: accepted = read_as_gltf(path, &error); break;
    case Kind::Pc2:
    case Kind::Mdd: accepted = read_as_point_cache(input, path, &error); break;
  }
  if (!accepted && error.empty()) __builtin_trap();  // every rejection must say why
  return 0;
}
