// Duotone surfaces (paper Section 5): the colour graphs, the separating curve, the
// picture itself sampled through its texture, and the two regions cut along the curve,
// on every kind of surface.
#include "meander/duotone.h"

#include "meander/check.h"
#include "meander/connectivity.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/remesh.h"
#include "meander/shapes.h"
#include "meander/subdivide.h"

#include "io_test_support.h"
#include "test_support.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numeric>
#include <set>
#include <unordered_map>

namespace meander {
namespace {

using ::testing::HasSubstr;

// Disjoint sets written for the tests, sharing nothing with the library.
struct Sets {
  std::vector<int32_t> parent;
  explicit Sets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int32_t find(int32_t x) {
    while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
    return x;
  }
  bool unite(int32_t a, int32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent[size_t(a)] = b;
    return true;
  }
};

Duotone duotone_of(const PolygonMesh& mesh, const DuotoneOptions& options = {}) {
  const RepairResult r = repair(mesh, "test");
  const Connectivity c = r.connectivity.edge_start.empty() ? build_connectivity(r.mesh) : r.connectivity;
  return make_duotone(r.mesh, c, options);
}

// Quad components: quads joined across sides.
int32_t count_components(const QuadMesh& m, Sets& sets) {
  for (int32_t q = 0; q < m.num_quads(); ++q)
    for (int32_t n : m.neighbors[size_t(q)])
      if (n >= 0) sets.unite(q, n >> 2);
  int32_t count = 0;
  for (int32_t q = 0; q < m.num_quads(); ++q) count += sets.find(q) == q;
  return count;
}

// The invariants of Section 5.2 checked from the quads alone: every side joins the two
// colours; yellow and blue graphs each connect all their vertices in each component; under
// the tree rule yellow has no cycle once each boundary loop (the half quads' fixed
// yellow diagonals) is contracted; one loop per component.
void expect_duotone_invariants(const Duotone& d, DuotoneRule rule, const std::string& what) {
  const QuadMesh& m = d.quads;
  EXPECT_EQ(verify_cycle(m, d.cycle), "") << what;
  Sets quad_sets(size_t(m.num_quads()));
  const int32_t components = count_components(m, quad_sets);
  EXPECT_EQ(d.cycle.num_cycles(), components) << what;

  for (int32_t q = 0; q < m.num_quads(); ++q) {
    const auto& c = m.quads[size_t(q)];
    for (int k = 0; k < 4; ++k) {
      if (c[size_t(k)] < 0 || c[size_t((k + 1) & 3)] < 0) continue;
      ASSERT_NE(d.color[size_t(c[size_t(k)])], d.color[size_t(c[size_t((k + 1) & 3)])]) << what << ": quad " << q << " side " << k;
    }
  }
  // Graphs: yellow diagonals (half quads' boundary diagonals included), blue diagonals.
  Sets yellow(m.positions.size()), blue(m.positions.size()), contracted(m.positions.size());
  for (int32_t q = 0; q < m.num_quads(); ++q)
    if (m.is_half(q)) contracted.unite(m.quads[size_t(q)][0], m.quads[size_t(q)][2]);
  int32_t yellow_cycles = 0;
  for (int32_t q = 0; q < m.num_quads(); ++q) {
    const auto& c = m.quads[size_t(q)];
    const int dg = d.cycle.diagonal[size_t(q)];
    const int32_t a = c[size_t(dg)], b = c[size_t(dg + 2)];
    if (d.color[size_t(a)] == 0) {
      yellow.unite(a, b);
      if (!m.is_half(q)) yellow_cycles += !contracted.unite(a, b);
    } else {
      blue.unite(a, b);
    }
  }
  // Per component, all its vertices of one colour lie in one set of that colour.
  std::unordered_map<int32_t, std::array<int32_t, 2>> root_of_component;
  for (int32_t q = 0; q < m.num_quads(); ++q)
    for (int32_t v : m.quads[size_t(q)]) {
      if (v < 0) continue;
      const int col = d.color[size_t(v)];
      const int32_t root = col == 0 ? yellow.find(v) : blue.find(v);
      auto [it, fresh] = root_of_component.try_emplace(quad_sets.find(q), std::array<int32_t, 2>{-1, -1});
      int32_t& expected = it->second[size_t(col)];
      if (expected < 0) expected = root;
      ASSERT_EQ(root, expected) << what << ": the " << (col == 0 ? "yellow" : "blue") << " graph is not connected (vertex " << v << ")";
    }
  if (rule == DuotoneRule::tree) {
    EXPECT_EQ(yellow_cycles, 0) << what << ": the yellow graph has a cycle";
  }
}

// The picture itself: samples on a lattice over every fan triangle of the textured
// surface (as writers and renderers fan its faces), each classified to the nearer of
// the two colours, joined to lattice neighbours and to the same point seen from the
// next triangle when their colours agree. Returns the number of same-colour regions.
int32_t count_picture_regions(const TexturedMesh& t, const std::array<Color8, 2>& colors) {
  constexpr int N = 9; // odd, so no sample falls on a side midpoint, where the curve crosses
  const Texture& tex = t.appearance.materials[0].texture;
  std::array<LinearRgb, 2> lin{};
  for (int k = 0; k < 2; ++k) {
    Texture one{.width = 1, .height = 1, .rgba = {colors[size_t(k)][0], colors[size_t(k)][1], colors[size_t(k)][2], 255}};
    lin[size_t(k)] = sample_texture(one, {0.5f, 0.5f});
  }
  auto classify = [&](TexCoord uv) {
    const LinearRgb c = sample_texture(tex, uv);
    double d[2] = {0, 0};
    for (int k = 0; k < 2; ++k)
      for (int ch = 0; ch < 3; ++ch) d[k] += std::pow(double(c[size_t(ch)]) - lin[size_t(k)][size_t(ch)], 2);
    return d[1] < d[0] ? 1 : 0;
  };
  const int per_triangle = (N + 1) * (N + 2) / 2;
  int64_t triangles = 0;
  for (int32_t f = 0; f < t.mesh.num_faces(); ++f) triangles += t.mesh.face_size(f) - 2;
  Sets sets(size_t(triangles * per_triangle));
  std::vector<uint8_t> cls(sets.parent.size());
  std::unordered_map<uint64_t, std::vector<int32_t>> shared; // lattice point on an edge -> its samples
  auto index = [](int i, int j) { return j * (N + 1) - j * (j - 1) / 2 + i; };
  int32_t base = 0;
  for (int32_t f = 0; f < t.mesh.num_faces(); ++f) {
    const int32_t s = t.mesh.face_start[size_t(f)];
    for (int32_t k = 1; k + 1 < t.mesh.face_size(f); ++k, base += per_triangle) {
      const std::array<int32_t, 3> corner{s, s + k, s + k + 1};
      std::array<int32_t, 3> v{};
      std::array<TexCoord, 3> uv{};
      for (int i = 0; i < 3; ++i) {
        v[size_t(i)] = t.mesh.face_vertices[size_t(corner[size_t(i)])];
        uv[size_t(i)] = t.appearance.texcoords[size_t(corner[size_t(i)])];
      }
      // Edge lattice points keyed by the edge's vertices and the step from the lower one.
      auto key = [&](int32_t a, int32_t b, int step) {
        if (a > b) std::swap(a, b), step = N - step;
        if (step == 0) b = a;
        if (step == N) a = b, step = 0;
        return (uint64_t(a) << 36) | (uint64_t(b) << 8) | uint64_t(step);
      };
      for (int j = 0; j <= N; ++j)
        for (int i = 0; i + j <= N; ++i) {
          const float wb = float(i) / N, wc = float(j) / N, wa = 1 - wb - wc;
          const int32_t node = base + index(i, j);
          cls[size_t(node)] = uint8_t(classify({wa * uv[0].u + wb * uv[1].u + wc * uv[2].u, wa * uv[0].v + wb * uv[1].v + wc * uv[2].v}));
          if (j == 0) shared[key(v[0], v[1], i)].push_back(node);
          else if (i == 0) shared[key(v[0], v[2], j)].push_back(node);
          else if (i + j == N) shared[key(v[1], v[2], j)].push_back(node);
          auto join = [&](int32_t other) {
            if (cls[size_t(other)] == cls[size_t(node)]) sets.unite(node, other);
          };
          if (i > 0) join(base + index(i - 1, j));
          if (j > 0) join(base + index(i, j - 1));
          if (j > 0) join(base + index(i + 1, j - 1));
        }
    }
  }
  for (const auto& [k, nodes] : shared)
    for (size_t i = 1; i < nodes.size(); ++i)
      for (size_t j = 0; j < i; ++j)
        if (cls[size_t(nodes[i])] == cls[size_t(nodes[j])]) sets.unite(nodes[i], nodes[j]);
  int32_t regions = 0;
  for (size_t n = 0; n < sets.parent.size(); ++n) regions += sets.find(int32_t(n)) == int32_t(n);
  return regions;
}

struct Case {
  std::string name;
  PolygonMesh mesh;
  int32_t components = 1;
};

std::vector<Case> generated_cases() {
  return {{"sphere", sphere(200), 1},          {"torus", torus(300), 1},   {"pretzel", genus_surface(2, 600), 1},
          {"genus3", genus_surface(3, 800), 1}, {"grid (disc)", grid(72), 1}, {"moebius", moebius(40), 1}};
}

TEST(Duotone, ColourGraphsAndOneLoopPerComponentOnEverySurface) {
  for (const Case& c : generated_cases())
    for (Quadrangulation quad : {Quadrangulation::catmull_clark, Quadrangulation::dual_simplest})
      for (DuotoneRule rule : {DuotoneRule::tree, DuotoneRule::flip})
        for (TreeStrategy tree : {TreeStrategy::random, TreeStrategy::uniform, TreeStrategy::bfs, TreeStrategy::dfs}) {
          const Duotone d = duotone_of(c.mesh, {.quadrangulation = quad, .rule = rule, .tree = tree, .seed = 7});
          expect_duotone_invariants(d, rule, c.name + " " + std::string(to_string(tree)) + (rule == DuotoneRule::tree ? " tree" : " flip"));
          EXPECT_EQ(d.cycle.num_cycles(), c.components);
        }
}

TEST(Duotone, RealMeshesOfEveryKind) {
  MEANDER_REQUIRE_SHARED_MESHES();
  // Closed of genus 0..4, with boundary, non-orientable with boundary, several components.
  const std::vector<std::pair<std::string, int32_t>> files = {
      {"tetrahedron.obj", 1}, {"bob_small.ply", 1}, {"eight.off", 1},  {"genus3hexa1.obj", 1},
      {"fertility.off", 1},   {"grid.off", 1},      {"moebius.obj", 1}, {"platonic_shelf.obj", 5}};
  for (const auto& [file, components] : files)
    for (DuotoneRule rule : {DuotoneRule::tree, DuotoneRule::flip}) {
      const Duotone d = duotone_of(read_mesh(test::shared_meshes() / file), {.rule = rule});
      expect_duotone_invariants(d, rule, file);
      EXPECT_EQ(d.cycle.num_cycles(), components) << file;
    }
}

TEST(Duotone, CatmullClarkOnABoundaryFallsBackToDualSimplestAndSaysSo) {
  const Duotone closed = duotone_of(torus(100));
  EXPECT_EQ(closed.quadrangulation, Quadrangulation::catmull_clark);
  EXPECT_TRUE(closed.notes.empty());
  const Duotone open = duotone_of(grid(50));
  EXPECT_EQ(open.quadrangulation, Quadrangulation::dual_simplest);
  ASSERT_EQ(open.notes.size(), 1u);
  EXPECT_THAT(open.notes[0], HasSubstr("boundary edges"));
}

TEST(Duotone, TreeRuleYellowIsASpanningTreeOnAClosedSurface) {
  // Without boundary nothing is contracted: the yellow diagonals are exactly a spanning
  // tree, one edge fewer than the yellow vertices.
  const Duotone d = duotone_of(genus_surface(3, 500));
  int32_t yellow_vertices = 0, yellow_edges = 0;
  std::vector<uint8_t> used(d.quads.positions.size(), 0);
  for (const auto& c : d.quads.quads)
    for (int32_t v : c) used[size_t(v)] = 1;
  for (size_t v = 0; v < used.size(); ++v) yellow_vertices += used[v] && d.color[v] == 0;
  for (int32_t q = 0; q < d.quads.num_quads(); ++q) yellow_edges += duotone_diagonal_color(d, q) == 0;
  EXPECT_EQ(yellow_edges, yellow_vertices - 1);
}

// A closed quad torus of n x m quads: 2-colourable only if n and m are even.
PolygonMesh quad_torus(int n, int m) {
  PolygonMesh t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double a = 2 * M_PI * i / n, b = 2 * M_PI * j / m;
      t.positions.push_back({float((1 + 0.4 * std::cos(b)) * std::cos(a)), float((1 + 0.4 * std::cos(b)) * std::sin(a)), float(0.4 * std::sin(b))});
    }
  auto id = [&](int i, int j) { return ((i + n) % n) * m + (j + m) % m; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) t.add_face({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return t;
}

TEST(Duotone, QuadsAsIsWhenTwoColourable) {
  const Duotone d = duotone_of(quad_torus(8, 6), {.quadrangulation = Quadrangulation::none});
  EXPECT_EQ(d.quads.num_quads(), 48);
  expect_duotone_invariants(d, DuotoneRule::tree, "8x6 quad torus");
}

TEST(Duotone, NoneRefusesPrecisely) {
  // A 5 x 6 torus has an odd cycle of 5 edges around it.
  EXPECT_THAT(test::message_of<TopologyError>([] { duotone_of(quad_torus(5, 6), {.quadrangulation = Quadrangulation::none}); }),
              HasSubstr("would need both colours (an odd cycle of edges runs through it)"));
  // A quad grid has a boundary, which alternates colours.
  PolygonMesh sheet;
  for (int i = 0; i < 9; ++i) sheet.positions.push_back({float(i % 3), float(i / 3), 0});
  sheet.add_face({0, 1, 4, 3});
  sheet.add_face({1, 2, 5, 4});
  sheet.add_face({3, 4, 7, 6});
  sheet.add_face({4, 5, 8, 7});
  EXPECT_THAT(test::message_of<TopologyError>([&] { duotone_of(sheet, {.quadrangulation = Quadrangulation::none}); }),
              HasSubstr("face 0 has a boundary edge (0, 1)"));
  EXPECT_THAT(test::message_of<TopologyError>([] { duotone_of(torus(50), {.quadrangulation = Quadrangulation::none}); }),
              HasSubstr("quad none needs a mesh of quads only"));
}

TEST(Duotone, PictureHasExactlyTwoColourRegionsPerComponent) {
  const TileOptions tiles{.texture_size = 256};
  std::vector<Case> cases = {{"sphere", sphere(150), 1}, {"pretzel", genus_surface(2, 400), 1}, {"grid", grid(50), 1}, {"moebius", moebius(30), 1}};
  if (std::filesystem::is_directory(test::shared_meshes())) {
    cases.push_back({"bob_small.ply", read_mesh(test::shared_meshes() / "bob_small.ply"), 1});
    cases.push_back({"eight.off", read_mesh(test::shared_meshes() / "eight.off"), 1});
    cases.push_back({"platonic_shelf.obj", read_mesh(test::shared_meshes() / "platonic_shelf.obj"), 5});
  }
  for (const Case& c : cases)
    for (DuotoneRule rule : {DuotoneRule::tree, DuotoneRule::flip}) {
      const Duotone d = duotone_of(c.mesh, {.rule = rule, .seed = 3});
      EXPECT_EQ(count_picture_regions(duotone_surface(d, tiles), tiles.colors), 2 * c.components) << c.name;
    }
  // The straight-chord tiles have the same topology.
  const Duotone d = duotone_of(genus_surface(2, 400));
  const TileOptions chords{.style = TileStyle::triangles, .texture_size = 256};
  EXPECT_EQ(count_picture_regions(duotone_surface(d, chords), chords.colors), 2);
}

TEST(Duotone, SubdivisionCarriesTheTilesWithoutSeams) {
  // Face-varying texture coordinates keep each tile on the patch of its quad: the smooth
  // surface still shows exactly two regions, on a closed surface and on one with boundary.
  const TileOptions tiles{.texture_size = 256};
  for (const PolygonMesh& mesh : {genus_surface(2, 300), grid(40)}) {
    const TexturedMesh smooth = subdivide(duotone_surface(duotone_of(mesh), tiles), {.levels = 1});
    EXPECT_EQ(smooth.appearance.texcoords.size(), smooth.mesh.face_vertices.size());
    EXPECT_EQ(smooth.appearance.materials.size(), 1u);
    EXPECT_EQ(count_picture_regions(smooth, tiles.colors), 2);
  }
}

TEST(Duotone, RandomDiagonalsGiveManyRegionsWhichTheRulesJoin) {
  // The control for the picture check: Truchet tiles with no rule (Figure 18) break
  // into many regions, and the counter sees them.
  Duotone d = duotone_of(sphere(150));
  for (size_t q = 0; q < d.cycle.diagonal.size(); ++q) d.cycle.diagonal[q] = uint8_t(q * 7 % 3 == 0);
  EXPECT_GT(count_picture_regions(duotone_surface(d, {.texture_size = 256}), TileOptions{}.colors), 4);
}

using Segment = std::array<float, 6>;
Segment segment(Vec3 a, Vec3 b) {
  Segment s{a.x, a.y, a.z, b.x, b.y, b.z};
  if (std::lexicographical_compare(s.begin() + 3, s.end(), s.begin(), s.begin() + 3)) {
    std::rotate(s.begin(), s.begin() + 3, s.end());
  }
  return s;
}

std::set<Segment> boundary_segments(const PolygonMesh& m) {
  const Connectivity c = build_connectivity(m);
  std::set<Segment> out;
  for (int32_t e = 0; e < c.num_edges(); ++e)
    if (c.edge_degree(e) == 1) out.insert(segment(m.positions[size_t(c.edge_vertices[size_t(e)][0])], m.positions[size_t(c.edge_vertices[size_t(e)][1])]));
  return out;
}

TEST(Duotone, RegionsAreManifoldsCutExactlyAlongTheCurve) {
  for (const Case& c : generated_cases())
    for (TileStyle style : {TileStyle::truchet, TileStyle::triangles}) {
      const Duotone d = duotone_of(c.mesh, {.seed = 5});
      const std::array<PolygonMesh, 2> regions = duotone_regions(d, style);
      const Polylines curve = separating_curves(d, style);
      ASSERT_EQ(curve.size(), c.components) << c.name;
      std::set<Segment> curve_segments;
      for (int32_t k = 0; k < curve.size(); ++k) {
        const auto p = curve.polyline(k);
        for (size_t i = 0; i < p.size(); ++i) curve_segments.insert(segment(p[i], p[(i + 1) % p.size()]));
        EXPECT_TRUE(curve.closed(k));
      }
      // The surface's own boundary (half quads' diagonals) lies in the yellow region, each
      // edge in two halves at its midpoint.
      std::set<Segment> surface_boundary;
      for (const Segment& e : boundary_segments(duotone_surface(d, {.texture_size = 64}).mesh)) {
        const Vec3 a{e[0], e[1], e[2]}, b{e[3], e[4], e[5]};
        const Vec3 mid{float(0.5 * (double(a.x) + b.x)), float(0.5 * (double(a.y) + b.y)), float(0.5 * (double(a.z) + b.z))};
        surface_boundary.insert(segment(a, mid));
        surface_boundary.insert(segment(mid, b));
      }
      double regions_area = 0;
      for (int r = 0; r < 2; ++r) {
        const MeshReport report = inspect(regions[size_t(r)]);
        EXPECT_EQ(report.non_manifold_edges, 0) << c.name << " region " << r;
        EXPECT_EQ(report.non_manifold_vertices, 0) << c.name << " region " << r;
        EXPECT_EQ(report.components.size(), size_t(c.components)) << c.name << " region " << r;
        regions_area += surface_area(regions[size_t(r)]);
        std::set<Segment> expected = curve_segments;
        if (r == 0) expected.insert(surface_boundary.begin(), surface_boundary.end());
        EXPECT_TRUE(boundary_segments(regions[size_t(r)]) == expected) << c.name << " region " << r;
      }
      EXPECT_NEAR(regions_area, surface_area(duotone_surface(d, {.texture_size = 64}).mesh), 1e-5 * regions_area) << c.name;
    }
}

TEST(Duotone, TexCoordsPutEachTileOnItsQuadTurnedToItsDiagonal) {
  // At a quad's corners the texture shows the corner's own colour.
  const Duotone d = duotone_of(torus(80));
  const TileOptions tiles{.texture_size = 128};
  const TexturedMesh t = duotone_surface(d, tiles);
  ASSERT_EQ(t.mesh.num_faces(), d.quads.num_quads());
  const Texture& tex = t.appearance.materials[0].texture;
  for (int32_t f = 0; f < t.mesh.num_faces(); ++f)
    for (int32_t i = t.mesh.face_start[size_t(f)]; i < t.mesh.face_start[size_t(f) + 1]; ++i) {
      const LinearRgb c = sample_texture(tex, t.appearance.texcoords[size_t(i)]);
      const uint8_t col = d.color[size_t(t.mesh.face_vertices[size_t(i)])];
      // Yellow is far brighter than blue in its red channel.
      EXPECT_EQ(c[0] > 0.3f, col == 0) << "face " << f << " corner " << i;
    }
}

TEST(Duotone, ColoursAndStylesParseOrAreRefusedPrecisely) {
  EXPECT_EQ(parse_duotone_colors("red,#0A0b0c")[1], (Color8{10, 11, 12}));
  EXPECT_EQ(parse_duotone_colors("yellow,blue"), TileOptions{}.colors);
  EXPECT_THAT(test::message_of<UsageError>([] { parse_duotone_colors("red,#12345"); }),
              HasSubstr("colors 'red,#12345': '#12345' is not a colour (expected #rrggbb or one of yellow"));
  EXPECT_THAT(test::message_of<UsageError>([] { parse_duotone_colors("mauve,blue"); }), HasSubstr("'mauve' is not a colour"));
  EXPECT_THAT(test::message_of<UsageError>([] { parse_duotone_colors("red"); }), HasSubstr("expected two colours C1,C2"));
  EXPECT_THAT(test::message_of<UsageError>([] { parse_duotone_colors("red,red,blue"); }), HasSubstr("expected two colours"));
  EXPECT_THAT(test::message_of<UsageError>([] { parse_duotone_colors("#be2828,red"); }), HasSubstr("the two colours are the same"));
  for (const char* name : {"truchet", "outline", "triangles", "stripes", "dots"}) EXPECT_EQ(to_string(parse_tile_style(name)), name);
  EXPECT_EQ(test::message_of<UsageError>([] { parse_tile_style("zigzag"); }),
            "unknown tile style 'zigzag' (expected truchet, outline, triangles, stripes or dots)");
  EXPECT_THAT(test::message_of<UsageError>([] { duotone_atlas({.texture_size = 100000}); }), HasSubstr("texture_size 100000"));
  EXPECT_THAT(test::message_of<UsageError>([] { parse_duotone_rule("greedy"); }), HasSubstr("expected tree or flip"));
}

} // namespace
} // namespace meander
