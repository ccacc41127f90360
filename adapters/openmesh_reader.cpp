#include "adapters/openmesh_reader.h"

#include "adapters/format_headers.h"
#include "adapters/text_input.h"

#include <algorithm>
#include <cctype>
#include <string>

#ifdef OSD_CULL_HAVE_OPENMESH
#include <OpenMesh/Core/IO/IOInstances.hh>
#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <mutex>
#include <sstream>
#endif

namespace osd_cull::adapters::detail {

#ifdef OSD_CULL_HAVE_OPENMESH
namespace {

namespace OM = OpenMesh;
using OM::IO::BaseImporter;

// Records what an OpenMesh reader delivers: positions and the face list, untouched.
// Everything else a reader may hand over (normals, colours, texture coordinates, status,
// halfedge connectivity of the OM format) does not affect a subdivision cage.
class FaceListImporter final : public BaseImporter {
 public:
  explicit FaceListImporter(CageMesh& mesh) : mesh_(mesh) {}

  OM::VertexHandle add_vertex(const OM::Vec3f& p) override { return add_vertex(OM::Vec3d(p)); }
  OM::VertexHandle add_vertex(const OM::Vec3d& p) override {
    mesh_.positions.emplace_back(p[0], p[1], p[2]);
    return OM::VertexHandle(static_cast<int>(mesh_.positions.size()) - 1);
  }
  OM::VertexHandle add_vertex() override { return add_vertex(OM::Vec3d(0, 0, 0)); }
  void set_point(OM::VertexHandle v, const OM::Vec3f& p) override {
    if (v.is_valid() && static_cast<size_t>(v.idx()) < mesh_.positions.size())
      mesh_.positions[static_cast<size_t>(v.idx())] = glm::dvec3(p[0], p[1], p[2]);
  }
  OM::FaceHandle add_face(const VHandles& vertices) override {
    mesh_.faceSizes.push_back(static_cast<int>(vertices.size()));
    for (OM::VertexHandle v : vertices) mesh_.faceVertices.push_back(v.idx());
    return OM::FaceHandle(mesh_.faceCount() - 1);
  }
  OM::HalfedgeHandle add_edge(OM::VertexHandle, OM::VertexHandle) override {
    return OM::HalfedgeHandle();
  }
  OM::FaceHandle add_face(OM::HalfedgeHandle) override { return OM::FaceHandle(); }

  void add_face_texcoords(OM::FaceHandle, OM::VertexHandle,
                          const std::vector<OM::Vec2f>&) override {}
  void add_face_texcoords(OM::FaceHandle, OM::VertexHandle,
                          const std::vector<OM::Vec3f>&) override {}
  void set_face_texindex(OM::FaceHandle, int) override {}
  void set_halfedge(OM::VertexHandle, OM::HalfedgeHandle) override {}
  void set_normal(OM::VertexHandle, const OM::Vec3f&) override {}
  void set_normal(OM::VertexHandle, const OM::Vec3d&) override {}
  void set_color(OM::VertexHandle, const OM::Vec3uc&) override {}
  void set_color(OM::VertexHandle, const OM::Vec4uc&) override {}
  void set_color(OM::VertexHandle, const OM::Vec3f&) override {}
  void set_color(OM::VertexHandle, const OM::Vec4f&) override {}
  void set_texcoord(OM::VertexHandle, const OM::Vec2f&) override {}
  void set_status(OM::VertexHandle, const OM::Attributes::StatusInfo&) override {}
  void set_next(OM::HalfedgeHandle, OM::HalfedgeHandle) override {}
  void set_face(OM::HalfedgeHandle, OM::FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(OM::HalfedgeHandle, const OM::Vec2f&) override {}
  void set_texcoord(OM::VertexHandle, const OM::Vec3f&) override {}
  void set_texcoord(OM::HalfedgeHandle, const OM::Vec3f&) override {}
  void set_status(OM::HalfedgeHandle, const OM::Attributes::StatusInfo&) override {}
  void set_color(OM::EdgeHandle, const OM::Vec3uc&) override {}
  void set_color(OM::EdgeHandle, const OM::Vec4uc&) override {}
  void set_color(OM::EdgeHandle, const OM::Vec3f&) override {}
  void set_color(OM::EdgeHandle, const OM::Vec4f&) override {}
  void set_status(OM::EdgeHandle, const OM::Attributes::StatusInfo&) override {}
  void set_normal(OM::FaceHandle, const OM::Vec3f&) override {}
  void set_normal(OM::FaceHandle, const OM::Vec3d&) override {}
  void set_color(OM::FaceHandle, const OM::Vec3uc&) override {}
  void set_color(OM::FaceHandle, const OM::Vec4uc&) override {}
  void set_color(OM::FaceHandle, const OM::Vec3f&) override {}
  void set_color(OM::FaceHandle, const OM::Vec4f&) override {}
  void set_status(OM::FaceHandle, const OM::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

  size_t n_vertices() const override { return mesh_.positions.size(); }
  size_t n_faces() const override { return mesh_.faceSizes.size(); }
  size_t n_edges() const override { return 0; }

 private:
  CageMesh& mesh_;
};

// OpenMesh reports problems on its global omerr() stream; while a file is read, they go
// into a string (for the error message) instead of stderr.
class CapturedOmErr {
 public:
  CapturedOmErr() {
    // omlog() chatters about every header token it skips; silence it while reading.
    logWasEnabled_ = ::omlog().is_enabled();
    ::omlog().disable();
    cerrWasConnected_ = ::omerr().disconnect(std::cerr);
    ::omerr().connect(text_);
  }
  ~CapturedOmErr() {
    ::omerr().flush();
    ::omerr().disconnect(text_);
    if (cerrWasConnected_) ::omerr().connect(std::cerr);
    if (logWasEnabled_) ::omlog().enable();
  }
  /// The distinct lines OpenMesh wrote (it checks a file before reading it, and repeats
  /// itself), joined with "; ".
  std::string text() {
    ::omerr().flush();
    std::istringstream in(text_.str());
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) {
      while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back())))
        line.pop_back();
      if (!line.empty() && std::find(lines.begin(), lines.end(), line) == lines.end())
        lines.push_back(line);
    }
    std::string joined;
    for (const std::string& line : lines) joined += (joined.empty() ? "" : "; ") + line;
    return joined;
  }

