// Catmull-Clark through OpenSubdiv: what the wires rely on beyond "it looks smooth".
#include "meander/subdivide.h"

#include "meander/error.h"
#include "meander/shapes.h"

#include <gtest/gtest.h>

#include <numeric>

namespace meander {
namespace {

// A small mixed mesh with a boundary: quads of a grid, with its corner cells split into
// triangles.
PolygonMesh mixed_patch() {
  PolygonMesh m;
  const int n = 4;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.push_back({float(i), float(j), float((i * j) % 3) * 0.25f});
  auto v = [&](int i, int j) { return int32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if ((i + j) % 3 == 0) {
        m.add_face({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
        m.add_face({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
      } else {
        m.add_face({v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)});
      }
    }
  return m;
}

// variable_wire maps a smoothed face back to its control face by number: the children of
// a quad are 4^levels consecutive faces, in the order of their parents.
TEST(Subdivide, ChildrenOfAQuadAreConsecutive) {
  const PolygonMesh quads = subdivide(sphere(80), {.levels = 1}); // all quads
  for (int levels = 1; levels <= 3; ++levels) {
    TexturedMesh tagged{quads, {}};
    tagged.appearance.materials.resize(size_t(quads.num_faces()));
    tagged.appearance.face_material.resize(size_t(quads.num_faces()));
    std::iota(tagged.appearance.face_material.begin(), tagged.appearance.face_material.end(), 0);
    const TexturedMesh fine = subdivide(tagged, {.levels = levels});
    const int32_t children = 1 << (2 * levels);
    ASSERT_EQ(fine.mesh.num_faces(), quads.num_faces() * children);
    for (int32_t f = 0; f < fine.mesh.num_faces(); ++f)
      ASSERT_EQ(fine.appearance.face_material[size_t(f)], f / children) << "level " << levels << ", face " << f;
  }
}

// The kept refiner gives, for any positions of the control points, what subdivide()
// gives for the control mesh moved there.
TEST(Subdivide, KeptRefinerMatchesSubdivideForNewPositions) {
  PolygonMesh control = mixed_patch();
  for (const bool limit : {true, false}) {
    const CatmullClark refiner(control, {.levels = 2, .limit = limit});
    for (int move = 0; move < 3; ++move) {
      PolygonMesh moved = control;
      for (size_t v = 0; v < moved.positions.size(); ++v) moved.positions[v].z += float(move) * 0.1f * float(v % 5);
      const PolygonMesh expected = subdivide(moved, {.levels = 2, .limit = limit});
      const PolygonMesh got = refiner.refine(moved.positions);
      EXPECT_EQ(got.face_start, expected.face_start);
      EXPECT_EQ(got.face_vertices, expected.face_vertices);
      EXPECT_TRUE(got.positions == expected.positions) << "limit " << limit << ", move " << move;
    }
  }
  EXPECT_THROW(CatmullClark(control, {.levels = -1}), UsageError);
}

} // namespace
} // namespace meander
