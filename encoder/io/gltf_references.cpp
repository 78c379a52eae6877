#include "encoder/io/gltf_references.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "encoder/io/files.h"

namespace dcurve {
namespace {

// Collects the strings at buffers[*].uri and images[*].uri: depth 1 is the top object,
// 2 the array, 3 an entry, whose "uri" key is wanted.
class UriCollector : public nlohmann::json_sax<nlohmann::json> {
 public:
  std::vector<std::string> uris;

  bool key(string_t& k) override {
    if (depth_ == 1) in_list_ = k == "buffers" || k == "images";
    want_ = depth_ == 3 && in_list_ && k == "uri";
    return true;
  }
  bool string(string_t& s) override {
    if (want_ && depth_ == 3) uris.push_back(s);
    want_ = false;
    return true;
  }
  bool start_object(std::size_t) override { return enter(); }
  bool start_array(std::size_t) override { return enter(); }
  bool end_object() override { return leave(); }
  bool end_array() override { return leave(); }
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

 private:
  // Deeper than any glTF needs: stop (the reader refuses such a file).
  bool enter() {
    want_ = false;
    return ++depth_ < 256;
  }
  bool leave() {
    --depth_;
    return true;
  }
  bool value() {
    want_ = false;
    return true;
  }
  int depth_ = 0;
  bool in_list_ = false, want_ = false;
};

// A .glb's JSON chunk (header, then the chunk's length and type), or the whole .gltf.
std::string json_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  if (lowercase_extension(path) != ".glb") return std::string(std::istreambuf_iterator<char>(in), {});
  uint8_t head[20];
  if (!in.read(reinterpret_cast<char*>(head), sizeof head) || std::memcmp(head, "glTF", 4) != 0 ||
      std::memcmp(head + 16, "JSON", 4) != 0)
    return "";
  uint32_t length;
  std::memcpy(&length, head + 12, 4);
  std::string text(std::min<uint32_t>(length, 1u << 28), '\0');
  in.read(text.data(), std::streamsize(text.size()));
  text.resize(size_t(in.gcount()));
  return text;
}

std::string percent_decoded(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uint8_t(uri[i + 1])) && std::isxdigit(uint8_t(uri[i + 2]))) {
      out.push_back(char(std::stoi(uri.substr(i + 1, 2), nullptr, 16)));
      i += 2;
    } else {
      out.push_back(uri[i]);
    }
  }
  return out;
}

}  // namespace

std::vector<std::string> gltf_referenced_files(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  if (ext != ".gltf" && ext != ".glb") return {};
  UriCollector collector;
  nlohmann::json::sax_parse(json_text(path), &collector, nlohmann::json::input_format_t::json, false);
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::vector<std::string> files;
  for (const std::string& uri : collector.uris)
    if (uri.rfind("data:", 0) != 0) files.push_back((folder / percent_decoded(uri)).string());
  return files;
}

}  // namespace dcurve
