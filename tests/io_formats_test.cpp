// What each reader must accept: the variants of every format that real files use.
// Each test says which trap it sets.
#include "io_test_support.h"
#include "meander/error.h"
#include "meander/io.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <bit>
#include <functional>
#include <limits>

namespace meander {
namespace {

using test::big;
using test::binary_stl;
using test::little;
using test::little_floats;

PolygonMesh read_text(std::string_view file, std::string_view text) { return read_mesh(test::write_file(file, text)); }

std::vector<int32_t> faces_of(const PolygonMesh& m) { return m.face_vertices; }

// Every face form: v, v/vt, v//vn, v/vt/vn, and negative indices, which count back from
// the vertices defined so far (not from the end of the file).
TEST(IoObj, AcceptsEveryIndexForm) {
  const PolygonMesh m = read_text("forms.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
                                               "f 1 2 3\nf 1/1 2/1 3/1\nf 1//1 2//1 3//1\nf 1/1/1 2/1/1 3/1/1\n"
                                               "f -3 -2 -1\nv 1 1 0\nf -3/1 -1//1 -2/1/1\n");
  ASSERT_EQ(m.num_vertices(), 4);
  ASSERT_EQ(m.num_faces(), 6);
  EXPECT_EQ(faces_of(m), (std::vector<int32_t>{0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 1, 3, 2}));
}

// Indices are read eight bytes at a time: every digit count from 1 to 18 (by leading
// zeros), each end of a number (space, tab, CR, LF, '/', '#', the file's end) and an
// index within the last eight bytes of the file must give the same faces.
TEST(IoObj, IndicesOfEveryLengthAndEveryEnd) {
  std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n";
  std::vector<int32_t> expected;
  const char* ends[] = {" ", "\t", "/1 ", "/1/1\t", "//1 "};
  for (int digits = 1; digits <= 18; ++digits)
    for (int end = 0; end < 5; ++end) {
      text += "f";
      for (int corner = 1; corner <= 3; ++corner) {
        text += " " + std::string(digits - 1, '0') + char('0' + corner);
        text += corner == 3 ? (end % 2 ? "\r\n" : "# note\n") : ends[end];
      }
      expected.insert(expected.end(), {0, 1, 2});
    }
  text += "f 3 2 1";
  expected.insert(expected.end(), {2, 1, 0});
  EXPECT_EQ(faces_of(read_text("lengths.obj", text)), expected);
  EXPECT_EQ(faces_of(read_text("lengths_end.obj", text.substr(0, text.size() - 1) + "00000001")), expected);
}

// A byte order mark, CRLF line ends, tabs, comments after statements, a '+' sign,
// extra vertex components (w, colours), statements Meander does not use, and a stray
// line like the one beveledcube.obj ends with.
TEST(IoObj, AcceptsWhatRealFilesCarry) {
  const PolygonMesh m =
      read_text("real.obj", "\xEF\xBB\xBF# exported\r\nmtllib a.mtl\r\no thing\r\ng group\r\ns off\r\n"
                            "v\t+1 -2.5 .5 1.0 0.2 0.3 0.4\r\nv 1e-3 2E2 -0\r\nv 3 4 5 # note\r\n"
                            "vp 0.5\r\nusemtl red\r\nl 1 2\r\np 3\r\nf 1 2 3 # face\r\n1 14\r\n");
  ASSERT_EQ(m.num_vertices(), 3);
  EXPECT_EQ(m.positions[0], (Vec3{1, -2.5f, 0.5f}));
  EXPECT_EQ(m.positions[1], (Vec3{0.001f, 200, 0}));
  EXPECT_TRUE(std::signbit(m.positions[1].z));
  EXPECT_EQ(faces_of(m), (std::vector<int32_t>{0, 1, 2}));
}

// Lone CRs end lines as LF and CRLF do, also at the end of a comment or of a skipped
// statement, and a CR before a LF stays one line end.
TEST(IoObj, ReadsLoneCarriageReturnsAsLineEnds) {
  const PolygonMesh m = read_text("mac.obj", "# classic\rvt 0 0\rv 0 0 0\rv 1 0 0\r\nv 0 1 0\nv 0 0 1\r"
                                             "f 1 3 2\rf 1 2 4\r\r\nf 2 3 4\nf 3 1 4\r");
  ASSERT_EQ(m.num_vertices(), 4);
  EXPECT_EQ(m.positions[3], (Vec3{0, 0, 1}));
  EXPECT_EQ(faces_of(m), (std::vector<int32_t>{0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3}));
}

// A face may name a vertex defined further down.
TEST(IoObj, AcceptsForwardReferences) {
  const PolygonMesh m = read_text("forward.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_EQ(m.num_faces(), 1);
}

// Values below the smallest float are zero, not an error; subnormals are kept.
TEST(IoObj, UnderflowIsZeroAndSubnormalsAreKept) {
  const PolygonMesh m = read_text("tiny.obj", "v 1e-50 -1e-60 1e-40\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(m.positions[0].x, 0.0f);
  EXPECT_TRUE(std::signbit(m.positions[0].y));
  EXPECT_EQ(m.positions[0].z, 1e-40f);
}

TEST(IoObj, PolygonsOfAnySize) {
  const PolygonMesh m = read_text("heptagon.obj", "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 2 2 0\nv 1 3 0\nv 0 2 0\nv -1 1 0\n"
                                                  "f 1 2 3 4 5 6 7\nf 7 6 5\n");
  ASSERT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.face_size(0), 7);
  EXPECT_EQ(m.face_size(1), 3);
}

// Counts on the header line, no edge count, comments and blank lines anywhere, and
// colours after a face's indices.
TEST(IoOff, AcceptsCommentsColoursAndShortCounts) {
  const PolygonMesh m = read_text("loose.off", "# a comment first\nOFF 4 2\n\n0 0 0\n1 0 0 # x axis\n0 1 0\n\n1 1 0\n"
                                               "3 0 1 2 255 0 0\n# between faces\n3 1 3 2 0.5 0.5 0.5 1\n");
  ASSERT_EQ(m.num_vertices(), 4);
  EXPECT_EQ(faces_of(m), (std::vector<int32_t>{0, 1, 2, 1, 3, 2}));
}

// COFF, NOFF and STOFF put colours, normals or texture coordinates after the position.
TEST(IoOff, AcceptsColourNormalAndTextureVariants) {
  for (const char* header : {"COFF", "NOFF", "CNOFF", "STOFF", "STCNOFF"}) {
    SCOPED_TRACE(header);
    const PolygonMesh m = read_text("variant.off", std::string(header) + "\n3 1 0\n0 0 0 1 2 3 4\n1 0 0 1 2 3 4\n"
                                                                         "0 1 0 1 2 3 4\n3 0 1 2\n");
    EXPECT_EQ(m.positions[1], (Vec3{1, 0, 0}));
    EXPECT_EQ(m.num_faces(), 1);
  }
}

std::string ply_header(const std::string& format, const std::string& elements) {
  return "ply\nformat " + format + " 1.0\ncomment made by a test\n" + elements + "end_header\n";
}

// Every scalar type in every role: x, y, z of three types, extra scalars and a list on
// the vertices, ushort lengths and uint indices on faces with more properties after
// them, and elements Meander does not use before and after. Read once as big endian
// and once as little endian, through the value-by-value path.
class IoPlyLayout : public ::testing::TestWithParam<bool> {};

TEST_P(IoPlyLayout, ReadsEveryScalarTypeAndSkipsTheRest) {
  const bool big_endian = GetParam();
  const auto put = [&](auto value) { return big_endian ? big(value) : little(value); };
  const std::string header = ply_header(
      big_endian ? "binary_big_endian" : "binary_little_endian",
      "element material 2\nproperty uchar red\nproperty list uint8 float weights\n"
      "element vertex 4\nproperty char a\nproperty double x\nproperty uchar b\nproperty int16 y\nproperty ushort c\n"
      "property float32 z\nproperty int d\nproperty uint e\nproperty list short int neighbours\nproperty float64 f\n"
      "element face 2\nproperty uchar flags\nproperty list ushort uint vertex_index\nproperty list int int32 "
      "texnumber\n"
      "property int8 g\nproperty uint16 h\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\n");
  std::string body;
  for (int k = 0; k < 2; ++k) body += put(uint8_t(k)) + put(uint8_t(2)) + put(1.5f) + put(2.5f);
  const float xyz[4][3] = {{0.25f, 0, -1}, {1, 0, 0}, {1, 1, 0}, {-3, 7, 1e-3f}};
  for (int v = 0; v < 4; ++v) {
    body += put(int8_t(-v)) + put(double(xyz[v][0])) + put(uint8_t(v)) + put(int16_t(xyz[v][1])) + put(uint16_t(9));
    body += put(xyz[v][2]) + put(int32_t(-7)) + put(uint32_t(7)) + put(int16_t(v % 2));
    if (v % 2) body += put(int32_t(3));
    body += put(0.5);
  }
  body += put(uint8_t(1)) + put(uint16_t(3)) + put(uint32_t(0)) + put(uint32_t(1)) + put(uint32_t(2)) + put(int32_t(0));
  body += put(int8_t(0)) + put(uint16_t(0));
  body +=
      put(uint8_t(0)) + put(uint16_t(4)) + put(uint32_t(0)) + put(uint32_t(2)) + put(uint32_t(3)) + put(uint32_t(1));
  body += put(int32_t(2)) + put(int32_t(5)) + put(int32_t(6)) + put(int8_t(-1)) + put(uint16_t(65535));
  body += put(int32_t(0)) + put(int32_t(1));
  const PolygonMesh m = read_mesh(test::write_file("layout.ply", header + body));
  ASSERT_EQ(m.num_vertices(), 4);
  for (int v = 0; v < 4; ++v) EXPECT_EQ(m.positions[size_t(v)], (Vec3{xyz[v][0], xyz[v][1], xyz[v][2]}));
  EXPECT_EQ(m.face_start, (std::vector<int32_t>{0, 3, 7}));
  EXPECT_EQ(faces_of(m), (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 1}));
}

INSTANTIATE_TEST_SUITE_P(IoByteOrders, IoPlyLayout, ::testing::Bool(),
                         [](const auto& instance) { return instance.param ? "big_endian" : "little_endian"; });

// The fast path with x, y, z among other float properties (a stride of 24 bytes, not 12).
TEST(IoPly, ReadsFloatVerticesWithOtherProperties) {
  const std::string header = ply_header(
      "binary_little_endian", "element vertex 3\nproperty float nx\nproperty float x\nproperty uchar red\n"
                              "property float y\nproperty float z\nproperty uchar green\nproperty ushort alpha\n"
                              "element face 1\nproperty list uchar uint vertex_indices\n");
  std::string body;
  const float xyz[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.5f}};
  for (const auto& p : xyz)
    body += little(9.0f) + little(p[0]) + little(uint8_t(1)) + little_floats({p[1], p[2]}) + little(uint8_t(2)) +
            little(uint16_t(3));
  body += little(uint8_t(3)) + little(2) + little(1) + little(0);
  const PolygonMesh m = read_mesh(test::write_file("interleaved.ply", header + body));
  ASSERT_EQ(m.num_vertices(), 3);
  EXPECT_EQ(m.positions[2], (Vec3{0, 1, 0.5f}));
  EXPECT_EQ(faces_of(m), (std::vector<int32_t>{2, 1, 0}));
}

// Ascii PLY: values separated by any space (not one element per line), `vertex_index`
// for the list, lists and scalars skipped, CRLF in the header and body.
TEST(IoPly, ReadsAsciiWithExtraPropertiesAndElements) {
  const std::string text = "ply\r\nformat ascii 1.0\r\nobj_info x\r\nelement vertex 3\r\nproperty float x\r\n"
                           "property float y\r\nproperty float z\r\nproperty list uchar float uv\r\n"
                           "element face 1\r\nproperty list uchar int vertex_index\r\nproperty float quality\r\n"
                           "element edge 2\r\nproperty list uchar int ends\r\nend_header\r\n"
                           "0 0 0 2 0.5 0.5\r\n1 0 0 0\r\n0 1 -2e-3 1 nan\r\n3 0 1\r\n 2 0.75\r\n2 0 1\r\n2 1 2\r\n";
  const PolygonMesh m = read_text("ascii.ply", text);
  ASSERT_EQ(m.num_vertices(), 3);
  EXPECT_EQ(m.positions[2], (Vec3{0, 1, -2e-3f}));
  EXPECT_EQ(faces_of(m), (std::vector<int32_t>{0, 1, 2}));
}

// Triangle strips (element tristrips): -1 restarts a strip, every other triangle is wound
// backwards, and the repeated-vertex triangles strips use to join are not faces. Faces of
// a face element come first.
TEST(IoPly, ReadsTriangleStrips) {
  const std::string header =
      ply_header("binary_little_endian", "element vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
                                         "element face 1\nproperty list uchar int vertex_indices\n"
                                         "element tristrips 2\nproperty list int int vertex_indices\n");
  std::string body = little_floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0, 1, 2, 0});
  body += little(uint8_t(3)) + little(3) + little(5) + little(4);
  for (int32_t v : {6, 0, 1, 2, 3, 3, 4}) body += little(v); // (0,1,2) (2,1,3); (2,3,3) (3,3,4) joins
  for (int32_t v : {5, 2, 3, -1, 4, 5}) body += little(v);    // restart: too short for a triangle
  const PolygonMesh m = read_mesh(test::write_file("strips.ply", header + body));
  EXPECT_EQ(faces_of(m), (std::vector<int32_t>{3, 5, 4, 0, 1, 2, 2, 1, 3}));

  const std::string ascii = ply_header("ascii", "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                                                "element tristrips 1\nproperty list uchar int vertex_indices\n") +
                            "0 0 0\n1 0 0\n0 1 0\n1 1 0\n4 0 1 2 7\n";
  EXPECT_EQ(test::message_of<InputError>([&] { read_text("strip_index.ply", ascii); }),
            (test::output_dir() / "strip_index.ply").string() + ":15: tristrips 0: vertex index 7 out of range (0..3)");
}

