// An OBJ file parsed once, by dcurve: positions, polygons, each corner's texture coordinate and
// normal, `usemtl` per face and the `mtllib` name. Nothing but the OBJ itself is opened: an
// `mtllib` (a path the file controls, possibly `../..`, absolute, a FIFO or a device) is kept
// as a name for the outputs and never read, so frame folders, `--mesh` files and scene meshes
// fall under the same rule as the glTF reader (read nothing outside the asset).
#pragma once
#include <string>
#include <string_view>

#include "encoder/io/obj_corners.h"
#include "encoder/io/polygon_reader.h"

namespace dcurve {

struct ObjMesh {
  PolygonSoup soup;     // positions and polygons as stored (vertex i is the file's vertex i)
  ObjCorners corners;   // the same polygons as triangle fans, with vt/vn/material per corner
};

// Parses `text` (the bytes of the OBJ at `path`, named in errors). Refused with "PATH: line N:
// ...": a control character, a `v`/`vt`/`vn` record whose values are not decimal numbers within
// float range, a face with fewer than 3 corners, an index (1-based, or negative counting back)
// out of the records read so far, a vertex used twice in a face, a name that is not UTF-8.
// `#` at the start of a line or after white space starts a comment; names (`usemtl`, `mtllib`)
// are the rest of their line, spaces included. Unknown records (o, g, s, l, ...) are skipped.
bool parse_obj(const std::string& path, std::string_view text, ObjMesh* out, std::string* error);

// Reads the regular file at `path` (encoder/io/files.h) and parses it.
bool read_obj(const std::string& path, ObjMesh* out, std::string* error);

}  // namespace dcurve
