#include "meander/duotone.h"

#include "meander/error.h"
#include "core/random.h"
#include "core/union_find.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace meander {

DuotoneRule parse_duotone_rule(std::string_view name) {
  if (name == "tree") return DuotoneRule::tree;
  if (name == "flip") return DuotoneRule::flip;
  throw UsageError("unknown duotone rule '" + std::string(name) + "' (expected tree or flip)");
}

namespace {

constexpr std::array<std::pair<std::string_view, TileStyle>, 5> kStyles{{{"truchet", TileStyle::truchet},
                                                                        {"outline", TileStyle::outline},
                                                                        {"triangles", TileStyle::triangles},
                                                                        {"stripes", TileStyle::stripes},
                                                                        {"dots", TileStyle::dots}}};

struct NamedColor {
  std::string_view name;
  Color8 color;
};
// A few names that read well on a surface; anything else as #rrggbb.
constexpr std::array<NamedColor, 16> kColorNames{{{"yellow", {242, 190, 34}},
                                                  {"gold", {214, 160, 22}},
                                                  {"blue", {28, 62, 128}},
                                                  {"navy", {20, 33, 72}},
                                                  {"sky", {92, 160, 214}},
                                                  {"red", {190, 40, 40}},
                                                  {"orange", {236, 122, 28}},
                                                  {"green", {46, 125, 50}},
                                                  {"teal", {0, 128, 120}},
                                                  {"purple", {106, 27, 154}},
                                                  {"pink", {228, 96, 150}},
                                                  {"brown", {109, 76, 65}},
                                                  {"cream", {244, 236, 214}},
                                                  {"white", {255, 255, 255}},
                                                  {"gray", {128, 128, 128}},
                                                  {"black", {17, 17, 17}}}};

Color8 parse_color(std::string_view text, std::string_view all) {
  for (const NamedColor& c : kColorNames)
    if (text == c.name) return c.color;
  auto hex = [](char ch) -> int {
    if (ch >= '0' && ch <= '9') return ch - '0';
    if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
    if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
    return -1;
  };
  if (text.size() == 7 && text[0] == '#') {
    Color8 c{};
    bool ok = true;
    for (int i = 0; i < 3; ++i) {
      const int hi = hex(text[size_t(1 + 2 * i)]), lo = hex(text[size_t(2 + 2 * i)]);
      ok = ok && hi >= 0 && lo >= 0;
      c[size_t(i)] = uint8_t(16 * hi + lo);
    }
    if (ok) return c;
  }
  std::string names;
  for (const NamedColor& c : kColorNames) names += (names.empty() ? "" : ", ") + std::string(c.name);
  throw ParameterError("colors", " '" + std::string(all) + "': '" + std::string(text) + "' is not a colour (expected #rrggbb or one of " +
                   names + ")");
}

// ---- The duotone itself -----------------------------------------------------------------

QuadMesh duotone_quads(const PolygonMesh& mesh, const Connectivity& c, Quadrangulation& used, std::vector<std::string>& notes) {
  if (used == Quadrangulation::catmull_clark) {
    int32_t boundary = 0;
    for (int32_t e = 0; e < c.num_edges(); ++e) boundary += c.edge_degree(e) == 1;
    if (boundary == 0) return catmull_clark_quads(mesh, c);
    notes.push_back("the mesh has " + std::to_string(boundary) +
                    " boundary edges: Catmull-Clark quads would alternate colours along them, so the duotone uses "
                    "dual-simplest quads, whose boundaries lie inside the first colour's region");
    used = Quadrangulation::dual_simplest;
  }
  if (used == Quadrangulation::dual_simplest) return dual_simplest(mesh, c);
  QuadMesh quads = quads_as_is(mesh, c);
  for (int32_t q = 0; q < quads.num_quads(); ++q)
    for (int k = 0; k < 4; ++k)
      if (quads.neighbors[size_t(q)][size_t(k)] < 0)
        throw TopologyError("face " + std::to_string(q) + " has a boundary edge (" +
                            std::to_string(quads.quads[size_t(q)][size_t(k)]) + ", " +
                            std::to_string(quads.quads[size_t(q)][size_t((k + 1) & 3)]) +
                            "): a boundary of quads alternates colours, so no duotone of it has two connected "
                            "regions; quad none needs a closed quad mesh (use quad dual-simplest)");
  return quads;
}

// Two colours such that every quad side joins both, spread across each component from
// corner 0 of its first quad. A half quad's corners 0 and 2 share a colour (they are the
// ends of its boundary diagonal).
std::vector<uint8_t> two_coloring(const QuadMesh& m) {
  constexpr uint8_t unset = 2;
  std::vector<uint8_t> color(m.positions.size(), unset);
  std::vector<uint8_t> seen(size_t(m.num_quads()), 0);
  std::vector<int32_t> stack;
  for (int32_t q0 = 0; q0 < m.num_quads(); ++q0) {
    if (seen[size_t(q0)]) continue;
    seen[size_t(q0)] = 1;
    if (color[size_t(m.quads[size_t(q0)][0])] == unset) color[size_t(m.quads[size_t(q0)][0])] = 0;
    stack.push_back(q0);
    while (!stack.empty()) {
      const int32_t q = stack.back();
      stack.pop_back();
      const auto& c = m.quads[size_t(q)];
      int known = -1;
      for (int k = 0; k < 4 && known < 0; ++k)
        if (c[size_t(k)] >= 0 && color[size_t(c[size_t(k)])] != unset) known = k;
      for (int k = 0; k < 4; ++k) {
        if (c[size_t(k)] < 0) continue;
        const uint8_t want = color[size_t(c[size_t(known)])] ^ uint8_t((k - known) & 1);
        uint8_t& have = color[size_t(c[size_t(k)])];
        if (have == unset) have = want;
        if (have != want)
          throw TopologyError("face " + std::to_string(q) + ": vertex " + std::to_string(c[size_t(k)]) +
                              " would need both colours (an odd cycle of edges runs through it): quad none needs "
                              "a quad mesh whose vertices are 2-colourable, as Catmull-Clark makes them (use quad "
                              "catmull-clark or dual-simplest)");
      }
      for (int32_t n : m.neighbors[size_t(q)])
        if (n >= 0 && !seen[size_t(n >> 2)]) {
          seen[size_t(n >> 2)] = 1;
          stack.push_back(n >> 2);
        }
    }
  }
  return color;
}

// The reviewer's rule. Half quads join the two ends of a boundary edge by a yellow
// diagonal that cannot change, so each boundary loop is a yellow cycle already: it is
// contracted to one node first, and the tree is taken in what remains. The yellow region
// with the boundary's neighbourhood is then a disc on the surface closed by capping each
// boundary loop, so its outline is one closed curve and the rest, blue, is connected.
std::vector<uint8_t> tree_diagonals(const QuadMesh& m, const std::vector<uint8_t>& color, const DuotoneOptions& options) {
  const int32_t nq = m.num_quads();
  UnionFind boundary(int32_t(m.positions.size()));
  for (int32_t q = 0; q < nq; ++q)
    if (m.is_half(q)) boundary.unite(m.quads[size_t(q)][0], m.quads[size_t(q)][2]);
  Graph yellow{.num_nodes = int32_t(m.positions.size()), .edges = {}};
  yellow.edges.reserve(size_t(nq));
  std::vector<int32_t> edge_quad;
  edge_quad.reserve(size_t(nq));
  std::vector<uint8_t> diagonal(size_t(nq), 0);
  for (int32_t q = 0; q < nq; ++q) {
    if (m.is_half(q)) continue;
    const auto& c = m.quads[size_t(q)];
    const int y = color[size_t(c[0])] == 0 ? 0 : 1; // the diagonal joining yellow corners
    diagonal[size_t(q)] = uint8_t(1 - y);
    yellow.edges.push_back({boundary.find(c[size_t(y)]), boundary.find(c[size_t(y + 2)])});
    edge_quad.push_back(q);
  }
  for (int32_t e : spanning_forest(yellow, options.tree, options.seed)) diagonal[size_t(edge_quad[size_t(e)])] ^= 1;
  return diagonal;
}

} // namespace

