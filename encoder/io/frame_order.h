// The order of a folder's frame files: by the frame number in their names, so Houdini's
// unpadded anim.2.obj comes before anim.10.obj.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace dcurve {

// Sorts `files` by the last run of digits in each name (without the extension). Names
// without digits sort by name, but only when no file has digits. A missing or repeated frame
// number, or a mix of numbered and unnumbered names, is an error naming the files.
bool order_frame_files(std::vector<std::filesystem::path>* files, std::string* error);

}  // namespace dcurve
