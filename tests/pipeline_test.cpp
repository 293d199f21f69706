// Property test of the whole pipeline on arbitrary small polygon soups: whatever repair
// accepts, the curve stage must turn into valid cycles, one per component; whatever it
// refuses, it refuses with a meander error, never a crash or a wrong cycle.
#include "meander/check.h"
#include "meander/connectivity.h"
#include "meander/error.h"
#include "meander/pipeline.h"

#include <gtest/gtest.h>

#include <random>

namespace meander {
namespace {

// A soup of random faces over few vertices, so that shared edges, non-manifold edges,
// pinched vertices, duplicates, repeated indices and misoriented faces all occur often.
PolygonMesh random_soup(std::mt19937& rng) {
  std::uniform_int_distribution<int> vertex_count(3, 12), face_count(1, 24), face_size(3, 6);
  PolygonMesh m;
  const int nv = vertex_count(rng);
  std::uniform_real_distribution<float> coordinate(-1, 1);
  for (int v = 0; v < nv; ++v) m.positions.push_back({coordinate(rng), coordinate(rng), coordinate(rng)});
  std::uniform_int_distribution<int32_t> vertex(0, nv - 1);
  const int nf = face_count(rng);
  for (int f = 0; f < nf; ++f) {
    std::vector<int32_t> face(size_t(face_size(rng)));
    for (int32_t& v : face) v = vertex(rng);
    m.add_face(face);
  }
  return m;
}

// Number of edge-connected components (faces joined across shared edges).
int components(const PolygonMesh& m) {
  const Connectivity c = build_connectivity(m);
  std::vector<int32_t> label(size_t(m.num_faces()));
  for (int32_t f = 0; f < m.num_faces(); ++f) label[size_t(f)] = f;
  for (bool changed = true; changed;) {
    changed = false;
    for (int32_t e = 0; e < c.num_edges(); ++e) {
      int32_t low = INT32_MAX;
      for (int32_t h : c.halfedges(e)) low = std::min(low, label[size_t(c.face_of(h))]);
      for (int32_t h : c.halfedges(e))
        if (label[size_t(c.face_of(h))] != low) label[size_t(c.face_of(h))] = low, changed = true;
    }
  }
  std::sort(label.begin(), label.end());
  return int(std::unique(label.begin(), label.end()) - label.begin());
}

TEST(Pipeline, ArbitrarySoupsGiveValidCyclesOrClearErrors) {
  std::mt19937 rng(20261123);
  int accepted = 0, refused = 0, closed_meshes = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const PolygonMesh soup = random_soup(rng);
    SCOPED_TRACE("trial " + std::to_string(trial));
    RepairResult repaired;
    try {
      repaired = repair(soup, "soup.obj");
    } catch (const Error& e) {
      ++refused;
      EXPECT_EQ(std::string(e.what()).rfind("soup.obj: ", 0), 0u) << e.what();
      continue;
    }
    ++accepted;
    const int expected = components(repaired.mesh);
    for (TreeStrategy tree : {TreeStrategy::random, TreeStrategy::uniform, TreeStrategy::bfs, TreeStrategy::dfs, TreeStrategy::shaped}) {
      const CurveResult r = make_curve(repaired.mesh, repaired.connectivity, {.cycle = {.tree = tree, .seed = uint64_t(trial)}});
      ASSERT_EQ(verify_cycle(r.quads, r.cycle), "");
      ASSERT_EQ(r.cycle.num_cycles(), expected);
      for (Vec3 p : r.curves.points) ASSERT_TRUE(is_finite(p));
    }
    // Catmull-Clark quads carry the cycle on closed meshes and refuse open ones.
    const Connectivity c = build_connectivity(repaired.mesh);
    bool closed = true;
    for (int32_t e = 0; e < c.num_edges(); ++e) closed = closed && c.edge_degree(e) == 2;
    if (closed) {
      const CurveResult r = make_curve(repaired.mesh, {.quadrangulation = Quadrangulation::catmull_clark});
      ASSERT_EQ(verify_cycle(r.quads, r.cycle), "");
      ASSERT_EQ(r.cycle.num_cycles(), expected);
      ++closed_meshes;
    } else {
      EXPECT_THROW(make_curve(repaired.mesh, {.quadrangulation = Quadrangulation::catmull_clark}), TopologyError);
    }
  }
  // Both branches must really be exercised for the test to mean anything.
  EXPECT_GT(accepted, 500);
  EXPECT_GT(refused, 0);
  EXPECT_GT(closed_meshes, 0);
}

} // namespace
} // namespace meander
