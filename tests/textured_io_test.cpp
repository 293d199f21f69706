// Textured meshes in files: OBJ + MTL + PNG and glTF/GLB, read and written; plain GLB
// output; the Khronos validator's verdict on what we write; precise refusals.
#include "meander/error.h"
#include "meander/io.h"
#include "meander/textured_io.h"
#include "meander/shapes.h"
#include "checker_quad.h"
#include "gltf_validator.h"
#include "io_test_support.h"
#include "test_support.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <memory>

namespace meander {
namespace {

namespace fs = std::filesystem;
using test::checker_quad;
using test::message_of;
using test::output_dir;
using test::write_file;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// The position of every face corner: compares geometry whatever the vertex numbering.
std::vector<Vec3> corner_positions(const PolygonMesh& mesh) {
  std::vector<Vec3> out;
  for (int32_t v : mesh.face_vertices) out.push_back(mesh.positions[size_t(v)]);
  return out;
}

void expect_same_textured(const TexturedMesh& read, const TexturedMesh& written) {
  EXPECT_EQ(read.mesh.face_start, written.mesh.face_start);
  EXPECT_EQ(corner_positions(read.mesh), corner_positions(written.mesh));
  EXPECT_EQ(read.appearance.texcoords, written.appearance.texcoords);
  ASSERT_EQ(read.appearance.materials.size(), written.appearance.materials.size());
  for (size_t k = 0; k < read.appearance.materials.size(); ++k) {
    const Material &a = read.appearance.materials[k], &b = written.appearance.materials[k];
    EXPECT_EQ(a.base_color, b.base_color);
    EXPECT_EQ(a.texture.width, b.texture.width);
    EXPECT_EQ(a.texture.height, b.texture.height);
    EXPECT_EQ(a.texture.rgba, b.texture.rgba);
  }
}

// A quad and a pentagon sharing an edge, in the z = 0 plane.
PolygonMesh quad_and_pentagon() {
  PolygonMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2.5f, 0.5f, 0}, {2, 1, 0}};
  mesh.add_face({0, 1, 2, 3});
  mesh.add_face({1, 4, 5, 6, 2});
  return mesh;
}

// A quad split into two triangles with one material each: red (textured) and blue.
TexturedMesh two_material_quad() {
  TexturedMesh quad = checker_quad();
  quad.appearance.materials.push_back({.name = "plain blue", .base_color = {0.1f, 0.2f, 0.9f}});
  quad.appearance.face_material = {1, 0};
  return quad;
}

TEST(TexturedObj, WritesObjMtlAndPngThatReadBackTheSame) {
  const fs::path dir = output_dir();
  const TexturedMesh quad = checker_quad();
  write_textured_mesh(quad, dir / "quad.obj");
  EXPECT_TRUE(fs::exists(dir / "quad.mtl"));
  EXPECT_TRUE(fs::exists(dir / "quad_texture.png"));
  EXPECT_THAT(test::read_file(dir / "quad.mtl"), HasSubstr("map_Kd quad_texture.png\n"));
  expect_same_textured(read_textured_mesh(dir / "quad.obj"), quad);
  // Plain readers see the geometry.
  EXPECT_EQ(read_mesh(dir / "quad.obj").face_vertices, quad.mesh.face_vertices);
}

TEST(TexturedObj, AFailedFileLeavesNoneOfTheOthers) {
  // Tricky: the OBJ and the MTL are written and renamed first; the texture's rename then
  // fails (a folder holds its name), and the two already in place must go again.
  const fs::path dir = output_dir();
  fs::create_directory(dir / "quad_texture.png");
  EXPECT_THROW(write_textured_mesh(checker_quad(), dir / "quad.obj"), IOError);
  EXPECT_EQ(std::vector<fs::path>(fs::directory_iterator(dir), {}), std::vector<fs::path>{dir / "quad_texture.png"});
}

