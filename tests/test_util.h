// Helpers shared by the tests: reading a few frames of the real corpus, simulating a
// shortened built-in scene, the decoded error of a file, a scratch folder (running the CLI:
// cli_util.h).
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "encoder/io/frames.h"
#include "encoder/metrics.h"

// The build defines the corpus folder (tests/CMakeLists.txt); beside the checkout otherwise,
// so that this header compiles on its own.
#ifndef DCURVE_CORPUS_EXT
#define DCURVE_CORPUS_EXT "../shared/corpus-ext"
#endif

namespace dcurve::test {

inline std::string corpus_ext(const std::string& name) { return std::string(DCURVE_CORPUS_EXT) + "/" + name; }
inline bool have_corpus_ext() { return std::filesystem::is_directory(DCURVE_CORPUS_EXT); }

// Reads frames [0, count) of a corpus-ext sequence (frame_%05d.obj), or fails the test.
inline Animation read_corpus_frames(const std::string& sequence, int count, int stride = 1) {
  Animation anim;
  for (int i = 0; i < count; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%05d.obj", i * stride);
    std::vector<float> xyz;
    std::vector<uint32_t> faces;
    std::string err;
    if (!read_mesh(corpus_ext(sequence) + name, &xyz, &faces, &err)) throw std::runtime_error(err);
    anim.vertex_count = uint32_t(xyz.size() / 3);
    anim.faces = faces;
    anim.frames.push_back(std::move(xyz));
  }
  return anim;
}

// Simulates the first `frames` (>= 1) frames of a built-in scene, or fails the test.
// Defined in test_util.cpp, compiled once for every test program: the scene's header brings
// Eigen and nlohmann/json, which most tests do not use.
Animation simulate_builtin(const std::string& name, uint32_t frames);

// The faces of a W x H grid of vertices numbered row by row, two triangles per cell.
inline std::vector<uint32_t> grid_faces(uint32_t W, uint32_t H) {
  std::vector<uint32_t> faces;
  for (uint32_t y = 0; y + 1 < H; ++y)
    for (uint32_t x = 0; x + 1 < W; ++x) {
      const uint32_t v = y * W + x;
      faces.insert(faces.end(), {v, v + 1, v + W, v + 1, v + W + 1, v + W});
    }
  return faces;
}

// Largest vertex error over all frames of `bytes` decoded by the runtime decoder against
// anim, as a fraction of L (HUGE_VAL, and a test failure, when it does not open).
inline double decoded_max_error(const std::vector<uint8_t>& bytes, const Animation& anim) {
  std::string err;
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  EXPECT_TRUE(dec) << err;
  if (!dec) return HUGE_VAL;
  std::vector<std::vector<float>> decoded(anim.frames.size(), std::vector<float>(size_t(anim.vertex_count) * 3));
  for (uint32_t f = 0; f < decoded.size(); ++f)
    if (!dec->evaluate_frame(f, decoded[f].data())) return std::numeric_limits<double>::infinity();
  return measure_error(anim, decoded).max_error;
}

// The file encode_animation writes for anim with options o (a test failure, and no bytes, when
// it fails).
inline std::vector<uint8_t> encoded(const Animation& anim, const EncodeOptions& o, EncodeReport* report = nullptr) {
  std::vector<uint8_t> bytes;
  std::string err;
  EXPECT_TRUE(encode_animation(anim, o, &bytes, report, &err)) << err;
  return bytes;
}

// Whether `file` is either refused (at open, or by the evaluation of a frame whose chunk
// fails its checks) or decodes every frame exactly as `original` (an open decoder of the
// undamaged file) does: what a damaged byte that no check can see must do.
inline ::testing::AssertionResult refused_or_decodes_as(const std::vector<uint8_t>& file, const Decoder& original) {
  std::string err;
  auto dec = Decoder::open_memory(file.data(), file.size(), &err);
  if (!dec) return ::testing::AssertionSuccess();
  std::vector<float> a(size_t(original.vertex_count()) * 3), b(a.size());
  for (uint32_t f = 0; f < dec->frame_count(); ++f) {
    if (!dec->evaluate_frame(f, a.data())) return ::testing::AssertionSuccess();
    if (!original.evaluate_frame(f, b.data())) return ::testing::AssertionFailure() << "original fails frame " << f;
    if (a != b) return ::testing::AssertionFailure() << "decodes frame " << f << " differently";
  }
  return ::testing::AssertionSuccess();
}

// Whether `bytes` open and every frame evaluates: what a damaged file must not do (a chunk
// is checked when a frame needs it, not at open).
inline bool opens_and_decodes(const std::vector<uint8_t>& bytes, std::string* error) {
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), error);
  if (!dec) return false;
  std::vector<float> xyz(size_t(dec->vertex_count()) * 3);
  Error e;
  for (uint32_t f = 0; f < dec->frame_count(); ++f)
    if (!dec->evaluate_frame(f, xyz.data(), &e)) {
      *error = e.message;
      return false;
    }
  return true;
}

// A unit square as two triangles in a text format ("obj", "off" or "ply"), its second
// vertex written as `v1` (three numbers, or a bad value to test the readers).
inline std::string square(const std::string& ext, const std::string& v1) {
  const std::string v = "0 0 0\n" + v1 + "\n0 1 0\n1 1 0\n";
  if (ext == "obj") return "v 0 0 0\nv " + v1 + "\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
  if (ext == "off") return "OFF\n4 2 0\n" + v + "3 0 1 2\n3 1 3 2\n";
  return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 2\nproperty list uchar int vertex_indices\nend_header\n" + v + "3 0 1 2\n3 1 3 2\n";
}
// The line of square()'s second vertex in its file, counted from 1.
inline size_t square_second_vertex_line(const std::string& ext) { return ext == "obj" ? 2 : ext == "off" ? 4 : 11; }

// Each triangle rotated to start at its smallest id (winding kept), then sorted.
inline std::vector<std::array<uint32_t, 3>> canonical_triangles(const std::vector<uint32_t>& faces) {
  std::vector<std::array<uint32_t, 3>> t;
  for (size_t i = 0; i + 2 < faces.size(); i += 3) {
    std::array<uint32_t, 3> f = {faces[i], faces[i + 1], faces[i + 2]};
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    t.push_back(f);
  }
  std::sort(t.begin(), t.end());
  return t;
}

// The whole content of a file ("" when it cannot be read).
// The names in a folder, sorted.
inline std::vector<std::string> listing(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(folder)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

inline std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A scratch folder removed when the object dies.
// Writes a one-triangle OBJ at height z = `z`, so each frame says which file it came from.
inline void write_triangle_obj(const std::string& path, double z) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error(path + ": cannot write");
  std::fprintf(f, "v 0 0 %.9g\nv 1 0 %.9g\nv 0 1 %.9g\nf 1 2 3\n", z, z, z);
  std::fclose(f);
}

struct TempDir {
  std::filesystem::path path;
  TempDir() {
    char tmpl[] = "/tmp/dcurve_test_XXXXXX";
    path = mkdtemp(tmpl);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

}  // namespace dcurve::test
