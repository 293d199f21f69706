// The 3MF writer, read back with lib3mf's own reader (an independent path: Meander only
// writes 3MF).
#include "meander/error.h"
#include "meander/io.h"
#include "meander/shapes.h"
#include "test_support.h"

#include <Model/COM/NMR_DLLInterfaces.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

namespace meander {
namespace {

struct Read3mf {
  int mesh_objects = 0;
  std::vector<NMR::MODELMESHVERTEX> vertices;     // of the first mesh object
  std::vector<NMR::MODELMESHTRIANGLE> triangles;  // of the first mesh object
};

Read3mf read_back(const std::filesystem::path& path) {
  Read3mf result;
  NMR::PLib3MFModel* model = nullptr;
  NMR::PLib3MFModelReader* reader = nullptr;
  NMR::PLib3MFModelResourceIterator* objects = nullptr;
  EXPECT_EQ(NMR::lib3mf_createmodel(&model), LIB3MF_OK);
  EXPECT_EQ(NMR::lib3mf_model_queryreader(model, "3mf", &reader), LIB3MF_OK);
  EXPECT_EQ(NMR::lib3mf_reader_readfromfileutf8(reader, path.c_str()), LIB3MF_OK);
  EXPECT_EQ(NMR::lib3mf_model_getmeshobjects(model, &objects), LIB3MF_OK);
  BOOL more = false;
  while (NMR::lib3mf_resourceiterator_movenext(objects, &more) == LIB3MF_OK && more) {
    NMR::PLib3MFModelResource* object = nullptr;
    NMR::lib3mf_resourceiterator_getcurrent(objects, &object);
    if (result.mesh_objects++ == 0) {
      DWORD vertices = 0, triangles = 0;
      NMR::lib3mf_meshobject_getvertexcount(object, &vertices);
      NMR::lib3mf_meshobject_gettrianglecount(object, &triangles);
      result.vertices.resize(vertices);
      result.triangles.resize(triangles);
      NMR::lib3mf_meshobject_getvertices(object, result.vertices.data(), vertices, nullptr);
      NMR::lib3mf_meshobject_gettriangleindices(object, result.triangles.data(), triangles, nullptr);
    }
    NMR::lib3mf_release(object);
  }
  NMR::lib3mf_release(objects);
  NMR::lib3mf_release(reader);
  NMR::lib3mf_release(model);
  return result;
}

TEST(ThreeMf, TrianglesReadBackAsWritten) {
  const PolygonMesh mesh = torus(3000);
  const std::filesystem::path path = test::output_dir() / "torus.3mf";
  write_mesh(mesh, path);
  const Read3mf back = read_back(path);
  EXPECT_EQ(back.mesh_objects, 1);
  ASSERT_EQ(back.vertices.size(), size_t(mesh.num_vertices()));
  ASSERT_EQ(back.triangles.size(), size_t(mesh.num_faces()));
  for (size_t v = 0; v < back.vertices.size(); ++v) {
    const Vec3 p = mesh.positions[v];
    // lib3mf writes 6 decimals: a micrometre when the unit is the millimetre.
    ASSERT_NEAR(back.vertices[v].m_fPosition[0], p.x, 1e-6) << "vertex " << v;
    ASSERT_NEAR(back.vertices[v].m_fPosition[1], p.y, 1e-6) << "vertex " << v;
    ASSERT_NEAR(back.vertices[v].m_fPosition[2], p.z, 1e-6) << "vertex " << v;
  }
  for (size_t t = 0; t < back.triangles.size(); ++t)
    for (size_t k = 0; k < 3; ++k) ASSERT_EQ(int32_t(back.triangles[t].m_nIndices[k]), mesh.face(int32_t(t))[k]);
}

// lib3mf would give each object a random UUID; Meander's are made from the mesh.
TEST(ThreeMf, SameMeshSameBytes) {
  const std::filesystem::path dir = test::output_dir();
  write_mesh(sphere(500), dir / "a.3mf");
  write_mesh(sphere(500), dir / "b.3mf");
  write_mesh(sphere(600), dir / "c.3mf");
  EXPECT_EQ(test::read_file(dir / "a.3mf"), test::read_file(dir / "b.3mf"));
  EXPECT_NE(test::read_file(dir / "a.3mf"), test::read_file(dir / "c.3mf"));
}

// Polygons are fanned from their first vertex; a fan triangle that repeats a vertex (3MF
// forbids it) is left out.
TEST(ThreeMf, PolygonsAreFanned) {
  PolygonMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 2, 0}};
  mesh.add_face({0, 1, 2, 4, 3}); // a pentagon: 3 triangles
  mesh.add_face({0, 3, 3, 4});    // repeats vertex 3: one of its 2 triangles is kept
  const std::filesystem::path path = test::output_dir() / "fan.3mf";
  write_mesh(mesh, path);
  const Read3mf back = read_back(path);
  ASSERT_EQ(back.triangles.size(), 4u);
  EXPECT_EQ(back.triangles[2].m_nIndices[0], 0u);
  EXPECT_EQ(back.triangles[2].m_nIndices[1], 4u);
  EXPECT_EQ(back.triangles[2].m_nIndices[2], 3u);
  EXPECT_EQ(back.triangles[3].m_nIndices[1], 3u);
  EXPECT_EQ(back.triangles[3].m_nIndices[2], 4u);
}

TEST(ThreeMf, NoFileIsLeftWhenTheFolderIsMissing) {
  const std::filesystem::path dir = test::output_dir();
  EXPECT_THROW(write_mesh(sphere(100), dir / "missing" / "x.3mf"), IOError);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(ThreeMf, IsWrittenNotRead) {
  const std::filesystem::path path = test::output_dir() / "sphere.3mf";
  write_mesh(sphere(100), path);
  EXPECT_THROW(read_mesh(path), UsageError);
}

} // namespace
} // namespace meander
