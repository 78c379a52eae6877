// Text a file controls (a glTF uri or name, a library's message that repeats it) made safe to
// print: a hostile file must not drive the terminal or flood the error output.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>

namespace dcurve {

// How much of a file-controlled text a message repeats.
constexpr size_t kMaxQuotedBytes = 200;

// `text` with control characters (C0, DEL, C1), terminal escapes and bytes that are not UTF-8
// shown as \xNN and backslashes doubled; cut after `max_bytes` bytes of the original with
// "... (N bytes)" appended. Valid UTF-8 (names in any script) is kept as it is.
std::string quote_file_text(std::string_view text, size_t max_bytes = kMaxQuotedBytes);

}  // namespace dcurve
