// The order of a folder's frame files: by the frame number in their names, so Houdini's
// unpadded anim.2.obj comes before anim.10.obj, and the step between their numbers.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace dcurve {

// Sorts `files` by the last run of digits in each name (without the extension). Names
// without digits sort by name, but only when no file has digits. The numbers may step by
// any constant (frame_00000, frame_00002, ...: a DCC's frame step), returned in
// *frame_step (1 for unnumbered names or one file). A repeated number, a gap unlike the
// first one (a missing frame or an irregular step), or a mix of numbered and unnumbered
// names is an error naming the files.
bool order_frame_files(std::vector<std::filesystem::path>* files, std::string* error, long long* frame_step = nullptr);

}  // namespace dcurve
