#include "encoder/io/polygon_reader.h"

// OpenMesh 9 headers trip GCC 12's -Wmaybe-uninitialized on a default-constructed Vec3f
// (clang, which builds the sanitizer and fuzz passes, has no such warning to ignore).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <exception>

#include "codec/common/error.h"

namespace dcurve {
namespace {

using Kernel = OpenMesh::PolyMesh_ArrayKernelT<>;

// OpenMesh's importer with faces recorded as given instead of added to the kernel (which
// only ever holds the vertices, so every id the readers hand out stays the file's id).
class SoupImporter : public OpenMesh::IO::ImporterT<Kernel> {
 public:
  SoupImporter(Kernel& kernel, PolygonSoup* soup) : ImporterT<Kernel>(kernel), soup_(soup) {
    soup_->polygon_offsets.assign(1, 0);
  }
  OpenMesh::FaceHandle add_face(const VHandles& ids) override {
    for (auto vh : ids) soup_->ids.push_back(uint32_t(vh.idx()));
    soup_->polygon_offsets.push_back(uint32_t(soup_->ids.size()));
    return OpenMesh::FaceHandle();  // no kernel face: the readers then set no face attribute
  }
  // Face texture coordinates need kernel faces; dcurve does not keep them.
  void add_face_texcoords(OpenMesh::FaceHandle, OpenMesh::VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
  void add_face_texcoords(OpenMesh::FaceHandle, OpenMesh::VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
  size_t n_faces() const override { return soup_->polygon_count(); }
  // A header's counts are not trusted to size anything: the file is read as it is.
  void reserve(unsigned int, unsigned int, unsigned int) override {}

 private:
  PolygonSoup* soup_;
};

// OpenMesh reports what it reads on its log streams; a codec's CLI must stay quiet.
void silence_openmesh() {
  static const bool done = [] {
    ::omlog().disable();
    ::omout().disable();
    ::omerr().disable();
    return true;
  }();
  (void)done;
}

}  // namespace

bool read_polygon_soup(const std::string& path, PolygonSoup* soup, std::string* error) {
  silence_openmesh();
  *soup = PolygonSoup{};
  Kernel kernel;
  SoupImporter importer(kernel, soup);
  OpenMesh::IO::Options opt;
  try {
    if (!OpenMesh::IO::IOManager().read(path, importer, opt))
      return fail(error, path + ": cannot read mesh (unsupported format or malformed file)");
  } catch (const std::exception& e) {  // e.g. std::bad_alloc for a count no file could hold
    return fail(error, path + ": cannot read mesh: " + e.what());
  }
  soup->xyz.resize(kernel.n_vertices() * 3);
  for (auto vh : kernel.vertices()) {
    const auto& p = kernel.point(vh);
    for (int a = 0; a < 3; ++a) soup->xyz[3 * size_t(vh.idx()) + a] = p[a];
  }
  return true;
}

}  // namespace dcurve