Duotone make_duotone(const PolygonMesh& mesh, const Connectivity& given, const DuotoneOptions& options) {
  const bool fits = given.halfedge_edge.size() == mesh.face_vertices.size() && !given.edge_start.empty();
  const Connectivity rebuilt = fits ? Connectivity() : build_connectivity(mesh);
  const Connectivity& connectivity = fits ? given : rebuilt;
  Duotone d;
  d.quadrangulation = options.quadrangulation;
  d.quads = duotone_quads(mesh, connectivity, d.quadrangulation, d.notes);
  d.color = two_coloring(d.quads);
  if (options.rule == DuotoneRule::tree) {
    d.cycle = triangle_loops(d.quads, tree_diagonals(d.quads, d.color, options));
  } else {
    // The paper's random initial triangulation; the seed also drives the flip forest, so
    // the two draws are decorrelated by a fixed offset.
    Random random(options.seed ^ 0x5deece66dULL);
    std::vector<uint8_t> initial(size_t(d.quads.num_quads()), 0);
    for (int32_t q = 0; q < d.quads.num_quads(); ++q)
      if (!d.quads.is_half(q)) initial[size_t(q)] = uint8_t(random.next() >> 63);
    d.cycle = hamiltonian_cycle(d.quads, {.tree = options.tree, .seed = options.seed, .initial_diagonal = initial});
  }
  return d;
}

// ---- Tiles ------------------------------------------------------------------------------

TileStyle parse_tile_style(std::string_view name) {
  for (const auto& [n, style] : kStyles)
    if (n == name) return style;
  throw UsageError("unknown tile style '" + std::string(name) + "' (expected truchet, outline, triangles, stripes or dots)");
}

std::string_view to_string(TileStyle style) {
  for (const auto& [n, s] : kStyles)
    if (s == style) return n;
  return "?";
}