 private:
  std::ostringstream text_;
  bool cerrWasConnected_ = false;
  bool logWasEnabled_ = false;
};

}  // namespace

bool haveOpenMesh() { return true; }

CageMesh readWithOpenMesh(const std::filesystem::path& path, std::string_view bytes,
                          Scheme scheme) {
  const std::string file = path.string();
  const std::string ext = lowerExtension(path);
  CageMesh mesh;
  mesh.source = file;
  mesh.scheme = scheme;
  int64_t expectedVertices = -1, expectedFaces = -1, triangles = -1;
  if (ext == ".ply") {
    const PlyInfo ply = checkPly(bytes, file);
    expectedVertices = ply.vertices;
    expectedFaces = ply.faces;
    if (ply.trailing > 0)
      mesh.notes.push_back(std::to_string(ply.trailing) + (ply.ascii ? " line(s)" : " byte(s)") +
                           " after the last PLY element were ignored");
  } else if (ext == ".stl") {
    triangles = checkStl(bytes, file).triangles;
  } else {
    fail(file, 0, "OpenMesh is not used for " + quote(ext) + " files");
  }

  FaceListImporter importer(mesh);
  OM::IO::Options options;
  bool ok = false;
  std::string messages;
  {
    static std::mutex omerrMutex;  // omerr() and the IOManager are process-global
    std::lock_guard lock(omerrMutex);
    CapturedOmErr captured;
    ok = OM::IO::IOManager().read(file, importer, options);
    messages = captured.text();
  }
  if (!ok)
    fail(file, 0,
         "OpenMesh could not read the file" + (messages.empty() ? std::string() : ": " + messages));
  if (!messages.empty()) mesh.notes.push_back("OpenMesh reported: " + messages);

  if (expectedVertices >= 0 &&
      (mesh.vertexCount() != expectedVertices || mesh.faceCount() != expectedFaces))
    fail(file, 0,
         "read " + std::to_string(mesh.vertexCount()) + " of " + std::to_string(expectedVertices) +
             " vertices and " + std::to_string(mesh.faceCount()) + " of " +
             std::to_string(expectedFaces) +
             " faces the header declares (truncated or malformed file)");
  if (triangles >= 0 && mesh.faceCount() < triangles)
    mesh.notes.push_back(
        std::to_string(triangles - mesh.faceCount()) +
        " STL triangle(s) collapsed when OpenMesh merged equal corner points, and were dropped");
  if (mesh.positions.empty()) fail(file, 0, "no vertices: the mesh is empty");
  if (mesh.faceSizes.empty()) fail(file, 0, "no faces: the mesh is empty");
  size_t offset = 0;
  for (int f = 0; f < mesh.faceCount(); ++f) {
    const int n = mesh.faceSizes[static_cast<size_t>(f)];
    if (n < 3)
      fail(file, 0,
           "face " + std::to_string(f) + " has " + std::to_string(n) +
               " vertices; a face needs at least 3");
    if (scheme == Scheme::Loop && n != 3)
      fail(file, 0,
           "face " + std::to_string(f) + " has " + std::to_string(n) +
               " vertices, but the Loop scheme needs triangles");
    for (int k = 0; k < n; ++k) {
      const int v = mesh.faceVertices[offset + static_cast<size_t>(k)];
      if (v < 0 || v >= mesh.vertexCount())
        fail(file, 0,
             "face " + std::to_string(f) + " uses vertex index " + std::to_string(v) +
                 ", out of range [0, " + std::to_string(mesh.vertexCount()) + ")");
    }
    offset += static_cast<size_t>(n);
  }
  return mesh;
}

#else

bool haveOpenMesh() { return false; }

CageMesh readWithOpenMesh(const std::filesystem::path& path, std::string_view, Scheme) {
  fail(path.string(), 0,
       "reading this format needs OpenMesh, which this build was configured without");
}

#endif

}  // namespace osd_cull::adapters::detail
