#pragma once
/// \file cage_mesh.h
/// \brief A subdivision control cage with its tags, independent of any file format.
///
/// Adapters (adapters/) fill a CageMesh from files; makeTopologyRefiner() turns it into an
/// OpenSubdiv Far::TopologyRefiner with every sharpness, hole and boundary rule applied.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace osd_cull {

/// \brief Subdivision scheme (OpenSubdiv Sdc::SchemeType).
enum class Scheme { CatmullClark, Loop, Bilinear };

/// \brief How boundary vertices are interpolated (Sdc::Options::VtxBoundaryInterpolation).
enum class BoundaryInterpolation { None, EdgeOnly, EdgeAndCorner };

/// \brief Face-varying boundary interpolation (Sdc::Options::FVarLinearInterpolation).
enum class FVarInterpolation { None, CornersOnly, CornersPlus1, CornersPlus2, Boundaries, All };

/// \brief Creasing method (Sdc::Options::CreasingMethod).
enum class CreasingMethod { Uniform, Chaikin };

/// \brief Triangle subdivision weights for Catmull-Clark (Sdc::Options::TriangleSubdivision).
enum class TriangleSubdivision { Catmark, Smooth };

std::string_view toString(Scheme scheme);
/// \brief Parses "catmark", "catmull-clark", "loop", "bilinear" (case-sensitive).
std::optional<Scheme> schemeFromString(std::string_view text);
/// \brief The scheme named by a file name prefix (catmark_, loop_, bilinear_), if any.
std::optional<Scheme> schemeFromFileName(std::string_view path);

/// \brief A sharp edge between two cage vertices (0-based).
struct CreaseEdge {
  int v0 = 0;
  int v1 = 0;
  float sharpness = 0.0f;
};

/// \brief A sharp vertex (0-based).
struct CornerVertex {
  int vertex = 0;
  float sharpness = 0.0f;
};

/// \brief A control cage. Indices are 0-based and, once produced by an adapter, valid.
struct CageMesh {
  std::string source;  ///< file name, or "built-in:<name>" for generated meshes
  Scheme scheme = Scheme::CatmullClark;
  BoundaryInterpolation boundary = BoundaryInterpolation::EdgeOnly;
  FVarInterpolation fvarBoundary = FVarInterpolation::All;
  CreasingMethod creasing = CreasingMethod::Uniform;
  TriangleSubdivision triangles = TriangleSubdivision::Catmark;

  std::vector<glm::dvec3> positions;
  std::vector<int> faceSizes;     ///< vertices per face
  std::vector<int> faceVertices;  ///< concatenated vertex indices of all faces
  std::vector<CreaseEdge> creases;
  std::vector<CornerVertex> corners;
  std::vector<int> holes;  ///< face indices tagged as holes
  /// Texture coordinates (OBJ `vt`), the face-varying channel of the cage; empty when the
  /// mesh has none. faceUVs has one index into uvs per entry of faceVertices.
  std::vector<glm::dvec2> uvs;
  std::vector<int> faceUVs;

  /// Notes the loader made while reading (e.g. "face 12 repeats vertex 5"); not errors.
  std::vector<std::string> notes;

  int vertexCount() const { return static_cast<int>(positions.size()); }
  int faceCount() const { return static_cast<int>(faceSizes.size()); }
  bool hasUVs() const { return !faceUVs.empty(); }
};

/// \brief Checks the cage and throws osd_cull::Error naming the first problem: no faces,
/// a face with fewer than three vertices, an index out of range, a NaN or Inf coordinate,
/// a negative or NaN sharpness, a hole index out of range, texture coordinates that are
/// non-finite, out of range or not one per face corner.
void validate(const CageMesh& mesh);

}  // namespace osd_cull
