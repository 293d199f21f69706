// Meshes whose elements lie scattered in memory are put in a locality order before the
// curve (locality.h, RepairOptions::reorder): the same surface, and the same messages
// as the input's order would give.
#include "test_support.h"

#include "meander/check.h"
#include "meander/error.h"
#include "meander/hamiltonian.h"
#include "meander/io.h"
#include "meander/locality.h"
#include "meander/quadrangulate.h"
#include "meander/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>

namespace meander {
namespace {

// A hash of each face's corner positions in order, sorted: what reordering must keep.
std::vector<uint64_t> faces_by_position(const PolygonMesh& mesh) {
  std::vector<uint64_t> faces(size_t(mesh.num_faces()));
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    uint64_t h = 1469598103934665603ULL;
    for (const int32_t v : mesh.face(f))
      for (const float x : {mesh.positions[size_t(v)].x, mesh.positions[size_t(v)].y, mesh.positions[size_t(v)].z})
        h = (h ^ std::bit_cast<uint32_t>(x)) * 1099511628211ULL;
    faces[size_t(f)] = h;
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

// What repair refuses the mesh with, or "no refusal".
std::string refusal(const PolygonMesh& mesh, const RepairOptions& options) {
  try {
    repair(PolygonMesh(mesh), "s.ply", options);
  } catch (const Error& e) {
    return e.what();
  }
  return "no refusal";
}

const PolygonMesh& large_sphere() {
  static const PolygonMesh mesh = sphere(300'000); // above is_scattered's 2^18 faces
  return mesh;
}

const PolygonMesh& large_shuffled_sphere() {
  static const PolygonMesh mesh = shuffled(large_sphere(), 1);
  return mesh;
}

TEST(Locality, ShuffledMeshIsScatteredAndGeneratedOnesAreNot) {
  // Each large enough to be looked at: 2^18 faces or more.
  ASSERT_GE(large_sphere().num_faces(), 1 << 18);
  EXPECT_FALSE(is_scattered(large_sphere()));
  const PolygonMesh ring = torus(300'000), subdivided = genus_surface(2, 1'000'000);
  ASSERT_GE(ring.num_faces(), 1 << 18);
  ASSERT_GE(subdivided.num_faces(), 1 << 18);
  EXPECT_FALSE(is_scattered(ring));
  // OpenSubdiv numbers the refined vertices in a few streams, each in order.
  EXPECT_FALSE(is_scattered(subdivided));
  EXPECT_TRUE(is_scattered(large_shuffled_sphere()));
  EXPECT_FALSE(is_scattered(shuffled(sphere(20000), 1))); // small: fits the caches anyway
}

TEST(Locality, ReorderedMeshIsTheSameSurfaceInOrder) {
  const PolygonMesh& input = large_shuffled_sphere();
  const MeshOrder order = locality_order(input);
  const PolygonMesh local = reordered(input, order);
  ASSERT_EQ(local.num_faces(), input.num_faces());
  ASSERT_EQ(local.num_vertices(), input.num_vertices());
  // Each face keeps its corners, first corner and orientation included.
  for (int32_t f = 0; f < local.num_faces(); f += 997) {
    const auto was = input.face(order.face_order[size_t(f)]), is = local.face(f);
    ASSERT_EQ(was.size(), is.size());
    for (size_t k = 0; k < is.size(); ++k) {
      EXPECT_EQ(is[k], order.vertex_rank[size_t(was[k])]);
      EXPECT_EQ(local.positions[size_t(is[k])], input.positions[size_t(was[k])]);
    }
  }
  EXPECT_EQ(faces_by_position(local), faces_by_position(input));
  EXPECT_FALSE(is_scattered(local));
}

TEST(Locality, MixedFaceSizesKeepTheirCorners) {
  PolygonMesh mesh = genus_surface(2, 262'144); // quads, half of them split below
  // Split every other quad into two triangles, so that sizes differ from face to face.
  PolygonMesh mixed;
  mixed.positions = mesh.positions;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto q = mesh.face(f);
    if (f % 2) {
      mixed.add_face(q);
    } else {
      mixed.add_face({q[0], q[1], q[2]});
      mixed.add_face({q[0], q[2], q[3]});
    }
  }
  const PolygonMesh input = shuffled(mixed, 1);
  ASSERT_GE(input.num_faces(), 1 << 18);
  ASSERT_TRUE(is_scattered(input));
  const MeshOrder order = locality_order(input);
  const PolygonMesh local = reordered(input, order);
  EXPECT_EQ(faces_by_position(local), faces_by_position(input));
  // Repair drops the input once reordered, and brings it back when it needs anything.
  const PolygonMesh back = restored(local, order);
  EXPECT_EQ(back.positions, input.positions);
  EXPECT_EQ(back.face_start, input.face_start);
  EXPECT_EQ(back.face_vertices, input.face_vertices);
}

// A scattered mesh that repair accepts with a notice (a Moebius band is not orientable) is
// brought back to its own order, read as without reordering, then reordered.
TEST(Locality, MeshWithANoticeIsBroughtBack) {
  const PolygonMesh band = shuffled(moebius(300'000), 1);
  ASSERT_TRUE(is_scattered(band));
  const RepairResult plain = repair(PolygonMesh(band), "s.ply");
  const RepairResult asked = repair(PolygonMesh(band), "s.ply", {.reorder = true});
  ASSERT_EQ(plain.notices.size(), 1u);
  EXPECT_EQ(asked.notices, plain.notices);
  EXPECT_TRUE(asked.reordered);
  EXPECT_EQ(faces_by_position(asked.mesh), faces_by_position(band));
  EXPECT_EQ(asked.mesh.face_vertices, reordered(band, locality_order(band)).face_vertices);
}

TEST(Locality, RepairReordersOnlyWhenAsked) {
  const RepairResult as_given = repair(PolygonMesh(large_shuffled_sphere()), "s.ply");
  EXPECT_FALSE(as_given.reordered);
  EXPECT_EQ(as_given.mesh.face_vertices, large_shuffled_sphere().face_vertices);
  const RepairResult local = repair(PolygonMesh(large_shuffled_sphere()), "s.ply", {.reorder = true});
  EXPECT_TRUE(local.reordered);
  EXPECT_TRUE(local.repairs.empty());
  EXPECT_FALSE(is_scattered(local.mesh));
  EXPECT_EQ(faces_by_position(local.mesh), faces_by_position(large_shuffled_sphere()));
  // Its connectivity is that of the reordered mesh: the cycle covers it.
  const QuadMesh quads = dual_simplest(local.mesh, local.connectivity);
  const TriangleCycle cycle = hamiltonian_cycle(quads);
  EXPECT_EQ(cycle.num_cycles(), 1);
  EXPECT_EQ(verify_cycle(quads, cycle), "");
}

// A mesh that needs repair is repaired in its own order, so that the messages name the
// input's faces and vertices as without reordering; then the result is reordered.
TEST(Locality, MeshThatNeedsRepairKeepsItsMessages) {
  PolygonMesh broken = large_shuffled_sphere();
  broken.add_face(broken.face(123)); // a duplicate of face 123
  broken.positions.push_back({9, 9, 9}); // an unreferenced vertex
  const RepairResult plain = repair(PolygonMesh(broken), "s.ply");
  const RepairResult asked = repair(PolygonMesh(broken), "s.ply", {.reorder = true});
  ASSERT_EQ(plain.repairs.size(), 2u);
  EXPECT_EQ(asked.repairs, plain.repairs);
  EXPECT_NE(asked.repairs[0].find("face " + std::to_string(broken.num_faces() - 1) + " duplicates face 123"), std::string::npos)
      << asked.repairs[0];
  EXPECT_FALSE(plain.reordered);
  EXPECT_TRUE(asked.reordered);
  EXPECT_FALSE(is_scattered(asked.mesh));
  EXPECT_EQ(faces_by_position(asked.mesh), faces_by_position(plain.mesh));
  EXPECT_TRUE(asked.connectivity.edge_start.empty()); // it was the input order's
  const std::string refused = refusal(broken, {.strict = true, .reorder = true});
  EXPECT_EQ(refused, refusal(broken, {.strict = true}));
  EXPECT_NE(refused.find("duplicates face 123"), std::string::npos) << refused;
}

// A position that is not a number is refused as it would be in the input's order; the
// reorder it meets first must survive it.
TEST(Locality, NonFinitePositionIsRefusedAsInTheInputOrder) {
  PolygonMesh broken = large_shuffled_sphere();
  broken.positions[5] = {std::nanf(""), 0, 0};
  const std::string refused = refusal(broken, {.reorder = true});
  EXPECT_EQ(refused, refusal(broken, {}));
  EXPECT_NE(refused.find("vertex 5 has a non-finite position"), std::string::npos) << refused;
}

// Through the CLI: the scattered mesh is reordered (-v says so) and covered by one curve.
TEST(Locality, CurveOfAScatteredMeshThroughTheCli) {
  const auto dir = test::output_dir();
  ASSERT_EQ(test::run_cli({"generate", "sphere", "--faces", "300000", "--shuffle", "1", "-o", (dir / "shuffled.ply").string()})
                .exit_code,
            0);
  ASSERT_EQ(read_mesh(dir / "shuffled.ply").face_vertices, large_shuffled_sphere().face_vertices);
  const auto run = test::run_cli({"curve", (dir / "shuffled.ply").string(), "-o", (dir / "c.ply").string(), "--samples",
                                  "1", "-v"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("reordered"), std::string::npos) << run.err;
  const Polylines curve = read_polylines(dir / "c.ply");
  EXPECT_EQ(curve.size(), 1);
  EXPECT_EQ(int64_t(curve.points.size()), int64_t(large_sphere().num_corners())); // one point per triangle: 2E
  // --quad none names faces by their number: the input is left in its order.
  const auto none = test::run_cli({"curve", (dir / "shuffled.ply").string(), "-o", (dir / "n.ply").string(), "--quad",
                                   "none", "-v"});
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_EQ(none.err.find("reordered"), std::string::npos) << none.err;
}

} // namespace
} // namespace meander
