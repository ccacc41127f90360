#pragma once
/// \file procedural.h
/// \brief Control cages generated in code, so tests and the default demo need no files.
///
/// Every generator returns a valid CageMesh (see osd_cull::validate) whose faces are wound
/// counter-clockwise seen from outside (outward normals, as OpenSubdiv's shapes), with
/// source "built-in:<name>" where <name> is what builtInMesh() accepts.

#include "osd_cull/patch/cage_mesh.h"

#include <glm/vec3.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace osd_cull::scene {

/// \brief The cube [-1, 1]^3: 8 vertices of valence 3, 6 quads, 12 edges, closed.
CageMesh cube();

/// \brief A torus of `u` × `v` quads (u around the axis z, v around the tube), major
/// radius `majorRadius`, tube radius `minorRadius`: u·v vertices, all of valence 4, closed,
/// genus 1. Needs u, v >= 3 and 0 < minorRadius < majorRadius.
/// \throws osd_cull::Error for other arguments.
CageMesh torus(int u = 12, int v = 8, double majorRadius = 1.0, double minorRadius = 0.4);

/// \brief A closed sphere-like cage with two poles of valence `valence` (any n >= 3): each
/// pole is a fan of n triangles, and `rings` >= 1 rings of n vertices on the unit sphere are
/// joined by (rings - 1)·n quads. 2 + rings·n vertices, n·(2·rings + 1) edges; every vertex
/// but the poles has valence 4. Source "built-in:pole-sphere-<n>".
/// \throws osd_cull::Error for valence < 3 or rings < 1.
CageMesh poleSphere(int valence, int rings = 3);

/// \brief cube() with tags: the four edges of the top face (z = 1) creased with sharpness
/// 2, the vertical edge at x = y = 1 infinitely sharp (10), and a corner of sharpness 3 at
/// vertex 0 (-1, -1, -1).
CageMesh creasedCube();

/// \brief A closed, manifold cage with a face of zero area: cube() with the top face
/// collapsed to a segment (vertices 4 and 7, and 5 and 6, at the same positions). Topology
/// is that of the cube; the geometry has two zero-length edges and a zero-area face, the
/// degenerate case culling must survive.
CageMesh collapsedFaceCube();

/// \brief The default mesh of the demo and of `osd-cull info` without a file: a rounded,
/// lumpy box — a cube with each face split into 4 × 4 quads (96 quads, 98 vertices, 192
/// edges; the 8 cube corners are extraordinary, valence 3), pushed towards a sphere, with a
/// sharpness-2 crease loop of 16 edges around its middle. Closed, genus 0.
CageMesh defaultMesh();

/// \brief A standing figure for the skinning demo (built-in:character): legs, a torso, arms
/// held out at shoulder height and a head, made of 0.3 x 0.45 x 0.3 voxels (feet on z = 0,
/// 2.4 tall, 2.1 across the arms), whose boundary quads form a closed, outward-oriented,
/// genus-0 cage. Its longest axis is up and its arms lie along the second longest, as the
/// limb rig of the skinning deformer expects.
CageMesh character();

/// \brief Names builtInMesh() accepts: cube, torus, pole-sphere-<n> (n >= 3), creased-cube,
/// collapsed-face, default, character.
std::vector<std::string> builtInMeshNames();

/// \brief The generated mesh with this name (with or without the "built-in:" prefix), or
/// nullopt for an unknown name.
std::optional<CageMesh> builtInMesh(std::string_view name);

/// \brief Adds `offset` to every position.
void translate(CageMesh& mesh, const glm::dvec3& offset);

/// \brief Multiplies every position by `factors` per axis. When the factors mirror the mesh
/// (their product is negative) every face's winding is reversed (first vertex kept), so
/// faces keep facing outward.
void scale(CageMesh& mesh, const glm::dvec3& factors);

/// \brief Uniform scale().
inline void scale(CageMesh& mesh, double factor) { scale(mesh, glm::dvec3(factor)); }

}  // namespace osd_cull::scene