std::array<Color8, 2> parse_duotone_colors(std::string_view text) {
  const size_t comma = text.find(',');
  if (comma == std::string_view::npos || text.find(',', comma + 1) != std::string_view::npos)
    throw ParameterError("colors", " '" + std::string(text) + "': expected two colours C1,C2 (names or #rrggbb)");
  const std::array<Color8, 2> colors{parse_color(text.substr(0, comma), text), parse_color(text.substr(comma + 1), text)};
  if (colors[0] == colors[1])
    throw ParameterError("colors", " '" + std::string(text) + "': the two colours are the same; a duotone needs two");
  return colors;
}

namespace {

using Linear = std::array<float, 3>;

float to_linear(uint8_t c) {
  const float x = float(c) / 255.0f;
  return x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f);
}
uint8_t to_srgb(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  const float s = x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1 / 2.4f) - 0.055f;
  return uint8_t(std::lround(s * 255.0f));
}
Linear linear(Color8 c) { return {to_linear(c[0]), to_linear(c[1]), to_linear(c[2])}; }
Linear mix(Linear a, Linear b, float t) {
  return {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t};
}

// The colour of tile point (s, t) in 0..1^2 with its corner regions around (0,0) and
// (1,1) in colour `corner` and the band between in colour `band`. Every style keeps the
// distance to the nearer of those corners the only thing that varies along a tile's
// sides, so the patterns continue across tiles whatever the neighbour's diagonal.
Linear tile_color(TileStyle style, Linear corner, Linear band, double s, double t) {
  const double to_corner = std::min(std::hypot(s, t), std::hypot(1 - s, 1 - t));
  const bool in_corner = style == TileStyle::triangles ? (s + t < 0.5 || s + t > 1.5) : to_corner < 0.5;
  const Linear base = in_corner ? corner : band;
  switch (style) {
  case TileStyle::truchet:
  case TileStyle::triangles:
    return base;
  case TileStyle::outline: {
    const Linear ink = mix(mix(corner, band, 0.5f), Linear{0, 0, 0}, 0.85f);
    return std::abs(to_corner - 0.5) < 0.06 ? ink : base;
  }
  case TileStyle::stripes: {
    // Bands 0.1 wide parallel to the curve, the one along it in the plain colour.
    const int stripe = int(std::abs(to_corner - 0.5) / 0.1);
    return stripe % 2 == 1 ? mix(base, Linear{1, 1, 1}, 0.3f) : base;
  }
  case TileStyle::dots:
    // Small enough to leave the band wide on both sides, in a tone between the two
    // colours so that it reads on either.
    return !in_corner && std::hypot(s - 0.5, t - 0.5) < 0.08 ? mix(band, corner, 0.5f) : base;
  }
  return base;
}

struct AtlasLayout {
  int32_t tile = 0, gutter = 0;
  int32_t width() const { return 2 * tile; }
};
AtlasLayout atlas_layout(int32_t size) {
  if (size < 64 || size > 8192 || size % 2 != 0)
    throw ParameterError("texture_size", " " + std::to_string(size) + ": expected an even number of pixels in 64..8192");
  return {.tile = size / 2, .gutter = std::max(2, size / 64)};
}

// Tile point (s, t) of tile k as a texture coordinate.
TexCoord atlas_uv(const AtlasLayout& a, int k, double s, double t) {
  const double inner = a.tile - 2 * a.gutter;
  return {float((k * a.tile + a.gutter + s * inner) / a.width()), float((a.gutter + t * inner) / a.tile)};
}

// ---- Geometry of the tiles on the surface -------------------------------------------------

// A point of the unit square that a quad's tile is drawn on.
struct LocalPoint {
  double s = 0, t = 0;
};

// Quad corner k sits at kCorner[k] of the unit square; the writers and the renderer fan a
// quad from corner 0, so the surface is affine on the triangles (0,1,2) (s >= t) and
// (0,2,3) (s <= t), and so are the texture coordinates. A half quad is the second one.
constexpr std::array<std::array<double, 2>, 4> kCorner{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};

// The interior points of the tile's curve around corner a of the unit square, from the
// midpoint of side a-1 (towards corner a-1) to that of side a (towards corner a+1): arcs
// of 8 segments, or one straight chord. Around corners 0 and 2 the middle point lies
// exactly on the fold s = t (equal offsets along both sides), so a piece is cut there at
// a point the curve has; a chord around corner 1 or 3 needs no interior point at all
// (one would be collinear with its ends and leave a triangle without area).
std::vector<LocalPoint> corner_curve(TileStyle style, int a) {
  const auto& p = kCorner[size_t(a)];
  const auto& prev = kCorner[size_t((a + 3) & 3)];
  const auto& next = kCorner[size_t((a + 1) & 3)];
  auto point = [&](double along_prev, double along_next) {
    return LocalPoint{p[0] + along_prev * (prev[0] - p[0]) + along_next * (next[0] - p[0]),
                      p[1] + along_prev * (prev[1] - p[1]) + along_next * (next[1] - p[1])};
  };
  if (style == TileStyle::triangles) {
    if (a % 2 == 1) return {};
    return {point(0.25, 0.25)};
  }
  constexpr int n = 8;
  std::array<double, n + 1> c{};
  for (int i = 0; i < n; ++i) c[size_t(i)] = 0.5 * std::cos(i * std::numbers::pi / (2 * n));
  std::vector<LocalPoint> out;
  for (int i = 1; i < n; ++i) out.push_back(point(c[size_t(i)], c[size_t(n - i)]));
  return out;
}

