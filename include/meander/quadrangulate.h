// Turning a polygon mesh into the quad mesh that Taubin's construction needs
// (paper Section 3, "Quadrangulation").
#pragma once

#include "meander/connectivity.h"
#include "meander/default_init.h"
#include "meander/mesh.h"

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace meander {

// A quad mesh with side adjacency. Quad q has corners quads[q] (vertex indices into
// positions), in the orientation of the surface it came from. Side k of a quad joins
// corners k and k+1 (mod 4); neighbors[q][k] = 4*q' + k' says that side k of q is side k'
// of quad q' (-1: no quad there).
//
// A half quad has quads[q][1] == -1: it stands for the single triangle (c2, c3, c0) that
// a boundary edge of the input makes. Its diagonal c0-c2 lies on the boundary and never
// flips; its sides 0 and 1 do not exist (neighbors -1).
struct QuadMesh {
  std::vector<Vec3> positions;
  UninitVector<std::array<int32_t, 4>> quads;
  UninitVector<std::array<int32_t, 4>> neighbors;
  // Set by dual_simplest: corners 1 and 3 are face points, vertex face_point_offset + f
  // standing for face f. With every quad split along corners 0-2, the triangle with apex
  // 1 or 3 then lies on the loop around that face, which spares the cycle a labelling
  // walk over every triangle. -1 when the quads have no such structure.
  int32_t face_point_offset = -1;
  int32_t num_quads() const { return int32_t(quads.size()); }
  bool is_half(int32_t q) const { return quads[size_t(q)][1] < 0; }
};

// Dual of Simplest subdivision: one quad per edge e = (v1, v2) of the input with corners
// (v1, f2, v2, f1), where f1, f2 are the faces on either side and face points sit at
// triangles' incentres and other faces' centroids (so that a needle's triangles are not
// flat). Vertices: the input's vertices first, then one face point per face.
// A boundary edge gives a half quad (v1, -, v2, f1). Works for any manifold-edge mesh:
// any genus, boundaries, non-orientable. O(corners).
// Throws TopologyError if an edge is shared by more than two faces (repair first).
QuadMesh dual_simplest(const PolygonMesh& mesh, const Connectivity& connectivity);

// The same, consuming the mesh and its connectivity (both left empty) so that their
// memory is released as the quads are built: the pipeline's peak on large meshes.
QuadMesh dual_simplest(PolygonMesh&& mesh, Connectivity&& connectivity);

// Catmull-Clark topology (one refinement step, without moving anything): per face
// corner a quad (vertex, edge midpoint, face centroid, edge midpoint). Vertices: input
// vertices, then one per edge, then one per face. The result is 2-colourable ({vertex,
// face} points vs edge points). Throws TopologyError on a non-manifold edge.
QuadMesh catmull_clark_quads(const PolygonMesh& mesh, const Connectivity& connectivity);

// An all-quad input used as it is. Throws TopologyError naming the first face that is
// not a quad, or an edge shared by more than two faces.
QuadMesh quads_as_is(const PolygonMesh& mesh, const Connectivity& connectivity);

// The number of quad sides with no neighbour among full quads' sides (boundary edges of
// a quad mesh made by catmull_clark_quads or quads_as_is). Half-quad sides 0 and 1 do
// not count: they do not exist.
int32_t count_open_sides(const QuadMesh& quads);

enum class Quadrangulation { dual_simplest, catmull_clark, none };

// Parses "dual-simplest" | "catmull-clark" | "none"; throws UsageError otherwise.
Quadrangulation parse_quadrangulation(std::string_view name);

} // namespace meander