TEST(TexturedObj, KeepsOneMaterialPerFace) {
  // Tricky: the faces switch material, and one material name holds a space, which an
  // MTL cannot carry: it is written under a usable name and read back the same.
  const fs::path dir = output_dir();
  const TexturedMesh quad = two_material_quad();
  write_textured_mesh(quad, dir / "two.obj");
  const TexturedMesh read = read_textured_mesh(dir / "two.obj");
  // Materials come back in order of first use: blue first.
  ASSERT_EQ(read.appearance.materials.size(), 2u);
  EXPECT_EQ(read.appearance.materials[0].name, "material_1");
  EXPECT_EQ(read.appearance.materials[0].base_color, quad.appearance.materials[1].base_color);
  EXPECT_EQ(read.appearance.materials[1].texture.rgba, quad.appearance.materials[0].texture.rgba);
  EXPECT_EQ(read.appearance.face_material, (std::vector<int32_t>{0, 1}));
}

TEST(TexturedObj, WithoutMtllibIsAPlainMesh) {
  output_dir();
  const fs::path obj = write_file("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl red\nf 1/1 2/2 3/3\n");
  const TexturedMesh read = read_textured_mesh(obj);
  EXPECT_TRUE(read.appearance.materials.empty());
  EXPECT_TRUE(read.appearance.texcoords.empty());
  EXPECT_EQ(read.mesh.num_faces(), 1);
}

TEST(TexturedObj, FacesBeforeUsemtlGetTheDefaultMaterialAndKdAloneNeedsNoVt) {
  output_dir();
  write_file("m.mtl", "newmtl red\nKd 0.9 0.1 0.1\n");
  const fs::path obj = write_file("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nusemtl red\nf 2 4 3\n");
  const Appearance a = read_textured_mesh(obj).appearance;
  ASSERT_EQ(a.materials.size(), 2u);
  EXPECT_EQ(a.materials[0].name, "red");
  EXPECT_EQ(a.materials[0].base_color, (LinearRgb{0.9f, 0.1f, 0.1f}));
  EXPECT_EQ(a.materials[1].name, "default");
  EXPECT_EQ(a.face_material, (std::vector<int32_t>{1, 0}));
  EXPECT_TRUE(a.texcoords.empty());
}

TEST(TexturedObj, MapKdOptionsAndFileNamesWithSpacesAreRead) {
  const fs::path dir = output_dir();
  write_textured_mesh(checker_quad(), dir / "quad.obj");
  fs::rename(dir / "quad_texture.png", dir / "my texture.png");
  write_file("quad.mtl", "newmtl checker\nKd 1 1 1\nmap_Kd -s 1 1 1 -clamp off my texture.png\n");
  expect_same_textured(read_textured_mesh(dir / "quad.obj"), checker_quad());
}

// Each refusal names the file and line at fault and says what is wrong.
class TexturedObjRefuses : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = output_dir();
    write_textured_mesh(checker_quad(), dir_ / "quad.obj");
  }
  std::string error_of(std::string_view obj_text) {
    const fs::path obj = write_file("bad.obj", obj_text);
    try {
      read_textured_mesh(obj);
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "no exception";
    return {};
  }
  fs::path dir_;
};

TEST_F(TexturedObjRefuses, AMissingMtllibTarget) {
  EXPECT_EQ(message_of<IOError>([&] { read_textured_mesh(write_file("bad.obj", "v 0 0 0\nmtllib gone.mtl\n")); }),
            (dir_ / "bad.obj").string() + ":2: mtllib 'gone.mtl': " + (dir_ / "gone.mtl").string() +
                ": cannot open: No such file or directory");
}

TEST_F(TexturedObjRefuses, AMalformedMtl) {
  write_file("bad.mtl", "newmtl red\nKd red 0 0\n");
  EXPECT_EQ(message_of<InputError>([&] { read_textured_mesh(write_file("bad.obj", "mtllib bad.mtl\n")); }),
            (dir_ / "bad.obj").string() + ":1: mtllib 'bad.mtl': " + (dir_ / "bad.mtl").string() + ":2: bad Kd value 'red'");
  write_file("bad.mtl", "Kd 1 1 1\n");
  EXPECT_THAT(error_of("mtllib bad.mtl\n"), HasSubstr("bad.mtl:1: Kd before any newmtl"));
  write_file("bad.mtl", "newmtl t\nmap_Kd -q 3 t.png\n");
  EXPECT_THAT(error_of("mtllib bad.mtl\n"), HasSubstr("bad.mtl:2: map_Kd: unknown option '-q'"));
}

