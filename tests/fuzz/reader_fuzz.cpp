// libFuzzer entry for the encoder's input readers (encoder/io): any bytes go through the
// reader a user's file of that kind would reach, the kind told by the first bytes as a file
// would be named: glTF binary ("glTF") or JSON ("{"), PC2 ("POINTCACHE2"), MDD (a "MDD:"
// prefix the harness strips: MDD has no magic), else OBJ, OFF or PLY (text or binary).
// A crash, sanitizer report, hang, a rejection without a message, or an accepted input that
// is inconsistent (another vertex count than the file declares, a frame of the wrong size, an
// index out of range, a coordinate that is not finite) is a finding.
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

const std::string& scratch_dir() {
  static const std::string dir = [] {
    char name[] = "/tmp/dcurve-reader-fuzz-XXXXXX";
    if (!mkdtemp(name)) std::abort();
    return std::string(name);
  }();
  return dir;
}

std::string write_scratch(const Input& input) {
  const std::string path = scratch_dir() + "/input" + input.extension;
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || std::fwrite(input.bytes.data(), 1, input.bytes.size(), f) != input.bytes.size() ||
      std::fclose(f) != 0)
    std::abort();
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

bool read_as_mesh(const Input& input, const std::string& path, std::string* error) {
  std::vector<float> xyz;
  std::vector<uint32_t> faces;
  if (!dcurve::read_mesh(path, &xyz, &faces, error)) return false;
  const size_t vertices = xyz.size() / 3;
  const long long declared = declared_mesh_vertices(input.bytes, input.extension);
  if (declared >= 0 && size_t(declared) != vertices) __builtin_trap();  // silent change of vertex count
  check_positions(xyz, vertices);
  check_faces(faces, vertices);
  return true;
}

bool read_as_gltf(const std::string& path, std::string* error) {
  dcurve::Animation anim;
  if (!dcurve::read_gltf_animation(path, -1, &anim, error)) return false;
  check_animation(anim);
  if (!(anim.frame_rate > 0) || !std::isfinite(anim.frame_rate)) __builtin_trap();
  return true;
}

// PC2: 12-byte signature, version, points, start, rate, samples; MDD: frames, points (big-endian).
bool read_as_point_cache(const Input& input, const std::string& path, std::string* error) {
  dcurve::Animation anim;
  dcurve::PointCacheInfo info;
  if (!dcurve::read_point_cache(path, &anim, &info, error)) return false;
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