// Binary faces all of one size are checked and copied in parallel chunks, and any other
// mix is read one face after another: both must give the faces as written, and the first
// bad face must be the one named. Enough faces that every chunk has some.
TEST(IoPly, FacesOfOneSizeOrMixedReadTheSame) {
  constexpr int32_t faces = 1000;
  const auto file = [&](const std::string& name, auto&& size_of, int32_t bad_face, int32_t bad_index) {
    std::string body = little_floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
    std::vector<int32_t> expected;
    for (int32_t f = 0; f < faces; ++f) {
      const int size = size_of(f);
      body += little(uint8_t(size));
      for (int k = 0; k < size; ++k) {
        const int32_t v = f == bad_face && k == 1 ? bad_index : (f + k) % 4;
        body += little(v);
        expected.push_back(v);
      }
    }
    const std::string header = ply_header(
        "binary_little_endian", "element vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                                    std::to_string(faces) + "\nproperty list uchar int vertex_indices\n");
    return std::pair{test::write_file(name, header + body), expected};
  };
  const auto triangles = [](int32_t) { return 3; };
  const auto quads = [](int32_t) { return 4; };
  const auto last_quad = [](int32_t f) { return f == faces - 1 ? 4 : 3; };
  const auto alternating = [](int32_t f) { return 3 + f % 2; };
  for (const auto& [name, sizes] : std::vector<std::pair<std::string, std::function<int(int32_t)>>>{
           {"triangles.ply", triangles}, {"quads.ply", quads}, {"last_quad.ply", last_quad}, {"alternating.ply", alternating}}) {
    const auto [path, expected] = file(name, sizes, -1, 0);
    const PolygonMesh m = read_mesh(path);
    ASSERT_EQ(m.num_faces(), faces) << name;
    EXPECT_EQ(faces_of(m), expected) << name;
    for (int32_t f = 0; f < faces; ++f) ASSERT_EQ(m.face_size(f), sizes(f)) << name << " face " << f;
    const auto [bad_path, unused] = file("bad_" + name, sizes, 777, 9);
    EXPECT_EQ(test::message_of<InputError>([&] { read_mesh(bad_path); }),
              bad_path.string() + ": face 777: vertex index 9 out of range (0..3)")
        << name;
  }
  // A face too small after faces of one size: the faces are read one by one, which names it.
  const auto [small_path, unused] = file("small_face.ply", [](int32_t f) { return f == 500 ? 2 : 3; }, -1, 0);
  EXPECT_EQ(test::message_of<InputError>([&] { read_mesh(small_path); }),
            small_path.string() + ": face 500: face with 2 vertices (at least 3 needed)");
}

// The face element may come before the vertex element.
TEST(IoPly, ReadsFacesBeforeVertices) {
  const std::string text =
      ply_header("ascii", "element face 1\nproperty list uchar int vertex_indices\n"
                          "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n") +
      "3 2 1 0\n0 0 0\n1 0 0\n0 1 0\n";
  const PolygonMesh m = read_text("faces_first.ply", text);
  EXPECT_EQ(faces_of(m), (std::vector<int32_t>{2, 1, 0}));
}

// Elements with no properties take no bytes, however many the header claims: skipping
// them must take no time.
TEST(IoPly, ElementsWithoutPropertiesTakeNoBytes) {
  const std::string header =
      ply_header("binary_little_endian", "element nothing 18446744073709551615\nelement vertex 3\nproperty float x\n"
                                         "property float y\nproperty float z\nelement face 1\n"
                                         "property list uchar int vertex_indices\n");
  const PolygonMesh m =
      read_mesh(test::write_file("empty_elements.ply", header + little_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}) +
                                                           little(uint8_t(3)) + little(0) + little(1) + little(2)));
  EXPECT_EQ(m.num_faces(), 1);
}