TEST_F(TexturedObjRefuses, AMissingTexture) {
  write_file("bad.mtl", "newmtl t\nKd 1 1 1\nmap_Kd gone.png\n");
  const std::string obj = "mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl t\nf 1/1 2/1 3/1\n";
  EXPECT_EQ(error_of(obj), (dir_ / "bad.mtl").string() + ":3: map_Kd 'gone.png': " + (dir_ / "gone.png").string() +
                               ": cannot open: No such file or directory");
}

TEST_F(TexturedObjRefuses, AnImageThatDoesNotDecode) {
  write_file("broken.png", "\x89PNG\r\n\x1a\n not really");
  write_file("bad.mtl", "newmtl t\nmap_Kd broken.png\n");
  const std::string obj = "mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl t\nf 1/1 2/1 3/1\n";
  EXPECT_THAT(error_of(obj), StartsWith((dir_ / "bad.mtl").string() + ":2: map_Kd 'broken.png': " +
                                        (dir_ / "broken.png").string() + ": cannot decode image: "));
}

TEST_F(TexturedObjRefuses, TextureCoordinateIndicesOutOfRange) {
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/7\n"),
            (dir_ / "bad.obj").string() + ":5: face references texture coordinate 7 but only 1 exist");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/-2 3/1\n"),
            (dir_ / "bad.obj").string() + ":5: face references texture coordinate -2 but only 1 exist");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3\n"),
            (dir_ / "bad.obj").string() + ":5: face gives texture coordinates for some corners only");
}

TEST_F(TexturedObjRefuses, AnUnknownMaterialAndATextureWithoutCoordinates) {
  EXPECT_EQ(error_of("mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl nope\nf 1 2 3\n"),
            (dir_ / "bad.obj").string() + ":5: usemtl 'nope': no material of that name in the mtllib files");
  EXPECT_EQ(error_of("mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl checker\nf 1 2 3\n"),
            (dir_ / "bad.obj").string() +
                ":6: face without texture coordinates (vt) uses material 'checker', which has a texture (map_Kd)");
}

TEST(TexturedGlb, WritesOneFileThatReadsBackTheSame) {
  const fs::path dir = output_dir();
  const TexturedMesh quad = checker_quad();
  write_textured_mesh(quad, dir / "quad.glb");
  EXPECT_EQ(std::vector<fs::path>(fs::directory_iterator(dir), {}), std::vector<fs::path>{dir / "quad.glb"});
  expect_same_textured(read_textured_mesh(dir / "quad.glb"), quad);
  // Deterministic: the same mesh gives the same bytes.
  write_textured_mesh(quad, dir / "again.glb");
  EXPECT_EQ(test::read_file(dir / "again.glb"), test::read_file(dir / "quad.glb"));
}

TEST(TexturedGlb, KeepsOneMaterialPerFace) {
  const fs::path dir = output_dir();
  write_textured_mesh(two_material_quad(), dir / "two.glb");
  const TexturedMesh read = read_textured_mesh(dir / "two.glb");
  ASSERT_EQ(read.appearance.materials.size(), 2u);
  // One primitive per material, in material order: the textured face comes first.
  EXPECT_FALSE(read.appearance.materials[0].texture.empty());
  EXPECT_EQ(read.appearance.materials[1].base_color, (LinearRgb{0.1f, 0.2f, 0.9f}));
  EXPECT_EQ(read.appearance.face_material, (std::vector<int32_t>{0, 1}));
  EXPECT_EQ(read.mesh.num_vertices(), 4); // welded again across the two primitives
}

