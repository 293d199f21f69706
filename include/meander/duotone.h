// Duotone surfaces (paper Section 5): a surface painted in two colours whose regions are
// each connected and meet along one closed curve per connected component.
//
// A 2-colourable quad mesh (Catmull-Clark topology or dual of Simplest: every quad side
// joins a colour-0 vertex, "yellow", to a colour-1 vertex, "blue") gets one diagonal per
// quad; the yellow diagonals form the yellow graph, the blue ones the blue graph. A
// Truchet tile on each quad paints a quarter disc around each corner its diagonal does
// not join and a band along the diagonal, so the yellow region is a thickening of the
// yellow graph and the blue region one of the blue graph. Both are connected exactly
// when the triangles of the triangulation form one loop per component, and that loop is
// the separating curve.
//
// Boundaries: a boundary of a Catmull-Clark or as-is quad mesh alternates colours (its
// sides join a yellow and a blue vertex), so the curve would cross it at every side and
// two connected regions are impossible (on a disc, a connected yellow set touching the
// boundary at two places cuts the blue set in two). Dual of Simplest makes every
// boundary edge the yellow diagonal of a half quad: boundaries lie inside the yellow
// region, which then has one hole per boundary loop, and the curve stays closed. So
// catmull-clark falls back to dual-simplest on a mesh with boundary (with a note) and
// `none` refuses one. docs/duotone.md says what is guaranteed.
#pragma once

#include "meander/hamiltonian.h"
#include "meander/quadrangulate.h"
#include "meander/spanning_tree.h"
#include "meander/textured_mesh.h"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace meander {

enum class DuotoneRule {
  // The reviewer's rule (Section 5.3): a spanning tree of the yellow-diagonal graph is
  // the yellow graph, every other quad takes its blue diagonal. Yellow is a tree (on a
  // mesh with boundary: a tree once each boundary loop is contracted to a point), blue
  // is connected, on any surface.
  tree,
  // The paper's own procedure: random diagonals, then flips of quads whose two
  // triangles lie on different loops until one loop per component is left (Taubin's
  // construction). Neither graph need be a tree on a surface of positive genus.
  flip,
};

// Parses "tree" | "flip"; throws UsageError otherwise.
DuotoneRule parse_duotone_rule(std::string_view name);

struct DuotoneOptions {
  Quadrangulation quadrangulation = Quadrangulation::catmull_clark;
  DuotoneRule rule = DuotoneRule::tree;
  TreeStrategy tree = TreeStrategy::random; // which spanning tree (tree rule) or flip forest (flip rule)
  uint64_t seed = 1;
};

struct Duotone {
  QuadMesh quads;
  // Per vertex of `quads`: 0 yellow (the first colour), 1 blue. Every quad side joins
  // the two colours; corner 0 of the first quad of each component is yellow.
  std::vector<uint8_t> color;
  // cycle.diagonal is the choice per quad (0: corners 0-2, 1: corners 1-3), and its
  // loops, one per connected component, are the separating curves as triangle strips.
  TriangleCycle cycle;
  Quadrangulation quadrangulation = Quadrangulation::catmull_clark; // the one used
  std::vector<std::string> notes; // e.g. the fallback to dual-simplest on a boundary
};

// The colour (0 or 1) of quad q's diagonal: that of the two corners it joins.
inline int duotone_diagonal_color(const Duotone& d, int32_t q) {
  return d.color[size_t(d.quads.quads[size_t(q)][size_t(d.cycle.diagonal[size_t(q)])])];
}

// Builds the duotone of a mesh that repair() accepted (manifold edges), with its edge
// connectivity (RepairResult::connectivity; an empty or mismatched one is rebuilt, as in
// make_curve). Works on any genus, orientable or not, with several components; with
// boundary as the header comment says. O(corners) plus the spanning forest.
// Throws TopologyError for `none` on a mesh that is not all quads, has boundary, or
// whose vertices cannot be 2-coloured (naming a quad on an odd cycle), and what the
// quadrangulations throw.
Duotone make_duotone(const PolygonMesh& mesh, const Connectivity& connectivity, const DuotoneOptions& options = {});

// ---- Tiles, texture and outputs -------------------------------------------------------

// Tile designs with the Truchet topology: each one paints the corners the diagonal does
// not join in their own colour up to a curve from the midpoint of one side to the
// midpoint of the next, and the rest in the diagonal's colour (paper Figure 21).
enum class TileStyle {
  truchet,   // two quarter-disc arcs of radius half the edge
  outline,   // the Truchet arcs drawn as a dark band over the boundary
  triangles, // straight chords between side midpoints instead of arcs
  stripes,   // the Truchet regions in bands of two shades parallel to the boundary
  dots,      // Truchet tiles with a dot of a middle tone in the middle of each band: a dotted river
};