// Where the surface of quad q, its corners at `at`, is at square point (s, t): on its
// two halves either side of the corner 0-2 fold, each flat.
Vec3 surface_point(const QuadMesh& m, std::span<const Vec3> at, int32_t q, double s, double t) {
  const auto& c = m.quads[size_t(q)];
  auto p = [&](int k) {
    const Vec3 v = at[size_t(c[size_t(k)])];
    return std::array<double, 3>{v.x, v.y, v.z};
  };
  const auto p0 = p(0), p2 = p(2), p3 = p(3);
  std::array<double, 3> x{};
  if (s > t) {
    const auto p1 = p(1);
    for (int i = 0; i < 3; ++i) x[size_t(i)] = p0[size_t(i)] + s * (p1[size_t(i)] - p0[size_t(i)]) + t * (p2[size_t(i)] - p1[size_t(i)]);
  } else {
    for (int i = 0; i < 3; ++i) x[size_t(i)] = p0[size_t(i)] + s * (p2[size_t(i)] - p3[size_t(i)]) + t * (p3[size_t(i)] - p0[size_t(i)]);
  }
  return {float(x[0]), float(x[1]), float(x[2])};
}

Vec3 surface_point(const QuadMesh& m, int32_t q, double s, double t) { return surface_point(m, m.positions, q, s, t); }

// The midpoint of two points, the same float whichever comes first (the sum is exact
// in double and commutes), so that both quads on a side get the same point.
Vec3 midpoint(Vec3 a, Vec3 b) {
  return {float(0.5 * (double(a.x) + b.x)), float(0.5 * (double(a.y) + b.y)), float(0.5 * (double(a.z) + b.z))};
}

Vec3 side_midpoint(const QuadMesh& m, std::span<const Vec3> at, int32_t q, int k) {
  const auto& c = m.quads[size_t(q)];
  return midpoint(at[size_t(c[size_t(k)])], at[size_t(c[size_t((k + 1) & 3)])]);
}

// One name per quad side, shared by the two quads on it.
int32_t side_key(const QuadMesh& m, int32_t q, int k) {
  const int32_t n = m.neighbors[size_t(q)][size_t(k)];
  return n >= 0 ? std::min(4 * q + k, n) : 4 * q + k;
}

// The corners the diagonal does not join: where the tile's curves go round.
std::array<int, 2> apexes(const Duotone& d, int32_t q) {
  if (d.quads.is_half(q)) return {3, -1};
  return d.cycle.diagonal[size_t(q)] == 0 ? std::array<int, 2>{1, 3} : std::array<int, 2>{0, 2};
}

} // namespace

Texture duotone_atlas(const TileOptions& options) {
  const AtlasLayout a = atlas_layout(options.texture_size);
  const Linear c0 = linear(options.colors[0]), c1 = linear(options.colors[1]);
  Texture tex{.width = a.width(), .height = a.tile, .rgba = {}};
  tex.rgba.resize(size_t(tex.width) * size_t(tex.height) * 4);
  constexpr int kSamples = 4; // per texel and axis: anti-aliasing
  const double inner = a.tile - 2 * a.gutter;
  for (int32_t y = 0; y < tex.height; ++y)
    for (int32_t x = 0; x < tex.width; ++x) {
      const int k = x / a.tile;
      const Linear corner = k == 0 ? c0 : c1, band = k == 0 ? c1 : c0;
      Linear sum{0, 0, 0};
      for (int j = 0; j < kSamples; ++j)
        for (int i = 0; i < kSamples; ++i) {
          // Rows run top down, t up; the gutter repeats the tile's border.
          const double s = std::clamp((x - k * a.tile + (i + 0.5) / kSamples - a.gutter) / inner, 0.0, 1.0);
          const double t = std::clamp((a.tile - y - 1 + (j + 0.5) / kSamples - a.gutter) / inner, 0.0, 1.0);
          const Linear c = tile_color(options.style, corner, band, s, t);
          for (int ch = 0; ch < 3; ++ch) sum[size_t(ch)] += c[size_t(ch)];
        }
      uint8_t* px = &tex.rgba[(size_t(y) * size_t(tex.width) + size_t(x)) * 4];
      for (int ch = 0; ch < 3; ++ch) px[ch] = to_srgb(sum[size_t(ch)] / (kSamples * kSamples));
      px[3] = 255;
    }
  return tex;
}

TexturedMesh duotone_surface(const Duotone& d, const TileOptions& options) {
  return duotone_surface(d, options, duotone_atlas(options));
}

