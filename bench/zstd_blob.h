// zstd and integer packing shared by the baselines that entropy-code quantized integers.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve::bench {

// Baselines compress with the same zstd level as the .dcrv container, so no side wins by
// a stronger entropy-coder setting.
constexpr int kBaselineZstdLevel = 19;

std::vector<uint8_t> zstd_pack(const void* data, size_t size, int level = kBaselineZstdLevel);

// Decompresses `blob`, which must hold exactly `expected_size` bytes.
bool zstd_unpack(const std::vector<uint8_t>& blob, size_t expected_size, std::vector<uint8_t>* out,
                 std::string* error);

// Little-endian int32 in/out, so packed bytes do not depend on the host.
void append_int32_le(const std::vector<int32_t>& values, std::vector<uint8_t>* out);
std::vector<int32_t> read_int32_le(const uint8_t* data, size_t count);

// Byte b of every 4-byte value together, b = 0..3: the high bytes of small integers form
// long zero runs that zstd codes almost for free. `le` holds whole int32 values.
std::vector<uint8_t> to_byte_planes(const std::vector<uint8_t>& le);
std::vector<uint8_t> from_byte_planes(const std::vector<uint8_t>& planes);

// Rounds x / step to the nearest integer; false when it leaves the int32 range.
bool quantize(double x, double step, int32_t* q);

}  // namespace dcurve::bench
