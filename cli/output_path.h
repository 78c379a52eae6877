// What `-o` names, and the one overwrite rule of encode, decode and simulate: an existing
// file, or a folder that holds frames, is replaced only with --force; a symbolic link or a
// special file is never replaced; nor is a file the command reads.
#pragma once
#include <string>
#include <vector>

namespace dcurve::cli {

enum class OutputKind { Folder, Mesh, Gltf, PointCache, Dcrv };

// The kind of output `path` names: a folder when it ends in "/", is an existing folder or
// has no extension; otherwise by its extension, which must be one of `allowed` (an unknown
// or unsupported one: false, and the message lists the known ones).
bool output_kind(const std::string& path, const std::vector<OutputKind>& allowed, OutputKind* kind, std::string* error);

// The kinds decode writes; simulate writes the same but one mesh.
std::vector<OutputKind> frame_output_kinds();

// For a file output: its folder exists, the path may be written (encoder/io/output_file's
// check_output_path: a file there only with `force`) and it is none of `inputs`. Folder
// outputs are checked by encoder/io/output_folder as they are opened.
bool check_output_file(const std::string& path, bool force, const std::vector<std::string>& inputs, std::string* error);

}  // namespace dcurve::cli
