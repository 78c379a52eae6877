#include "codec/common/residual_index.h"

#include "codec/common/bytes.h"
#include "codec/common/error.h"
#include "codec/common/fast_residual.h"
#include "codec/common/residual_walk.h"

namespace dcurve {

bool read_residual_index(const uint8_t* payload, size_t size, uint32_t F, bool has_faces, uint64_t data_limit,
                         ResidualIndex* index, std::string* error) {
  ByteReader r(payload, size);
  const uint8_t version = r.u8();
  const uint8_t from_faces = r.u8();
  const uint64_t chunk_frames = r.varint(), count = r.varint();
  if (!r.ok) return fail(error, "residual payload is truncated");
  if ((version < residual_walk::kOldestFormatVersion || version > residual_walk::kFormatVersion) && version != fast_residual::kPayloadVersion)
    return fail(error, "residual payload version " + std::to_string(version) + " is not supported");
  if (from_faces > 1 || from_faces != (has_faces ? 1 : 0))
    return fail(error, "residual payload was coded with a different neighbour structure (faces present or not)");
  if (chunk_frames == 0 || chunk_frames > F) return fail(error, "residual chunk length is out of range");
  if (count != chunk_count(F, uint32_t(chunk_frames)))
    return fail(error, "residual chunk index disagrees with the frame count");
  if (count * 6 > r.remaining()) return fail(error, "residual chunk index is truncated");
  index->version = version;
  index->from_faces = from_faces != 0;
  index->chunk_frames = uint32_t(chunk_frames);
  index->chunks.assign(size_t(count), ChunkEntry());
  uint64_t end = 0;
  for (ChunkEntry& e : index->chunks) {
    e.offset = r.varint();
    e.size = r.varint();
    e.crc = r.u32();
    if (!r.ok) return fail(error, "residual chunk index is truncated");
    if (e.offset != end) return fail(error, "residual chunk index has a gap or an overlap between chunks");
    if (e.size == 0 || e.size > data_limit - end) return fail(error, "residual chunk index points outside the data");
    end += e.size;
  }
  index->index_bytes = r.position();
  index->data_bytes = end;
  return true;
}

}  // namespace dcurve
