// What the REND and PLAC writers and readers agree on (format_spec/dcrv.md sections 19-20).
#pragma once
#include <cstddef>
#include <cstdint>

namespace dcurve::render_format {

constexpr uint8_t kVersion = 1;   // first byte of both payloads
constexpr size_t kMaxNameBytes = 1024;  // PLAC's mesh and node names, REND's group names
constexpr size_t kMaxMimeBytes = 64;     // MATL's image media types

}  // namespace dcurve::render_format
