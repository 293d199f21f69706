// Inspecting a polygon mesh for problems, and repairing what can be repaired without
// changing the surface.
#pragma once

#include "meander/mesh.h"

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace meander {

// One edge-connected component of the mesh (faces joined across shared edges).
struct ComponentReport {
  int32_t faces = 0;
  int32_t vertices = 0;
  int32_t edges = 0;
  int32_t boundary_loops = 0;
  int64_t euler_characteristic = 0; // V - E + F of the component
  bool manifold = true;             // no non-manifold edge or vertex in it
  bool orientable = true;
  // For a manifold component: orientable genus g from chi = 2 - 2g - b, or, if not
  // orientable, the number of cross-caps k from chi = 2 - k - b. -1 if non-manifold.
  int32_t genus = -1;
};

// Everything `meander info` prints. Counts are of the mesh as given (before repair).
struct MeshReport {
  int32_t vertices = 0;
  int32_t faces = 0;
  std::map<int32_t, int32_t> faces_by_size; // face size -> number of faces
  int32_t edges = 0;
  int32_t boundary_edges = 0;
  int32_t boundary_loops = 0;
  int32_t non_manifold_edges = 0;    // shared by more than two faces
  int32_t non_manifold_vertices = 0; // incident faces form more than one fan
  int32_t degenerate_faces = 0;      // a vertex repeated, fewer than 3 distinct vertices
  int32_t zero_area_faces = 0;       // distinct vertices but zero area (kept by repair)
  int32_t duplicate_faces = 0;       // same vertex set as an earlier face (extra copies counted)
  int32_t unreferenced_vertices = 0;
  int32_t non_finite_positions = 0;  // NaN or infinite coordinates
  int32_t out_of_range_indices = 0;
  int32_t misoriented_edges = 0;     // interior manifold edges crossed the same way by both faces
  bool orientable = true;
  Box3 bounding_box;                 // of the referenced vertices
  std::vector<ComponentReport> components;
};

// Inspects the mesh; never throws on a bad mesh (that is what it reports). O(n).
MeshReport inspect(const PolygonMesh& mesh);

struct RepairOptions {
  // Refuse (throw TopologyError) at the first problem instead of repairing it.
  bool strict = false;
};

struct RepairResult {
  PolygonMesh mesh;
  // One line per repair made, e.g. "split 1 non-manifold vertex (vertex 12 into 2 copies)".
  std::vector<std::string> repairs;
};

// Makes a mesh that the quadrangulation and the cycle accept: every index in range,
// every position finite, every face with >= 3 distinct vertices, every edge shared by at
// most two faces, every vertex a single fan, faces consistently oriented where the
// component is orientable, no duplicate faces, no unreferenced vertices. Repairs, in
// order: collapse repeated consecutive indices and drop faces left with < 3 distinct
// vertices; drop duplicate faces; cut non-manifold edges (each face keeps its own copy)
// and split non-manifold vertices into one copy per fan; re-orient each orientable
// component to its majority orientation; drop unreferenced vertices. Zero-area faces are
// kept (dropping them would cut the surface). Out-of-range indices and non-finite
// positions cannot be repaired: TopologyError (resp. InputError). With options.strict
// any problem throws TopologyError. Messages start with `name` ("conrod.stl: edge
// (17,42) is shared by 3 faces: mesh is not manifold"). O(n) time.
RepairResult repair(const PolygonMesh& mesh, std::string_view name, const RepairOptions& options = {});

} // namespace meander
