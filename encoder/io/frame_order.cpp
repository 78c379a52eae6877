#include "encoder/io/frame_order.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "codec/common/error.h"

namespace dcurve {
namespace {

constexpr size_t kMaxDigits = 18;  // fits an int64

// The last run of digits in the file's stem; -1 when it has none, -2 when too long.
long long frame_number(const std::filesystem::path& file) {
  const std::string stem = file.stem().string();
  size_t end = stem.size();
  while (end > 0 && !std::isdigit(static_cast<unsigned char>(stem[end - 1]))) --end;
  if (end == 0) return -1;
  size_t begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[begin - 1]))) --begin;
  if (end - begin > kMaxDigits) return -2;
  return std::stoll(stem.substr(begin, end - begin));
}

struct Numbered {
  long long number;
  std::filesystem::path file;
};

std::string gap_text(long long first, long long last) {
  return first == last ? "frame " + std::to_string(first) : "frames " + std::to_string(first) + "-" + std::to_string(last);
}

// Frame numbers sorted: none repeated, all one step apart (the first gap sets the step).
bool check_sequence(const std::vector<Numbered>& frames, long long* step, std::string* error) {
  *step = frames.size() > 1 ? frames[1].number - frames[0].number : 1;
  for (size_t i = 1; i < frames.size(); ++i) {
    const Numbered &a = frames[i - 1], &b = frames[i];
    if (a.number == b.number)
      return fail(error, a.file.string() + " and " + b.file.filename().string() + " are both frame " +
                             std::to_string(a.number));
    const long long gap = b.number - a.number;
    if (gap == *step) continue;
    const std::string where = a.file.parent_path().string() + ": ";
    const std::string files = a.file.filename().string() + " and " + b.file.filename().string();
    if (*step == 1 || gap % *step == 0)  // whole frames of the sequence are missing
      return fail(error, where + gap_text(a.number + *step, b.number - *step) + " missing between " + files +
                             (*step > 1 ? " (the frames step by " + std::to_string(*step) + ")" : ""));
    return fail(error, where + files + " are " + std::to_string(gap) + (gap == 1 ? " frame" : " frames") + " apart, but " +
                           frames[0].file.filename().string() + " and " + frames[1].file.filename().string() +
                           " are " + std::to_string(*step) + ": an irregular frame step");
  }
  return true;
}

}  // namespace

bool order_frame_files(std::vector<std::filesystem::path>* files, std::string* error, long long* frame_step) {
  long long ignored;
  long long* step = frame_step ? frame_step : &ignored;
  *step = 1;
  std::vector<Numbered> frames;
  std::sort(files->begin(), files->end());
  for (const auto& f : *files) frames.push_back({frame_number(f), f});
  const auto unnumbered = std::find_if(frames.begin(), frames.end(), [](const Numbered& n) { return n.number < 0; });
  if (unnumbered == frames.end()) {
    std::stable_sort(frames.begin(), frames.end(), [](const Numbered& a, const Numbered& b) { return a.number < b.number; });
    if (!check_sequence(frames, step, error)) return false;
    for (size_t i = 0; i < frames.size(); ++i) (*files)[i] = frames[i].file;
    return true;
  }
  if (unnumbered->number == -2) return fail(error, unnumbered->file.string() + ": frame number too long");
  const auto numbered = std::find_if(frames.begin(), frames.end(), [](const Numbered& n) { return n.number >= 0; });
  if (numbered != frames.end())
    return fail(error, unnumbered->file.string() + " has no frame number but " + numbered->file.filename().string() +
                           " has: keep only the frames in the folder");
  return true;  // no numbers at all: name order
}

}  // namespace dcurve