TexturedMesh duotone_surface(const Duotone& d, const TileOptions& options, Texture atlas) {
  const AtlasLayout layout = atlas_layout(options.texture_size);
  if (atlas.width != layout.width() || atlas.height != layout.tile)
    throw UsageError("duotone atlas of " + std::to_string(atlas.width) + "x" + std::to_string(atlas.height) +
                     " pixels for a texture size of " + std::to_string(options.texture_size));
  const QuadMesh& m = d.quads;
  TexturedMesh out;
  out.mesh.positions = m.positions;
  out.mesh.face_vertices.reserve(4 * size_t(m.num_quads()));
  out.mesh.face_start.reserve(size_t(m.num_quads()) + 1);
  out.appearance.texcoords.reserve(4 * size_t(m.num_quads()));
  for (int32_t q = 0; q < m.num_quads(); ++q) {
    const auto& c = m.quads[size_t(q)];
    // Corner `apex` takes the tile's corner (0,0), the others follow round the square,
    // and the tile is the one whose corner regions have the apex's colour.
    const int apex = apexes(d, q)[0];
    const int tile = d.color[size_t(c[size_t(apex)])];
    for (int k = 0; k < 4; ++k) {
      if (c[size_t(k)] < 0) continue;
      const auto& p = kCorner[size_t((k - apex) & 3)];
      out.mesh.face_vertices.push_back(c[size_t(k)]);
      out.appearance.texcoords.push_back(atlas_uv(layout, tile, p[0], p[1]));
    }
    out.mesh.face_start.push_back(int32_t(out.mesh.face_vertices.size()));
  }
  out.appearance.materials.push_back({.name = "duotone", .base_color = {1, 1, 1}, .texture = std::move(atlas)});
  return out;
}

Polylines separating_curves(const Duotone& d, TileStyle style) {
  const QuadMesh& m = d.quads;
  std::array<std::vector<LocalPoint>, 4> curve;
  for (int a = 0; a < 4; ++a) curve[size_t(a)] = corner_curve(style, a);
  Polylines out;
  out.points.reserve(d.cycle.order.size() * (curve[0].size() + 1));
  for (int32_t k = 0; k < d.cycle.num_cycles(); ++k) {
    const int32_t first = d.cycle.cycle_start[size_t(k)], last = d.cycle.cycle_start[size_t(k) + 1];
    // The side the curve left the previous triangle by; the first triangle leaves by
    // the side it shares with the second.
    int32_t entry = -1;
    {
      const int32_t id = d.cycle.order[size_t(first)], next = d.cycle.order[size_t(first + 1 < last ? first + 1 : first)];
      const int a = id & 3, b = next & 3;
      const int32_t exit = side_key(m, id >> 2, a);
      const bool forward = exit == side_key(m, next >> 2, b) || exit == side_key(m, next >> 2, (b + 3) & 3);
      entry = side_key(m, id >> 2, forward ? (a + 3) & 3 : a);
    }
    for (int32_t i = first; i < last; ++i) {
      const int32_t q = d.cycle.order[size_t(i)] >> 2;
      const int a = d.cycle.order[size_t(i)] & 3;
      const bool forward = side_key(m, q, (a + 3) & 3) == entry;
      out.points.push_back(side_midpoint(m, m.positions, q, forward ? (a + 3) & 3 : a));
      const auto& points = curve[size_t(a)];
      for (size_t j = 0; j < points.size(); ++j) {
        const LocalPoint& p = points[forward ? j : points.size() - 1 - j];
        out.points.push_back(surface_point(m, q, p.s, p.t));
      }
      entry = side_key(m, q, forward ? a : (a + 3) & 3);
    }
    out.start.push_back(int32_t(out.points.size()));
  }
  return out;
}

std::array<PolygonMesh, 2> duotone_regions(const Duotone& d, TileStyle style) { return duotone_regions(d, style, d.quads.positions); }

namespace {

// Triangles of a simple polygon (indices into `pts`, counter-clockwise) by ear clipping,
// appended to `out` counter-clockwise. Quadratic, for the few points of a tile piece.
void clip_ears(std::vector<int> polygon, const std::vector<LocalPoint>& pts, std::vector<std::array<int, 3>>& out) {
  const auto area = [&](int a, int b, int c) {
    const LocalPoint p = pts[size_t(a)], q = pts[size_t(b)], r = pts[size_t(c)];
    return (q.s - p.s) * (r.t - p.t) - (q.t - p.t) * (r.s - p.s);
  };
  while (polygon.size() > 3) {
    const size_t n = polygon.size();
    size_t ear = n, widest = 0;
    double widest_area = -INFINITY;
    for (size_t i = 0; i < n && ear == n; ++i) {
      const int a = polygon[(i + n - 1) % n], b = polygon[i], c = polygon[(i + 1) % n];
      const double abc = area(a, b, c);
      if (abc > widest_area) widest_area = abc, widest = i;
      if (!(abc > 0)) continue;
      bool empty = true;
      for (const int x : polygon)
        if (x != a && x != b && x != c && area(a, b, x) >= 0 && area(b, c, x) >= 0 && area(c, a, x) >= 0) empty = false;
      if (empty) ear = i;
    }
    if (ear == n) ear = widest; // only rounding leaves no clean ear: the widest goes
    out.push_back({polygon[(ear + n - 1) % n], polygon[ear], polygon[(ear + 1) % n]});
    polygon.erase(polygon.begin() + std::ptrdiff_t(ear));
  }
  if (polygon.size() == 3) out.push_back({polygon[0], polygon[1], polygon[2]});
}

} // namespace

