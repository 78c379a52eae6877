#include "encoder/io/frame_order.h"

#include <algorithm>
#include <cctype>

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

bool check_sequence(const std::vector<Numbered>& frames, std::string* error) {
  for (size_t i = 1; i < frames.size(); ++i) {
    const Numbered &a = frames[i - 1], &b = frames[i];
    if (a.number == b.number)
      return fail(error, a.file.string() + " and " + b.file.filename().string() + " are both frame " +
                             std::to_string(a.number));
    if (b.number != a.number + 1)
      return fail(error, a.file.parent_path().string() + ": frame" + (b.number - a.number > 2 ? "s " : " ") +
                             std::to_string(a.number + 1) +
                             (b.number - a.number > 2 ? "-" + std::to_string(b.number - 1) : "") + " missing between " +
                             a.file.filename().string() + " and " + b.file.filename().string());
  }
  return true;
}

}  // namespace

bool order_frame_files(std::vector<std::filesystem::path>* files, std::string* error) {
  std::vector<Numbered> frames;
  std::sort(files->begin(), files->end());
  for (const auto& f : *files) frames.push_back({frame_number(f), f});
  const auto unnumbered = std::find_if(frames.begin(), frames.end(), [](const Numbered& n) { return n.number < 0; });
  if (unnumbered == frames.end()) {
    std::stable_sort(frames.begin(), frames.end(), [](const Numbered& a, const Numbered& b) { return a.number < b.number; });
    if (!check_sequence(frames, error)) return false;
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