// Parses a style name; throws UsageError("unknown tile style 'x' (expected truchet,
// outline, triangles, stripes or dots)").
TileStyle parse_tile_style(std::string_view name);
std::string_view to_string(TileStyle style);

// An sRGB colour as image files store it.
using Color8 = std::array<uint8_t, 3>;

// "C1,C2": two colours, each a name (yellow, gold, blue, navy, red, ...) or #rrggbb.
// Throws UsageError naming the bad part and the accepted forms; the two must differ.
std::array<Color8, 2> parse_duotone_colors(std::string_view text);

struct TileOptions {
  TileStyle style = TileStyle::truchet;
  std::array<Color8, 2> colors{Color8{242, 190, 34}, Color8{28, 62, 128}}; // yellow, blue
  int32_t texture_size = 1024; // atlas width in pixels (height half of it), 64..8192
  friend bool operator==(const TileOptions&, const TileOptions&) = default;
};

// The texture atlas: two square tiles side by side, tile k with its corner regions in
// colour k and its band in the other colour, each with a gutter that repeats its border
// so that filtering does not bleed across tiles; 4x4 samples per texel. Throws
// UsageError for a size out of range. O(size^2).
Texture duotone_atlas(const TileOptions& options);

// The textured surface: the quads (half quads as triangles), each with the texture
// coordinates that put its tile on it, turned to match its diagonal and its corners'
// colours, one material with the atlas. O(quads) plus the atlas.
TexturedMesh duotone_surface(const Duotone& duotone, const TileOptions& options);

// The same with the atlas given: duotone_atlas(options) made before, which depends on
// the options alone (the studio keeps it from one update to the next, where drawing it
// took most of the time). O(quads).
TexturedMesh duotone_surface(const Duotone& duotone, const TileOptions& options, Texture atlas);

// The separating curves as closed polylines, one per loop (component), through the
// midpoints of the quad sides they cross, following each tile's curve (arcs of 8
// segments, or chords for `triangles`) on the surface as the texture maps it: exactly
// where the colour changes. O(quads).
Polylines separating_curves(const Duotone& duotone, TileStyle style);

// The two colour regions as triangle meshes cut exactly along separating_curves(): each
// tile piece split at the quad's corner 0-2 fold (where the writers fan it) and mapped
// onto the surface, vertices shared across pieces and quads. regions[k] has colour k.
// Their areas sum to the quad surface's area and their boundary edges are the curve's
// segments, plus the surface's own boundary edges, all yellow, each in two halves at its
// midpoint (where the fan of its half quad's band starts). O(quads).
std::array<PolygonMesh, 2> duotone_regions(const Duotone& duotone, TileStyle style);

// Where the faces and vertices of the regions come from: each face's quad, and each
// vertex's point of the quads (a corner: its index; a side's midpoint, a point inside a
// quad: numbers after those), the same number in both regions where they share a point.
struct RegionOrigins {
  std::array<std::vector<int32_t>, 2> face_quad;
  std::array<std::vector<int64_t>, 2> vertex_point;
};

// The same with the quads' corners at `at` (one place per vertex of duotone.quads): the
// same vertices and faces, each mapped from the quad halves either side of its corner
// 0-2 fold to the moved ones (the inside of a shell, shell.h), and with `origins`, where
// they come from. With `gaps` (5 per quad, in [0, 0.2]: at 5 * quad + side, the same for
// both quads on a side, then the inside's), the regions are drawn apart: on each side
// the cut's point moves that fraction of the side towards the corner of the region's
// colour (each region its own point), and inside each quad the curves move as far in
// between the sides' gaps, at least the inside's, scaled about their apex; the bands are
// then triangulated by ear clipping. Throws std::invalid_argument unless `at` has a
// place per vertex and `gaps`, if given, 5 per quad.
std::array<PolygonMesh, 2> duotone_regions(const Duotone& duotone, TileStyle style, std::span<const Vec3> at,
                                           RegionOrigins* origins = nullptr, std::span<const float> gaps = {});

// The gaps that draw the regions `clearance` apart on two copies of the quads (their
// corners at `outer` and at `inner`: a shell's outside and inside): on each side, the
// fraction of it that moves the cut's point so far that the curve leaving it (at its
// angle to the side) moves half the clearance, the largest of both copies and both
// quads on the side; inside each quad, the fraction of a unit step of its square that
// is at least half the clearance in every direction on either copy. Values over 0.2
// are returned as they are (too wide for the quad). Throws std::invalid_argument unless
// `outer` and `inner` have a place per vertex.
std::vector<float> duotone_gaps(const Duotone& duotone, TileStyle style, std::span<const Vec3> outer,
                                std::span<const Vec3> inner, double clearance);

} // namespace meander