std::array<PolygonMesh, 2> duotone_regions(const Duotone& d, TileStyle style, std::span<const Vec3> at,
                                           RegionOrigins* origins, std::span<const float> gaps) {
  const QuadMesh& m = d.quads;
  if (at.size() != m.positions.size())
    throw std::invalid_argument("duotone_regions: " + std::to_string(at.size()) + " corners for a duotone of " +
                                std::to_string(m.positions.size()));
  const bool apart = !gaps.empty();
  if (apart && gaps.size() != 5 * size_t(m.num_quads()))
    throw std::invalid_argument("duotone_regions: " + std::to_string(gaps.size()) + " gaps for " +
                                std::to_string(m.num_quads()) + " quads");
  // Points of a quad: 32 (8 + 2 * 7 + 1) at most, or with the regions apart, each curve
  // and side point twice.
  const int64_t stride = apart ? 64 : 32;
  std::array<std::vector<LocalPoint>, 4> curve;
  for (int a = 0; a < 4; ++a) curve[size_t(a)] = corner_curve(style, a);
  std::array<PolygonMesh, 2> out;
  // Corners and side midpoints are shared with neighbouring quads: one vertex each per
  // region. Curve points inside a quad belong to it alone.
  std::array<std::vector<int32_t>, 2> corner_vertex, side_vertex;
  for (int r = 0; r < 2; ++r) {
    corner_vertex[size_t(r)].assign(m.positions.size(), -1);
    side_vertex[size_t(r)].assign(4 * size_t(m.num_quads()), -1);
  }
  std::vector<LocalPoint> pts;
  std::array<std::vector<int32_t>, 2> local_vertex;
  std::vector<int> piece, half;
  std::vector<std::array<int, 3>> ears;
  for (int32_t q = 0; q < m.num_quads(); ++q) {
    const auto& c = m.quads[size_t(q)];
    const auto ap = apexes(d, q);
    // Local points: corners 0..3, side points 4..7 (the midpoints; apart, moved towards
    // the apex on the side), the interior curve points of each apex (from side a-1's
    // midpoint towards side a's), the quad's centre; apart, then the band's own side
    // points (moved away from the apex) and curves.
    const auto gap = [&](int k) { return apart ? double(gaps[5 * size_t(q) + size_t(k)]) : 0.0; };
    const auto is_apex = [&](int k) { return k == ap[0] || k == ap[1]; };
    const auto along_side = [&](int k, bool towards_apex) {
      const int w = towards_apex == is_apex(k) ? k : (k + 1) & 3, o = w == k ? (k + 1) & 3 : k; // from w, 0.5 - gap towards o
      const double f = 0.5 - gap(k);
      return LocalPoint{kCorner[size_t(w)][0] + f * (kCorner[size_t(o)][0] - kCorner[size_t(w)][0]),
                        kCorner[size_t(w)][1] + f * (kCorner[size_t(o)][1] - kCorner[size_t(w)][1])};
    };
    pts.assign(8, {});
    for (int k = 0; k < 4; ++k) {
      pts[size_t(k)] = {kCorner[size_t(k)][0], kCorner[size_t(k)][1]};
      pts[size_t(4 + k)] = along_side(k, true);
    }
    // A curve point scaled about its apex so that the curve lies `g` further in (towards
    // the apex, g < 0: away), g moving from side a-1's gap to side a's along it, and at
    // least the quad's inner gap.
    const auto add_points = [&](int a, double sign) {
      const std::vector<LocalPoint>& points = curve[size_t(a)];
      const auto& corner = kCorner[size_t(a)];
      for (size_t i = 0; i < points.size(); ++i) {
        if (!apart) { // the curve itself, exactly
          pts.push_back(points[i]);
          continue;
        }
        const double w = double(i + 1) / double(points.size() + 1);
        const double f = 1 - sign * 2 * std::max((1 - w) * gap((a + 3) & 3) + w * gap(a), gap(4));
        pts.push_back({corner[0] + f * (points[i].s - corner[0]), corner[1] + f * (points[i].t - corner[1])});
      }
    };
    std::array<int, 2> curve_first{}, band_first{};
    for (int j = 0; j < 2 && ap[size_t(j)] >= 0; ++j) {
      curve_first[size_t(j)] = int(pts.size());
      add_points(ap[size_t(j)], 1);
    }
    const int centre = int(pts.size());
    pts.push_back({0.5, 0.5});
    std::array<int, 4> band_side{4, 5, 6, 7};
    band_first = curve_first;
    if (apart) {
      for (int k = 0; k < 4; ++k) {
        band_side[size_t(k)] = int(pts.size());
        pts.push_back(along_side(k, false));
      }
      for (int j = 0; j < 2 && ap[size_t(j)] >= 0; ++j) {
        band_first[size_t(j)] = int(pts.size());
        add_points(ap[size_t(j)], -1);
      }
    }
    const auto side_of = [&](int p) {
      if (p >= 4 && p < 8) return p - 4;
      for (int k = 0; k < 4 && apart; ++k)
        if (p == band_side[size_t(k)]) return k;
      return -1;
    };
    for (auto& v : local_vertex) v.assign(pts.size(), -1);
    auto vertex = [&](int r, int p) -> int32_t {
      int32_t& id = local_vertex[size_t(r)][size_t(p)];
      if (id >= 0) return id;
      const int side = side_of(p);
      int32_t* shared = p < 4       ? &corner_vertex[size_t(r)][size_t(c[size_t(p)])]
                        : side >= 0 ? &side_vertex[size_t(r)][size_t(side_key(m, q, side))]
                                    : nullptr;
      if (shared && *shared >= 0) return id = *shared;
      id = out[size_t(r)].num_vertices();
      // Apart, the regions' side points differ: the second's are numbered after the
      // quads' points.
      const int64_t points = int64_t(m.positions.size()), sides = 4 * int64_t(m.num_quads());
      if (origins)
        origins->vertex_point[size_t(r)].push_back(p < 4       ? int64_t(c[size_t(p)])
                                                   : side >= 0 ? points + side_key(m, q, side) + (apart && r == 1 ? sides + stride * sides / 4 : 0)
                                                               : points + sides + stride * int64_t(q) + p);
      // A half quad's centre halves its boundary edge. A side point is placed from the
      // side's corners alone, so that both quads on it place it alike: the midpoint, or
      // apart, the gap from it towards the corner of the region's colour.
      Vec3 position;
      if (p < 4) {
        position = at[size_t(c[size_t(p)])];
      } else if (side >= 0 && !apart) {
        position = side_midpoint(m, at, q, side);
      } else if (side >= 0) {
        int32_t w = c[size_t(side)], o = c[size_t((side + 1) & 3)];
        if (d.color[size_t(w)] != r) std::swap(w, o);
        const Vec3d from = to_double(at[size_t(w)]);
        position = to_float(from + (to_double(at[size_t(o)]) - from) * (0.5 - gap(side)));
      } else if (p == centre && m.is_half(q)) {
        position = midpoint(at[size_t(c[0])], at[size_t(c[2])]);
      } else {
        position = surface_point(m, at, q, pts[size_t(p)].s, pts[size_t(p)].t);
      }
      out[size_t(r)].positions.push_back(position);
      if (shared) *shared = id;
      return id;
    };
    // The curve around apex ap[j] from side a-1's midpoint to side a's, or back: the
    // corner piece's or, apart, the band's own.
    auto add_curve = [&](int j, bool backwards, bool band = false) {
      const int a = ap[size_t(j)];
      const int count = int(curve[size_t(a)].size());
      const int first = band ? band_first[size_t(j)] : curve_first[size_t(j)];
      const int start = band ? band_side[size_t((a + 3) & 3)] : 4 + ((a + 3) & 3);
      if (!backwards) piece.push_back(start);
      for (int i = 0; i < count; ++i) piece.push_back(first + (backwards ? count - 1 - i : i));
      if (backwards) piece.push_back(start);
    };
    // Splits the piece at the fold (its points there are corners 0 and 2 or curve points
    // placed on it) and fans each half: a corner piece from its corner (a quarter disc,
    // or half of one, is convex), a band from the quad's centre, which lies on the fold
    // between the band's two points there and sees all of the band's outline (every
    // arc's tangent through it meets the arc at a side midpoint). Constant work per quad.
    auto emit_piece = [&](int r, bool band) {
      for (int side = 0; side < 2; ++side) {
        if (m.is_half(q) && side == 0) continue;
        half.clear();
        for (int p : piece) {
          const double f = pts[size_t(p)].s - pts[size_t(p)].t;
          if (side == 0 ? f >= 0 : f <= 0) half.push_back(p);
        }
        const size_t n = half.size();
        if (n < 3) continue;
        auto face = [&](int a, int b, int cc) {
          out[size_t(r)].add_face({vertex(r, a), vertex(r, b), vertex(r, cc)});
          if (origins) origins->face_quad[size_t(r)].push_back(q);
        };
        if (!band) {
          for (size_t i = 1; i + 1 < n; ++i) face(half[0], half[i], half[i + 1]);
          continue;
        }
        // Apart, the band's curves lie further out than the tangents through the centre.
        if (apart) {
          ears.clear();
          clip_ears(half, pts, ears);
          for (const auto& [a, b, cc] : ears) face(a, b, cc);
          continue;
        }
        size_t fold = 0; // half[fold] and the point after it lie on the fold
        auto on_fold = [&](int p) { return pts[size_t(p)].s == pts[size_t(p)].t; };
        while (fold < n && !(on_fold(half[fold]) && on_fold(half[(fold + 1) % n]))) ++fold;
        if (fold == n) throw std::logic_error("duotone_regions: a band of quad " + std::to_string(q) + " misses the fold");
        for (size_t i = 1; i < n; ++i) face(centre, half[(fold + i) % n], half[(fold + i + 1) % n]);
      }
    };
    for (int j = 0; j < 2 && ap[size_t(j)] >= 0; ++j) {
      const int a = ap[size_t(j)];
      piece.assign({a, 4 + a});
      add_curve(j, true);
      emit_piece(d.color[size_t(c[size_t(a)])], false);
    }
    if (m.is_half(q)) {
      piece.assign({0, 2});
      add_curve(0, false, true);
      piece.push_back(band_side[3]);
      emit_piece(d.color[size_t(c[0])], true);
    } else {
      const int a = ap[0];
      piece.assign({(a + 1) & 3});
      add_curve(1, false, true);
      piece.push_back(band_side[size_t((a + 2) & 3)]);
      piece.push_back((a + 3) & 3);
      add_curve(0, false, true);
      piece.push_back(band_side[size_t(a)]);
      emit_piece(d.color[size_t(c[size_t((a + 1) & 3)])], true);
    }
  }
  return out;
}

