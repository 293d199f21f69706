// Inspecting a polygon mesh for problems, and repairing what can be repaired without
// changing the surface.
#pragma once

#include "meander/connectivity.h"
#include "meander/mesh.h"

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace meander {

// One edge-connected component of the mesh: faces joined across shared edges, non-manifold
// edges included (a sheet glued to another along an edge is part of it), a lone shared
// vertex not (two cubes touching at a corner are two components, as repair will leave them).
struct ComponentReport {
  int32_t faces = 0;
  int32_t vertices = 0;             // used by its faces; a vertex shared by components counts in each
  int32_t edges = 0;
  int32_t boundary_loops = 0;
  int64_t euler_characteristic = 0; // V - E + F of the component
  bool manifold = true;             // no non-manifold edge, and no non-manifold vertex on its faces
  // Its faces can be oriented to agree across every manifold edge of it.
  bool orientable = true;
  int32_t misoriented_edges = 0;    // as MeshReport::misoriented_edges, in this component
  // For a manifold component: orientable genus g from chi = 2 - 2g - b, or, if not
  // orientable, the number of cross-caps k from chi = 2 - k - b. -1 if non-manifold.
  int32_t genus = -1;
};

// Everything `meander info` prints. Counts are of the mesh as given (before repair).
// Element counts (faces by size, degenerate, zero-area, unreferenced, non-finite,
// out-of-range) look at every face and vertex. The topology (edges, boundary, non-manifold
// elements, duplicates, orientation, components) is that of the faces as repair step 2
// leaves them: faces with an index out of range left out, repeated consecutive vertices
// collapsed, faces left with fewer than 3 distinct vertices left out.
struct MeshReport {
  int32_t vertices = 0;
  int32_t faces = 0;
  std::map<int32_t, int32_t> faces_by_size; // face size -> number of faces
  int32_t edges = 0;
  int32_t boundary_edges = 0;
  // Closed chains of boundary edges. At a vertex the two boundary edges that end the same
  // fan of faces are chained, so loops touching at a vertex stay apart. Where fans end at
  // a non-manifold edge instead, the boundary edges ending them at that vertex are chained
  // together (a walk along the boundary passes from one to the next). Exact on manifold
  // meshes; on others it is one reasonable count among several.
  int32_t boundary_loops = 0;
  int32_t non_manifold_edges = 0;    // shared by more than two faces
  // Its faces form more than one fan (faces joined across the manifold edges through it);
  // both ends of a non-manifold edge are such vertices.
  int32_t non_manifold_vertices = 0;
  int32_t degenerate_faces = 0;      // a vertex repeated, or fewer than 3 vertices
  // Distinct vertices but a vector area below 1e-12 of the squared bounding-box diagonal:
  // zero as far as float coordinates can tell (kept by repair).
  int32_t zero_area_faces = 0;
  // The same cycle of vertices as an earlier face, up to rotation and orientation
  // (extra copies counted).
  int32_t duplicate_faces = 0;
  int32_t unreferenced_vertices = 0;
  int32_t non_finite_positions = 0;  // vertices with a NaN or infinite coordinate
  int32_t out_of_range_indices = 0;  // face indices < 0 or >= vertices
  int32_t misoriented_edges = 0;     // manifold edges crossed the same way by both faces
  bool orientable = true;            // every component is
  Box3 bounding_box;                 // of the referenced vertices with finite positions
  std::vector<ComponentReport> components; // numbered by their first face
  // Per input face: its index in `components`, or -1 for a face left out of the topology
  // (an index out of range, or fewer than 3 distinct vertices once repeated consecutive
  // ones are collapsed). Lets a caller sum over components without building the
  // connectivity again (check_printability's volumes).
  std::vector<int32_t> face_components;
};

// Inspects the mesh; never throws on a bad mesh (that is what it reports), whatever its
// indices and positions hold, provided face_start is well formed (starts at 0, never
// decreases, ends at face_vertices.size()), as PolygonMesh requires. O(n).
MeshReport inspect(const PolygonMesh& mesh);

struct RepairOptions {
  // Refuse (throw TopologyError) at the first problem instead of repairing it.
  bool strict = false;
  // Refuse (throw InputError) a mesh of more faces than this before any work, so that a
  // server bounds what one request may cost; 0: no limit.
  int64_t max_faces = 0;
  // Let the result's vertices and faces come in another order when the mesh is large and
  // scattered in memory (locality.h), since every later stage follows its adjacency.
  // Messages still name the input's elements: a mesh that needs a repair or gets a
  // notice is repaired in its own order, and only its result reordered. For callers
  // whose output and later messages never refer to the input's numbering.
  bool reorder = false;
};

struct RepairResult {
  PolygonMesh mesh;
  // One line per repair made, with counts and an example, e.g. "split 6 non-manifold
  // vertices into 13 copies (vertex 12 had 2 fans)". Empty when the mesh needed nothing,
  // and then `mesh` is the input unchanged.
  std::vector<std::string> repairs;
  // What is worth telling but needs no repair, e.g. "component 0 is not orientable
  // (Möbius-like); faces left as they are".
  std::vector<std::string> notices;
  // Whether `mesh` is the input in the order RepairOptions::reorder allows.
  bool reordered = false;
  // The edge connectivity of `mesh` when repair still holds a valid one (always, unless
  // it re-oriented faces), so the pipeline need not build it again; empty otherwise.
  Connectivity connectivity;
};

// Makes a mesh that the quadrangulation and the cycle accept: every index in range,
// every position finite, every face with >= 3 distinct vertices, every edge shared by at
// most two faces, every vertex a single fan, faces consistently oriented where the
// component is orientable, no duplicate faces, no unreferenced vertices. Repairs, in
// order:
//  1. refuse an index out of range (TopologyError) or a non-finite position used by a
//     face (InputError);
//  2. collapse repeated consecutive indices (cyclically) and drop faces left with < 3
//     vertices or still repeating one;
//  3. drop duplicate faces (same cycle of vertices up to rotation and orientation), keeping
//     the first;
//  4. cut non-manifold edges and split non-manifold vertices: each fan of faces around a
//     vertex (faces joined across its manifold edges) gets its own copy of the vertex, the
//     first fan keeping the original index, copies appended. The faces on a non-manifold
//     edge then no longer share it (except two whose ends lie in one fan at both vertices);
//  5. flip the faces of each orientable component that disagree with the majority (on a
//     tie the component's first face keeps its orientation); a non-orientable component
//     is left as it is, with a notice;
//  6. drop unreferenced vertices, keeping the order of the others.
// Face order is kept. Zero-area faces are kept (dropping them would cut the surface).
// With options.strict the first problem throws TopologyError instead of being repaired
// (non-orientability is no problem: the cycle handles Möbius bands). Messages start with
// `name` and use 0-based indices of the input: "conrod.stl: edge (17,42) is shared by 3
// faces: mesh is not manifold", "x.obj: vertex 11 joins 2 separate fans of faces: mesh is
// not manifold", "x.obj: faces 3 and 9 disagree in orientation across edge (4,5)",
// "x.obj: face 3 repeats vertex 7", "x.obj: face 9 duplicates face 3", "x.obj: 1113
// vertices are not used by any face (first: 35001)". No face left: TopologyError.
// O(n) time: on a mesh that needs nothing, one connectivity build and a few passes.
RepairResult repair(const PolygonMesh& mesh, std::string_view name, const RepairOptions& options = {});

// The same, taking the mesh over: a mesh that needs nothing is moved, not copied, into the
// result.
RepairResult repair(PolygonMesh&& mesh, std::string_view name, const RepairOptions& options = {});

} // namespace meander
