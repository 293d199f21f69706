// The OBJ, PLY, STL and OFF files Meander writes, read back by another library: OpenMesh
// (its own readers, sharing no code with Meander's), so that a writer and Meander's
// reader cannot agree on a mistake. Positions come back as the same floats, faces as the
// same corners; STL, which has no shared vertices, as the same triangles.
#include "meander/io.h"
#include "meander/shapes.h"
#include "test_support.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace meander {
namespace {

namespace fs = std::filesystem;
using OpenMeshPoly = OpenMesh::PolyMesh_ArrayKernelT<>;

// A closed hexagonal prism: two hexagons and six quads, so that polygons of more than
// three corners are written as such.
PolygonMesh hexagonal_prism() {
  PolygonMesh m;
  for (const float z : {0.0f, 1.0f})
    for (int k = 0; k < 6; ++k) m.positions.push_back({float(std::cos(k * M_PI / 3)), float(std::sin(k * M_PI / 3)), z});
  m.add_face(std::vector<int32_t>{5, 4, 3, 2, 1, 0});
  m.add_face(std::vector<int32_t>{6, 7, 8, 9, 10, 11});
  for (int32_t k = 0; k < 6; ++k) m.add_face(std::vector<int32_t>{k, (k + 1) % 6, 6 + (k + 1) % 6, 6 + k});
  return m;
}

OpenMeshPoly read_with_openmesh(const fs::path& path) {
  OpenMeshPoly mesh;
  OpenMesh::IO::Options options; // binary or text as the file says
  EXPECT_TRUE(OpenMesh::IO::read_mesh(mesh, path.string(), options)) << path;
  return mesh;
}

std::array<float, 3> point(const OpenMeshPoly& mesh, OpenMeshPoly::VertexHandle v) {
  const auto p = mesh.point(v);
  return {p[0], p[1], p[2]};
}

std::array<float, 3> point(const PolygonMesh& mesh, int32_t v) {
  const Vec3 p = mesh.positions[size_t(v)];
  return {p.x, p.y, p.z};
}

struct Case {
  const char* extension;
  bool ascii;
};

class OpenMeshReadBack : public ::testing::TestWithParam<Case> {};

TEST_P(OpenMeshReadBack, GivesTheSameVerticesAndFaces) {
  const auto [extension, ascii] = GetParam();
  const fs::path dir = test::output_dir();
  for (const PolygonMesh& mesh : {hexagonal_prism(), torus(2000)}) {
    const fs::path path = dir / (std::string("mesh") + extension);
    write_mesh(mesh, path, {.ascii = ascii});
    const OpenMeshPoly read = read_with_openmesh(path);
    ASSERT_EQ(int64_t(read.n_vertices()), int64_t(mesh.num_vertices())) << path;
    ASSERT_EQ(int64_t(read.n_faces()), int64_t(mesh.num_faces())) << path;
    for (int32_t v = 0; v < mesh.num_vertices(); ++v)
      ASSERT_EQ(point(read, read.vertex_handle(unsigned(v))), point(mesh, v)) << path << " vertex " << v;
    for (int32_t f = 0; f < mesh.num_faces(); ++f) {
      std::vector<int32_t> corners;
      for (const auto v : read.fv_range(read.face_handle(unsigned(f)))) corners.push_back(v.idx());
      const auto expected = mesh.face(f);
      ASSERT_EQ(corners, std::vector<int32_t>(expected.begin(), expected.end())) << path << " face " << f;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, OpenMeshReadBack,
                         ::testing::Values(Case{".obj", false}, Case{".off", false}, Case{".ply", false}, Case{".ply", true}),
                         [](const ::testing::TestParamInfo<Case>& c) {
                           return test::test_name(std::string(c.param.extension + 1) + (c.param.ascii ? "_ascii" : ""));
                         });

// STL: each polygon fanned from its first corner, the triangles in order; OpenMesh merges
// corners at the same point, as the triangles' corners are.
TEST(OpenMeshReadBackStl, GivesTheSameTrianglesBinaryAndText) {
  const fs::path dir = test::output_dir();
  for (const bool ascii : {false, true})
    for (const PolygonMesh& mesh : {hexagonal_prism(), torus(2000)}) {
      const fs::path path = dir / "mesh.stl";
      write_mesh(mesh, path, {.ascii = ascii});
      const OpenMeshPoly read = read_with_openmesh(path);
      std::vector<std::array<std::array<float, 3>, 3>> expected;
      for (int32_t f = 0; f < mesh.num_faces(); ++f) {
        const auto c = mesh.face(f);
        for (size_t k = 1; k + 1 < c.size(); ++k) expected.push_back({point(mesh, c[0]), point(mesh, c[k]), point(mesh, c[k + 1])});
      }
      ASSERT_EQ(read.n_faces(), expected.size()) << "ascii " << ascii;
      EXPECT_EQ(int64_t(read.n_vertices()), int64_t(mesh.num_vertices())) << "ascii " << ascii;
      for (size_t t = 0; t < expected.size(); ++t) {
        std::vector<std::array<float, 3>> corners;
        for (const auto v : read.fv_range(read.face_handle(unsigned(t)))) corners.push_back(point(read, v));
        const std::vector<std::array<float, 3>> triangle(expected[t].begin(), expected[t].end());
        ASSERT_EQ(corners, triangle)
            << "ascii " << ascii << " triangle " << t;
      }
    }
}

} // namespace
} // namespace meander
