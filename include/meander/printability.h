// Will it print? A report on any polygon mesh as a 3D printer sees it: a closed,
// consistently oriented 2-manifold that encloses positive volume, does not cross itself
// and is nowhere thinner than the printer can make (issue 4, "Printability").
//
// Polygons are fanned from their first vertex into triangles, as the STL and 3MF writers
// do; face numbers in the report are those of the input polygons.
#pragma once

#include "meander/mesh.h"
#include "meander/progress.h"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace meander {

struct PrintabilityOptions {
  // Search for self-intersections: Embree's collision query (rtcCollide) over the
  // triangles' boxes and a triangle-triangle test per overlapping pair made of
  // orientation signs only, computed in double (exact for float inputs on a coarse
  // lattice, such as axis-aligned and touching configurations; otherwise wrong only
  // within ~1e-16 relative of a tie).
  bool self_intersections = true;
  // The caller has searched this very mesh with self_intersecting_faces() and found
  // nothing (VariableWire::clear): reported as checked and clear without a second search.
  bool known_clear = false;
  // Estimate the minimum thickness by casting a ray from every vertex inward (closed
  // meshes only: an open sheet has no inside). Embree finds the nearest triangle hit, in
  // float (relative error ~1e-7).
  bool thickness = true;
  // The thinnest wall the printer can make, in mesh units (about twice the nozzle width
  // for a filament printer, a few tenths of a millimetre for resin): a mesh thinner
  // anywhere is not printable. 0: thickness is reported, not judged.
  double required_thickness = 0;
  // > 0 (with thickness): also measure the narrowest gap between parts of the mesh (a
  // ray outward from each vertex, as the thickness's inward) and the smallest size at
  // which the mesh, scaled, is 2 nozzles thick and its parts a nozzle apart, in the
  // nozzle's units (millimetres).
  double nozzle = 0;
  // The narrowest gap the printer keeps open, in mesh units (a nozzle width): parts of
  // the mesh nearer anywhere make it not printable. 0: the gap is not judged.
  double required_gap = 0;
  // Per vertex (empty: none), 1 where no thickness or gap is measured: beside the crease
  // where a bridge meets a wire, whose V a vertex's ray takes for a gap of almost nothing
  // (a printer fills it).
  std::span<const uint8_t> unmeasured;
};

// One edge-connected component, as inspect() numbers them (by their first face).
struct SolidComponent {
  int32_t faces = 0;
  int64_t euler_characteristic = 0; // V - E + F: 2 for a sphere, 0 for a torus (each wire cycle)
  int32_t genus = -1;               // as ComponentReport::genus (-1: non-manifold)
  bool closed = false;              // no boundary edge
  // Signed volume of its triangles by the divergence theorem: positive when the faces
  // wind counter-clockwise seen from outside (normals point out). Meaningful when closed.
  double volume = 0;
};

struct PrintabilityReport {
  int32_t vertices = 0;
  int32_t faces = 0;
  int64_t triangles = 0;            // after fanning
  // Zero area: left out of the intersection search (CGAL's does_self_intersect reports
  // each as intersecting itself; here they are counted apart).
  int32_t degenerate_triangles = 0;
  // Topology, from inspect() (see check.h for the exact definitions).
  int32_t boundary_edges = 0;
  int32_t non_manifold_edges = 0;
  int32_t non_manifold_vertices = 0;
  int32_t misoriented_edges = 0; // manifold edges whose two faces disagree in orientation
  bool orientable = true;
  // Every edge shared by exactly two faces that cross it in opposite directions, and
  // every vertex a single fan of faces: a closed, consistently oriented 2-manifold.
  bool watertight = false;
  std::vector<SolidComponent> components;
  double volume = 0; // sum over the components
  Box3 bounding_box;

  // Self-intersection: two triangles meet where the mesh does not join them. Triangles
  // sharing an edge count only when they fold onto each other (coplanar, on the same
  // side of the edge); triangles sharing a vertex only when they meet elsewhere too;
  // triangles of one polygon never. Touching counts for all others.
  bool self_intersections_checked = false;
  bool self_intersecting = false;
  // The first intersecting pair of input faces: the smallest triangle with an
  // intersecting partner after it, and its smallest such partner. {-1, -1} if none.
  std::array<int32_t, 2> first_intersection{-1, -1};

  // Minimum thickness: from each vertex, the distance along the inward (angle-weighted)
  // vertex normal to the first surface hit, faces around the vertex left out; the least
  // over all vertices. On a round wire of radius r it is about 2r; it is an estimate from
  // the vertices only, so thin spots between vertices are missed. Infinite when nothing
  // was hit or not computed.
  bool thickness_checked = false;
  double min_thickness = INFINITY;
  int32_t thinnest_vertex = -1;
  double required_thickness = 0; // PrintabilityOptions::required_thickness

  // With PrintabilityOptions::nozzle: the distance from each vertex along its outward
  // normal to the first surface hit, the least over all vertices (infinite when nothing
  // was hit), and the smallest largest side of the bounding box at which the mesh would
  // be 2 nozzles thick and its parts a nozzle apart.
  bool gaps_checked = false;
  double min_gap = INFINITY;
  int32_t narrowest_vertex = -1;
  double required_gap = 0; // PrintabilityOptions::required_gap
  double nozzle = 0;
  double smallest_size = INFINITY;

  // A required thickness was given and the mesh is thinner somewhere, or its thickness
  // could not be measured (an open mesh).
  bool too_thin() const;
  // A required gap was given and parts of the mesh come nearer somewhere, or the gap
  // was not measured.
  bool too_close() const;
  // Watertight, positive volume in every component, no self-intersection found, and not
  // too thin or too close.
  bool printable() const;
};

// Checks the mesh. Throws InputError if a face index is out of range or a vertex used by
// a face has a non-finite position (readers never return such meshes). Deterministic
// whatever the number of threads. O(n log n) time and O(n) memory for n triangles of
// bounded overlap; the pair search and the rays run in parallel (oneTBB, Embree); its
// time is mostly in touching fresh memory (docs/wires.md, "Printability report").
// `progress`, if given, may cancel it (Cancelled) and has the fraction of the
// self-intersection search.
PrintabilityReport check_printability(const PolygonMesh& mesh, const PrintabilityOptions& options = {},
                                      Progress* progress = nullptr);

// Every face that meets another where the mesh does not join them (the
// self-intersections check_printability looks for; zero-area triangles left out),
// sorted. With `among` (a flag per face), only the pairs with at least one flagged face
// are tested: after a local change, what may have changed. O(n log n). `progress`, if
// given, may cancel the search of the whole mesh block by block (Cancelled).
std::vector<int32_t> self_intersecting_faces(const PolygonMesh& mesh, std::span<const uint8_t> among = {},
                                             Progress* progress = nullptr);

// The report as a JSON object (2-space indented, keys in a fixed order; infinite or
// unchecked figures are null): triangles, watertight, volume, min_thickness,
// self_intersecting, bounding_box, components, ...
std::string printability_json(const PrintabilityReport& report);

// One paragraph for people (no trailing newline), e.g. "12000 triangles, watertight,
// 1 component (Euler characteristic 0), volume 0.42 (outward), no self-intersection,
// minimum thickness 0.061 (at vertex 17), bounding box 2.1 x 2.1 x 0.7 from (-1.05,
// -1.05, -0.35): printable."
std::string printability_summary(const PrintabilityReport& report);

} // namespace meander
