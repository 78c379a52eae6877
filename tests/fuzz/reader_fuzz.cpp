// libFuzzer entry for the encoder's mesh readers (encoder/io): any bytes, as an OBJ, OFF or
// PLY file (text or binary; chosen by the first bytes, as a user's file would be named), go
// through read_mesh. A crash, sanitizer report, hang, a rejection without a message, or a
// mesh read with another vertex count than the file declares, an index out of range or a
// coordinate that is not finite is a finding.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "encoder/io/frames.h"

namespace {

std::string extension_for(const std::string& text) {
  if (text.rfind("ply", 0) == 0) return ".ply";
  std::istringstream s(text);
  std::string first;
  s >> first;
  return first.size() >= 3 && first.compare(first.size() - 3, 3, "OFF") == 0 ? ".off" : ".obj";
}

// The vertex count the file declares, found independently of the readers: "v" records in
// OBJ, the line after OFF's keyword line, the vertex element of PLY; -1 when it cannot be
// told (no counts line).
long long declared_vertices(const std::string& text, const std::string& ext) {
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

const std::string& scratch_dir() {
  static const std::string dir = [] {
    char name[] = "/tmp/dcurve-reader-fuzz-XXXXXX";
    if (!mkdtemp(name)) std::abort();
    return std::string(name);
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string ext = extension_for(text);
  const std::string path = scratch_dir() + "/input" + ext;
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || std::fwrite(data, 1, size, f) != size || std::fclose(f) != 0) std::abort();
  std::vector<float> xyz;
  std::vector<uint32_t> faces;
  std::string error;
  if (!dcurve::read_mesh(path, &xyz, &faces, &error)) {
    if (error.empty()) __builtin_trap();  // every rejection must say why
    return 0;
  }
  const size_t vertices = xyz.size() / 3;
  const long long declared = declared_vertices(text, ext);
  if (declared >= 0 && size_t(declared) != vertices) __builtin_trap();  // silent change of vertex count
  if (vertices == 0 || faces.size() % 3 != 0) __builtin_trap();
  for (uint32_t id : faces)
    if (id >= vertices) __builtin_trap();
  for (float x : xyz)
    if (!std::isfinite(x)) __builtin_trap();
  return 0;
}
