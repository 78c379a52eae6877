#include "encoder/io/quoted_text.h"

#include <cstdint>
#include <cstdio>

namespace dcurve {
namespace {

void append_hex(std::string* out, uint8_t byte) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "\\x%02x", byte);
  out->append(buf);
}

// Length of the well-formed UTF-8 sequence at text[i] that encodes a printable code point
// (not a C1 control), or 0.
size_t printable_utf8_length(std::string_view text, size_t i) {
  const uint8_t lead = uint8_t(text[i]);
  const size_t n = lead >= 0xf0 && lead <= 0xf4 ? 4 : lead >= 0xe0 ? 3 : lead >= 0xc2 && lead < 0xe0 ? 2 : 0;
  if (n == 0 || i + n > text.size() || lead > 0xf4) return 0;
  uint32_t cp = lead & (0x7f >> n);
  for (size_t k = 1; k < n; ++k) {
    const uint8_t c = uint8_t(text[i + k]);
    if ((c & 0xc0) != 0x80) return 0;
    cp = cp << 6 | (c & 0x3f);
  }
  const uint32_t smallest = n == 2 ? 0x80 : n == 3 ? 0x800 : 0x10000;
  if (cp < smallest || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff) || cp <= 0x9f) return 0;
  return n;
}

}  // namespace

std::string quote_file_text(std::string_view text, size_t max_bytes) {
  const size_t shown = text.size() > max_bytes ? max_bytes : text.size();
  std::string out;
  for (size_t i = 0; i < shown;) {
    const uint8_t c = uint8_t(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      if (c == '\\') out.push_back('\\');
      out.push_back(char(c));
      ++i;
    } else if (const size_t n = c >= 0x80 ? printable_utf8_length(text, i) : 0; n > 0 && i + n <= shown) {
      out.append(text.substr(i, n));
      i += n;
    } else {
      append_hex(&out, c);
      ++i;
    }
  }
  if (shown < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

}  // namespace dcurve