// Ascii STL: corners welded by position (-0 and +0 are one), keywords in any case,
// several solids, a facet of four vertices, names after solid and endsolid.
TEST(IoStl, AsciiWeldsCornersAcrossSolids) {
  const std::string text = "solid first part\n"
                           "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n"
                           "      vertex 0 1 0\n    endloop\n  endfacet\n"
                           "endsolid first part\n"
                           "SOLID second\nFACET NORMAL -nan -nan -nan\nOUTER LOOP\nVERTEX 1 0 0\nVERTEX 1 1 0\n"
                           "VERTEX 0 1 0\nVERTEX -0 0 -0\nENDLOOP\nENDFACET\nENDSOLID\n";
  const PolygonMesh m = read_text("parts.stl", text);
  ASSERT_EQ(m.num_vertices(), 4);
  EXPECT_EQ(m.face_start, (std::vector<int32_t>{0, 3, 7}));
  EXPECT_EQ(faces_of(m), (std::vector<int32_t>{0, 1, 2, 1, 3, 2, 0}));
}

// Many exporters begin a binary header with "solid": the size decides.
TEST(IoStl, BinaryWithASolidHeader) {
  const std::string bytes =
      binary_stl("solid this is binary, really", 2, {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 1, 1, 0, 0, 1, 0}});
  const PolygonMesh m = read_mesh(test::write_file("solid_header.stl", bytes));
  ASSERT_EQ(m.num_vertices(), 4);
  EXPECT_EQ(faces_of(m), (std::vector<int32_t>{0, 1, 2, 1, 3, 2}));
}

