// What the REND and PLAC writers and readers agree on (format_spec/dcrv.md sections 19-20).
#pragma once
#include <cstddef>
#include <cstdint>

namespace dcurve::render_format {

constexpr uint8_t kVersion = 1;   // first byte of both payloads
constexpr size_t kMaxNameBytes = 1024;  // PLAC's mesh and node names, REND's group names
constexpr size_t kMaxMimeBytes = 64;     // MATL's image media types
// Values (4 bytes each) a decoder builds per byte of REND's raw payload, at most: a face group
// of 2 bytes becomes a 40-byte record and 8 bytes of bookkeeping. A compressed REND whose raw
// size times this exceeds the file's value budget is refused (format_spec/dcrv.md section 15).
constexpr uint64_t kRenderValuesPerByte = 7;

}  // namespace dcurve::render_format