TEST(Glb, PlainMeshRoundTripsThroughReadMesh) {
  const fs::path dir = output_dir();
  // Polygons are written as triangle fans.
  PolygonMesh mesh = quad_and_pentagon();
  mesh.positions.push_back({5, 5, 5});
  write_mesh(mesh, dir / "grid.glb");
  const PolygonMesh read = read_mesh(dir / "grid.glb");
  int32_t triangles = 0;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) triangles += mesh.face_size(f) - 2;
  EXPECT_EQ(read.num_faces(), triangles);
  // The unused vertex is written but no face brings it back.
  EXPECT_EQ(read.num_vertices(), mesh.num_vertices() - 1);
  EXPECT_EQ(read_textured_mesh(dir / "grid.glb").appearance.materials.size(), 1u);
}

TEST(Glb, GltfIsNotWrittenAndTexturedWritersRefuseOtherFormats) {
  const fs::path dir = output_dir();
  EXPECT_THAT(message_of<UsageError>([&] { write_mesh(grid(8), dir / "a.gltf"); }),
              HasSubstr("writing .gltf is not supported"));
  EXPECT_THAT(message_of<UsageError>([&] { write_textured_mesh(checker_quad(), dir / "a.ply"); }),
              HasSubstr("unknown textured mesh format '.ply' (expected .obj or .glb)"));
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Gltf, NodeTransformsApplyAndAMirrorReversesTheWinding) {
  output_dir();
  // One triangle (0,0,0) (1,0,0) (0,1,0) in a data: URI, under a node that moves it by
  // +10 in x and mirrors x: the face must keep facing +z after the mirror.
  const fs::path path = write_file("mirror.gltf", R"({
    "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"translation": [10, 0, 0], "children": [1]}, {"scale": [-1, 1, 1], "mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]
  })");
  const PolygonMesh mesh = read_mesh(path);
  ASSERT_EQ(mesh.num_faces(), 1);
  const std::vector<Vec3> corners = corner_positions(mesh);
  EXPECT_EQ(corners, (std::vector<Vec3>{{10, 0, 0}, {10, 1, 0}, {9, 0, 0}}));
  EXPECT_GT(cross(corners[1] - corners[0], corners[2] - corners[0]).z, 0);
}

TEST(Gltf, RefusesMalformedFilesWithTheFileName) {
  const fs::path dir = output_dir();
  write_mesh(grid(8), dir / "good.glb");
  const std::string bytes = test::read_file(dir / "good.glb");
  const fs::path truncated = write_file("truncated.glb", bytes.substr(0, bytes.size() - 40));
  EXPECT_THAT(message_of<InputError>([&] { read_mesh(truncated); }), StartsWith(truncated.string() + ": "));
  const fs::path text = write_file("text.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [");
  EXPECT_THAT(message_of<InputError>([&] { read_mesh(text); }), StartsWith(text.string() + ": "));
  // Valid JSON whose accessor reaches past its buffer view: caught by Meander's checks.
  const fs::path past = write_file("past.gltf", R"({
    "asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "accessors": [{"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 3, "type": "VEC3"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]
  })");
  EXPECT_EQ(message_of<InputError>([&] { read_mesh(past); }),
            past.string() + ": mesh 0 primitive 0: POSITION: accessor 0: reaches past the end of its buffer view");
}

// A buffer whose URI names a folder (a fuzzer's find): tinygltf's own reader took the
// folder's stream for 2^63 bytes and asked for that much memory.
TEST(Gltf, BufferUriNamingAFolderIsRefused) {
  output_dir();
  for (const char* uri : {"../", ".", "missing.bin"}) {
    const fs::path path = write_file("folder_buffer.gltf", std::string(R"({
      "asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "buffers": [{"byteLength": 36, "uri": ")") + uri + R"("}]
    })");
    const std::string message = message_of<InputError>([&] { read_mesh(path); });
    EXPECT_THAT(message, StartsWith(path.string() + ": ")) << uri;
    EXPECT_THAT(message, HasSubstr(std::string(uri) == "missing.bin" ? "not found" : "not a regular file")) << message;
  }
}