// Welding compares positions exactly: a position one ulp away is another vertex.
TEST(IoStl, WeldingIsExact) {
  const float next = std::nextafter(1.0f, 2.0f);
  const std::string bytes = binary_stl("", 2, {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {next, 0, 0, 1, 1, 0, 0, 1, 0}});
  EXPECT_EQ(read_mesh(test::write_file("ulp.stl", bytes)).num_vertices(), 5);
}

// The bytes in memory are the file's, for every format (the studio's downloads).
TEST(IoMemory, FileBytesAreTheFilesBytes) {
  PolygonMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.5f}, {0.5f, 0.5f, 1}};
  mesh.face_start = {0, 4, 7};
  mesh.face_vertices = {0, 1, 2, 3, 0, 3, 4};
  for (const char* name : {"m.obj", "m.ply", "m.stl", "m.off", "m.glb", "m.3mf"}) {
    const std::filesystem::path path = test::output_dir() / name;
    write_mesh(mesh, path);
    EXPECT_TRUE(mesh_file_bytes(mesh, name) == test::read_file(path)) << name;
  }
  Polylines curves{.points = mesh.positions, .start = {0, 3, 5}, .open = {false, true}};
  for (const char* name : {"c.obj", "c.ply", "c.json"}) {
    const std::filesystem::path path = test::output_dir() / name;
    write_polylines(curves, path);
    EXPECT_TRUE(polylines_file_bytes(curves, name) == test::read_file(path)) << name;
  }
  EXPECT_THROW(mesh_file_bytes(mesh, "m.gltf"), UsageError);
  EXPECT_THROW(polylines_file_bytes(curves, "c.txt"), UsageError);
  EXPECT_THROW(polylines_file_bytes(curves, "c.svg"), UsageError); // a drawing (curve_svg)
}

} // namespace
} // namespace meander
