#include "cli/output_path.h"

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/output_file.h"

namespace dcurve::cli {
namespace fs = std::filesystem;
namespace {

struct Extension {
  const char* ext;
  OutputKind kind;
  const char* what;
};
constexpr Extension kExtensions[] = {
    {".obj", OutputKind::Mesh, "one mesh"},        {".ply", OutputKind::Mesh, "one mesh"},
    {".off", OutputKind::Mesh, "one mesh"},        {".glb", OutputKind::Gltf, "glTF"},
    {".gltf", OutputKind::Gltf, "glTF"},           {".pc2", OutputKind::PointCache, "point cache"},
    {".mdd", OutputKind::PointCache, "point cache"}, {".dcrv", OutputKind::Dcrv, "dcurve file"},
};

bool allows(const std::vector<OutputKind>& allowed, OutputKind kind) {
  return std::find(allowed.begin(), allowed.end(), kind) != allowed.end();
}

// "X, Y (one mesh), Z (glTF) or a folder (a name ending in /)" for the allowed kinds.
std::string known_outputs(const std::vector<OutputKind>& allowed) {
  std::string list;
  for (size_t i = 0; i < std::size(kExtensions); ++i) {
    const Extension& e = kExtensions[i];
    if (!allows(allowed, e.kind)) continue;
    list += (list.empty() ? "" : " ") + std::string(e.ext);
    const bool last_of_kind = i + 1 == std::size(kExtensions) || kExtensions[i + 1].kind != e.kind;
    if (last_of_kind) list += std::string(" (") + e.what + "),";
  }
  if (allows(allowed, OutputKind::Folder)) list += " or a folder (a name ending in /)";
  else if (!list.empty()) list.pop_back();
  return list;
}

bool is_folder_name(const std::string& path) {
  struct stat st;
  return path.back() == '/' || (lstat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) ||
         fs::path(path).extension().empty();
}

}  // namespace

std::vector<OutputKind> frame_output_kinds() {
  return {OutputKind::Folder, OutputKind::Mesh, OutputKind::Gltf, OutputKind::PointCache};
}

bool output_kind(const std::string& path, const std::vector<OutputKind>& allowed, OutputKind* kind, std::string* error) {
  if (path.empty()) return fail(error, "the output has no name");
  if (is_folder_name(path)) {
    *kind = OutputKind::Folder;
    if (allows(allowed, *kind)) return true;
    return fail(error, path + ": is a folder; the output is a file: " + known_outputs(allowed));
  }
  const std::string ext = lowercase_extension(path);
  for (const Extension& e : kExtensions)
    if (ext == e.ext && allows(allowed, e.kind)) {
      *kind = e.kind;
      return true;
    }
  return fail(error, path + ": unknown output extension " + ext + "; known: " + known_outputs(allowed));
}

bool check_output_file(const std::string& path, bool force, const std::vector<std::string>& inputs, std::string* error) {
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::is_directory(parent, ec))
    return fail(error, path + ": folder " + parent.string() + " does not exist");
  if (is_one_of(path, inputs)) return fail(error, path + ": the output is one of the input files; refusing to overwrite it");
  return check_output_path(path, force, error);
}

}  // namespace dcurve::cli