TEST(Glb, KhronosValidatorFindsNoErrorsOrWarnings) {
  MEANDER_REQUIRE(test::gltf_validator_installed(),
                  "glTF validator not installed: run `npm ci` in tests/ (make test does) with node on the PATH");
  const fs::path dir = output_dir();
  PolygonMesh with_unused_vertex = torus(400);
  with_unused_vertex.positions.push_back({3, 3, 3});
  write_mesh(with_unused_vertex, dir / "torus.glb");
  write_mesh(quad_and_pentagon(), dir / "grid_no_normals.glb", {.normals = false});
  write_textured_mesh(checker_quad(), dir / "quad.glb");
  write_textured_mesh(two_material_quad(), dir / "two.glb");
  for (const char* name : {"torus.glb", "grid_no_normals.glb", "quad.glb", "two.glb"}) {
    const nlohmann::json report = test::gltf_validator_report(dir / name);
    ASSERT_TRUE(report.is_object()) << name;
    EXPECT_EQ(report["numErrors"], 0) << name << ": " << report["messages"].dump(1);
    EXPECT_EQ(report["numWarnings"], 0) << name << ": " << report["messages"].dump(1);
  }
}

} // namespace
} // namespace meander

namespace meander {
namespace {

// An uncompressed image whose header claims more pixels than its file holds is refused
// before any pixel memory is taken (a 32-byte TGA claiming 15360 x 15360 pixels took
// 1.6 GB, found by fuzz_image); the same header with its pixels is read.
TEST(Image, AHeaderClaimingMorePixelsThanTheFileHoldsIsRefused) {
  const auto tga = [](uint16_t width, uint16_t height, size_t pixel_bytes) {
    std::string bytes(18, '\0');
    bytes[2] = 2; // uncompressed true colour
    bytes[12] = char(width & 0xff), bytes[13] = char(width >> 8), bytes[14] = char(height & 0xff), bytes[15] = char(height >> 8);
    bytes[16] = 24;
    return bytes + std::string(pixel_bytes, '\x7f');
  };
  EXPECT_THAT(test::message_of<InputError>([&] { read_texture(tga(15360, 15360, 14), "big.tga"); }),
              testing::HasSubstr("big.tga: cannot decode image: 15360x15360 pixels claimed by a file of 32 bytes"));
  const Texture small = read_texture(tga(2, 3, 18), "small.tga");
  EXPECT_EQ(small.width, 2);
  EXPECT_EQ(small.height, 3);
  EXPECT_THROW(read_texture("P6\n4000 4000\n255\n" + std::string(64, '\0'), "big.ppm"), InputError);
  // A PNM number stb_image would overflow (found by fuzz_image); a small PNM is read.
  EXPECT_THAT(test::message_of<InputError>([] { read_texture("P6 5555555555 1 255\n", "huge.ppm"); }),
              testing::HasSubstr("huge.ppm: cannot decode image: a number of the PNM header has more than 9 digits"));
  EXPECT_EQ(read_texture("P6 # two pixels\n2 1 255\n" + std::string(6, '\x40'), "small.ppm").width, 2);
  // 16-bit samples, which stb_image converts past its buffer (found by fuzz_image).
  EXPECT_THAT(test::message_of<InputError>([] { read_texture("P6 2 1 876\n" + std::string(12, 'c'), "deep.ppm"); }),
              testing::HasSubstr("deep.ppm: cannot decode image: 16-bit PNM samples are not supported"));
}

// An empty IDAT chunk holds nothing: the picture reads as without it (stb_image copied
// one from a null buffer when it came first, found by fuzz_image).
TEST(Image, EmptyPngDataChunksAreSkipped) {
  const Image image{.width = 2, .height = 2, .has_alpha = true, .rgba = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16}};
  std::string png = png_file_bytes(image);
  const size_t idat = png.find("IDAT") - 4;
  png.insert(idat, std::string("\0\0\0\0IDAT\0\0\0\0", 12));
  EXPECT_EQ(read_texture(png, "empty_idat.png").rgba, image.rgba);
  // A chunk cut short by the file's end is refused before stb_image allocates the length
  // it claims (1 GB for a 43-byte file, found by fuzz_image).
  const size_t data = png.find("IDAT", idat + 12) + 4;
  EXPECT_THAT(test::message_of<InputError>([&] { read_texture(png.substr(0, data + 2), "cut.png"); }),
              testing::HasSubstr("cut.png: cannot decode image: a PNG chunk is longer than the file"));
}

} // namespace
} // namespace meander