namespace {

// The shortest a unit step of a quad half's square maps to (the half's Jacobian's least
// singular value): its edges e1, e2 are the images of the square's two directions.
double least_stretch(Vec3d e1, Vec3d e2) {
  const double a = dot(e1, e1), b = dot(e1, e2), c = dot(e2, e2);
  return std::sqrt(std::max(0.0, (a + c) / 2 - std::hypot((a - c) / 2, b)));
}

} // namespace

std::vector<float> duotone_gaps(const Duotone& d, TileStyle style, std::span<const Vec3> outer, std::span<const Vec3> inner,
                                double clearance) {
  const QuadMesh& m = d.quads;
  if (outer.size() != m.positions.size() || inner.size() != m.positions.size())
    throw std::invalid_argument("duotone_gaps: corners not one per vertex of the duotone's quads");
  std::vector<float> gaps(5 * size_t(m.num_quads()), 0);
  const auto need = [&](int32_t q, int k, double gap) {
    float& g = gaps[5 * size_t(q) + size_t(k)];
    g = std::max(g, float(gap));
  };
  // The curve around each corner of the square, from side a-1's midpoint to side a's.
  std::array<std::vector<LocalPoint>, 4> lines;
  for (int a = 0; a < 4; ++a) {
    const auto mid = [](int k) {
      return LocalPoint{(kCorner[size_t(k)][0] + kCorner[size_t((k + 1) & 3)][0]) / 2,
                        (kCorner[size_t(k)][1] + kCorner[size_t((k + 1) & 3)][1]) / 2};
    };
    std::vector<LocalPoint>& line = lines[size_t(a)];
    line.assign(1, mid((a + 3) & 3));
    const std::vector<LocalPoint> points = corner_curve(style, a);
    line.insert(line.end(), points.begin(), points.end());
    line.push_back(mid(a));
  }
  for (int32_t q = 0; q < m.num_quads(); ++q) {
    const auto& c = m.quads[size_t(q)];
    const auto ap = apexes(d, q);
    for (const std::span<const Vec3> at : {outer, inner}) {
      const auto corner = [&](int k) { return to_double(at[size_t(c[size_t(k)])]); };
      const auto on = [&](LocalPoint x) { return to_double(surface_point(m, at, q, x.s, x.t)); };
      double least = least_stretch(corner(2) - corner(3), corner(3) - corner(0));
      if (c[1] >= 0) least = std::min(least, least_stretch(corner(1) - corner(0), corner(2) - corner(1)));
      need(q, 4, clearance / 2 / least);
      // A side's point moves along the side: the curve leaving it moves by that times the
      // sine of the angle between them.
      for (int j = 0; j < 2 && ap[size_t(j)] >= 0; ++j) {
        const int a = ap[size_t(j)];
        const std::vector<LocalPoint>& line = lines[size_t(a)];
        for (const auto& [k, end, inward] : {std::tuple{(a + 3) & 3, size_t(0), size_t(1)}, std::tuple{a, line.size() - 1, line.size() - 2}}) {
          const Vec3d side = corner((k + 1) & 3) - corner(k), leaving = on(line[inward]) - on(line[end]);
          const double sine = norm(cross(side, leaving)) / (norm(side) * norm(leaving));
          need(q, k, clearance / 2 / (norm(side) * std::max(sine, 0.05)));
        }
      }
    }
  }
  // Both quads on a side take the wider.
  for (int32_t q = 0; q < m.num_quads(); ++q)
    for (int k = 0; k < 4; ++k)
      if (const int32_t n = m.neighbors[size_t(q)][size_t(k)]; n >= 0) {
        float& mine = gaps[5 * size_t(q) + size_t(k)];
        float& theirs = gaps[5 * size_t(n / 4) + size_t(n % 4)];
        mine = theirs = std::max(mine, theirs);
      }
  return gaps;
}

} // namespace meander
