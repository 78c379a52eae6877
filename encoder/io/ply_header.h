// PLY headers, parsed strictly before OpenMesh's PLY reader sees a file: that reader crashes
// on some malformed headers (a property before any element) and trusts every count.
#pragma once
#include <fstream>
#include <string>
#include <vector>

namespace dcurve {

// What a PLY header declares, as far as the checks need it.
struct PlyElement {
  std::string name;
  long long count = 0;
  long long min_bytes = 0;  // the least a binary record takes (a list counted as empty)
};
struct PlyHeader {
  bool ascii = false;
  bool wide_list_count = false;  // a list whose count is wider than 16 bits
  std::vector<PlyElement> elements;
  std::vector<std::string> vertex_properties;
};

// Reads the header from the start of `in` up to "end_header" (*number: its last line).
// False with "PATH: line N: malformed PLY header" (or what else is wrong) when a line is not
// one PLY allows, the vertex element lacks x, y or z, or there is no end_header.
bool read_ply_header(std::ifstream& in, const std::string& path, PlyHeader* h, size_t* number, std::string* error);

// With `in` just past the header: whether a binary body can hold the records the header
// declares (OpenMesh's reader would otherwise add vertices past the end of the file).
bool binary_ply_fits(std::ifstream& in, const PlyHeader& h);

}  // namespace dcurve
