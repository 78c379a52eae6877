#include "encoder/io/json_depth.h"

#include "codec/common/error.h"

namespace dcurve {

bool check_json_depth(const char* text, size_t size, int max_depth, std::string* error) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < size; ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;  // the escaped character cannot end the string
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth)
        return fail(error, "JSON nested deeper than " + std::to_string(max_depth) + " levels (at byte " +
                               std::to_string(i) + ")");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return true;
}

}  // namespace dcurve
