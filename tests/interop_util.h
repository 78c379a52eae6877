// Running the independent tools of tests/interop (Node: glTF-Transform, the Khronos glTF
// validator, a PC2/MDD writer and reader of a few lines) and exchanging frames with them.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "cli_util.h"
#include "encoder/io/files.h"
#include "encoder/io/output_file.h"
#include "encoder/io/frames.h"

namespace dcurve::test {

inline std::string interop_dir() { return std::string(DCURVE_SOURCE_DIR) + "/tests/interop"; }

// Empty when the tools can run; else why not. Only a machine without npm skips: with npm,
// scripts/install-deps.sh installs the packages, so their absence is a failure.
inline std::string interop_unavailable() {
  if (std::system("command -v npm >/dev/null 2>&1 && command -v node >/dev/null 2>&1") != 0)
    return "npm is not installed (scripts/install-deps.sh installs it)";
  return "";
}

inline bool interop_packages_present() {
  return std::filesystem::is_directory(interop_dir() + "/node_modules/@gltf-transform/core") &&
         std::filesystem::is_directory(interop_dir() + "/node_modules/gltf-validator");
}

// Runs `node tests/interop/SCRIPT ARGS`, stdout and stderr together.
inline CommandResult run_node(const std::string& script_and_args) {
  CommandResult r;
  const std::string cmd = "node " + interop_dir() + "/" + script_and_args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// The exchange file of tests/interop/frames_io.mjs.
inline bool write_exchange(const std::string& path, const Animation& anim) {
  std::vector<uint8_t> b;
  auto u32 = [&b](uint32_t v) { for (int i = 0; i < 4; ++i) b.push_back(uint8_t(v >> (8 * i))); };
  u32(anim.vertex_count);
  u32(uint32_t(anim.frames.size()));
  u32(uint32_t(anim.faces.size()));
  for (uint32_t id : anim.faces) u32(id);
  for (const auto& f : anim.frames)
    for (float x : f) {
      uint32_t u;
      std::memcpy(&u, &x, 4);
      u32(u);
    }
  std::string err;
  return write_file_atomic(path, b.data(), b.size(), &err);
}

inline bool read_exchange(const std::string& path, Animation* anim) {
  std::vector<uint8_t> b;
  std::string err;
  if (!read_file(path, &b, &err) || b.size() < 12) return false;
  auto u32 = [&b](size_t at) { uint32_t v; std::memcpy(&v, &b[at], 4); return v; };
  const uint32_t v = u32(0), n = u32(4), f = u32(8);
  if (b.size() != 12 + 4 * size_t(f) + 12 * size_t(v) * n) return false;
  *anim = Animation{};
  anim->vertex_count = v;
  for (uint32_t i = 0; i < f; ++i) anim->faces.push_back(u32(12 + 4 * size_t(i)));
  size_t at = 12 + 4 * size_t(f);
  for (uint32_t k = 0; k < n; ++k) {
    anim->frames.emplace_back(3 * size_t(v));
    std::memcpy(anim->frames.back().data(), &b[at], 12 * size_t(v));
    at += 12 * size_t(v);
  }
  return true;
}

// The largest distance between corresponding vertices of two frame sets of equal sizes.
inline double max_distance(const Animation& a, const Animation& b) {
  double worst = 0;
  for (size_t f = 0; f < a.frames.size() && f < b.frames.size(); ++f)
    for (size_t v = 0; 3 * v + 2 < a.frames[f].size() && 3 * v + 2 < b.frames[f].size(); ++v) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) {
        const double d = double(a.frames[f][3 * v + k]) - b.frames[f][3 * v + k];
        d2 += d * d;
      }
      worst = std::max(worst, std::sqrt(d2));
    }
  return worst;
}

}  // namespace dcurve::test
