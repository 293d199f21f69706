// Every refusal of the readers, one malformed file each, with the exact message: the
// path as given, then the line (text) or the element (binary), then what is wrong.
#include "io_test_support.h"
#include "meander/error.h"
#include "meander/io.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace meander {
namespace {

using test::big;
using test::binary_stl;
using test::little;
using test::little_floats;

struct Malformed {
  std::string file; // its extension picks the reader
  std::string bytes;
  std::string message; // after the path
};

void PrintTo(const Malformed& c, std::ostream* out) { *out << c.file; }

// Pretty test names: "obj_bad_coordinate" for "bad_coordinate.obj".
std::string case_name(const ::testing::TestParamInfo<Malformed>& info) {
  const std::string& file = info.param.file;
  const size_t dot = file.rfind('.');
  return file.substr(dot + 1) + "_" + file.substr(0, dot);
}

class IoMalformed : public ::testing::TestWithParam<Malformed> {};

TEST_P(IoMalformed, IsRefusedWithAnExactMessage) {
  const Malformed& c = GetParam();
  const std::filesystem::path path = test::write_file(c.file, c.bytes);
  EXPECT_EQ(test::message_of<InputError>([&] { read_mesh(path); }), path.string() + c.message);
}

const std::string three_vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

INSTANTIATE_TEST_SUITE_P(
    IoObj, IoMalformed,
    ::testing::Values(
        Malformed{"empty.obj", "", ": file is empty"},
        Malformed{"bad_coordinate.obj", three_vertices + "v abc 0 0\nf 1 2 3\n", ":4: bad vertex coordinate 'abc'"},
        Malformed{"coordinate_suffix.obj", "v 1.5e 0 0\n", ":1: bad vertex coordinate '1.5e'"},
        Malformed{"missing_coordinate.obj", "v 1 2\n", ":1: missing vertex coordinate"},
        Malformed{"nan.obj", "v nan 0 0\n", ":1: non-finite vertex coordinate 'nan'"},
        Malformed{"infinity.obj", "v 0 -inf 0\n", ":1: non-finite vertex coordinate '-inf'"},
        // Finite as text, but beyond the largest float.
        Malformed{"overflow.obj", "v 0 0 1e39\n", ":1: non-finite vertex coordinate '1e39'"},
        // The line is counted right through a byte order mark and CRLF line ends.
        Malformed{"nan_after_bom_and_crlf.obj", "\xEF\xBB\xBFv 0 0 0\r\nv 0 nan 0\r\n",
                  ":2: non-finite vertex coordinate 'nan'"},
        // ... and through lone CRs (classic Mac OS), a comment ending at one, and a mix.
        Malformed{"nan_after_lone_cr.obj", "v 0 0 0\r# note\rv 1 0 0\r\nv 0 1 0\nv 0 nan 0\r",
                  ":5: non-finite vertex coordinate 'nan'"},
        Malformed{"index_zero.obj", three_vertices + "f 0 1 2\n",
                  ":4: vertex index 0 is invalid (OBJ indices start at 1)"},
        Malformed{"index_too_high.obj", three_vertices + "f 1 2 9\n", ":4: face references vertex 9 but only 3 exist"},
        Malformed{"index_too_negative.obj", three_vertices + "f -1 -2 -4\n",
                  ":4: face references vertex -4 but only 3 exist"},
        Malformed{"index_huge.obj", three_vertices + "f 1 2 99999999999\n",
                  ":4: face references vertex 99999999999 but only 3 exist"},
        Malformed{"index_too_long.obj", three_vertices + "f 1 2 1234567890123456789\n",
                  ":4: bad vertex index '1234567890123456789'"},
        Malformed{"index_letters.obj", three_vertices + "f 1 2 x\n", ":4: bad vertex index 'x'"},
        Malformed{"index_suffix.obj", three_vertices + "f 1 2 3x\n", ":4: bad vertex index '3x'"},
        Malformed{"index_suffix_long.obj", three_vertices + "f 1 2 0000003x 1\n", ":4: bad vertex index '0000003x'"},
        Malformed{"two_vertices.obj", three_vertices + "f 1 2\n", ":4: face with 2 vertices (at least 3 needed)"},
        // Positive indices may point forward, so they are checked at the end, where the
        // largest one is reported on its line.
        Malformed{"forward_index_missing.obj", "f 1 2 3\nv 0 0 0\nf 1 7 3\nv 1 0 0\n",
                  ":3: face references vertex 7 but only 2 exist"},
        Malformed{"no_faces.obj", three_vertices, ": no faces"},
        Malformed{"comments_only.obj", "# nothing here\n", ": no faces"},
        Malformed{"text.obj", "hello world\nthis is not a mesh\n", ": no faces"},
        Malformed{"binary.obj", std::string("\x01\x02\x00\xff\x7f garbage\n", 13), ": no faces"}),
    case_name);

const std::string three_off_vertices = "0 0 0\n1 0 0\n0 1 0\n";

INSTANTIATE_TEST_SUITE_P(
    IoOff, IoMalformed,
    ::testing::Values(
        Malformed{"empty.off", "", ": file is empty"},
        Malformed{"ply_content.off", "ply\nformat ascii 1.0\n", ":1: not an OFF file (expected 'OFF', found 'ply')"},
        Malformed{"no_header.off", "\n\n# only a comment\n", ":3: not an OFF file (no header)"},
        Malformed{"four_dimensional.off", "4OFF\n1 1 0\n", ":1: unsupported OFF variant '4OFF' (only [ST][C][N]OFF)"},
        Malformed{"n_dimensional.off", "nOFF\n4\n", ":1: unsupported OFF variant 'nOFF' (only [ST][C][N]OFF)"},
        Malformed{"binary.off", "OFF BINARY\n", ":1: binary OFF is not supported"},
        Malformed{"missing_counts.off", "OFF\n", ":1: missing vertex count"},
        Malformed{"bad_count.off", "OFF\nfour 1 0\n", ":2: bad vertex count 'four'"},
        Malformed{"negative_count.off", "OFF\n-1 1 0\n", ":2: negative vertex count"},
        // Refused from the header alone, before anything is allocated.
        Malformed{"huge_count.off", "OFF\n1000000000000 1 0\n0 0 0\n",
                  ":2: too many vertices (1000000000000; at most 2147483647)"},
        // Within int32 but not in the file: the reservation is bounded by the bytes left.
        Malformed{"large_claim.off", "OFF\n2000000000 1 0\n0 0 0\n",
                  ":3: expected 2000000000 vertices but the file ends after 1"},
        Malformed{"truncated_vertices.off", "OFF\n8 6 0\n" + three_off_vertices + "1 1 0\n0 0 1\n",
                  ":7: expected 8 vertices but the file ends after 5"},
        Malformed{"nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", ":4: non-finite vertex coordinate 'nan'"},
        Malformed{"index_too_high.off", "OFF\n3 1 0\n" + three_off_vertices + "3 0 1 3\n",
                  ":6: vertex index 3 out of range (0..2)"},
        Malformed{"index_negative.off", "OFF\n3 1 0\n" + three_off_vertices + "3 0 -1 2\n",
                  ":6: vertex index -1 out of range (0..2)"},
        Malformed{"two_vertices.off", "OFF\n3 1 0\n" + three_off_vertices + "2 0 1\n",
                  ":6: face with 2 vertices (at least 3 needed)"},
        Malformed{"short_face.off", "OFF\n3 1 0\n" + three_off_vertices + "3 0 1\n", ":6: missing vertex index"},
        Malformed{"truncated_faces.off", "OFF\n3 2 0\n" + three_off_vertices + "3 0 1 2\n",
                  ":6: expected 2 faces but the file ends after 1"},
        Malformed{"trailing_text.off", "OFF\n3 1 0\n" + three_off_vertices + "3 0 1 2\nextra\n",
                  ":7: unexpected 'extra' after the last face"},
        Malformed{"no_faces.off", "OFF\n3 0 0\n" + three_off_vertices, ": no faces"}),
    case_name);

std::string ply_header(const std::string& format, const std::string& elements) {
  return "ply\nformat " + format + " 1.0\n" + elements + "end_header\n";
}

const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
const std::string face_list = "element face 1\nproperty list uchar int vertex_indices\n";
const std::string le_vertices = little_floats({0, 0, 0, 1, 0, 0, 0, 1, 0});

// Three vertices and `face_count` faces of uchar length and `index_type` indices, binary
// little endian; `faces` is the bytes after the vertices.
std::string le_triangles(int face_count, const std::string& faces, const std::string& index_type = "int",
                         const std::string& vertices = le_vertices) {
  return ply_header("binary_little_endian", "element vertex 3\n" + xyz + "element face " + std::to_string(face_count) +
                                                "\nproperty list uchar " + index_type + " vertex_indices\n") +
         vertices + faces;
}

std::string le_face(uint8_t size, std::initializer_list<int32_t> indices) {
  std::string bytes = little(size);
  for (int32_t i : indices) bytes += little(i);
  return bytes;
}

std::string ascii_triangle(const std::string& body, int face_count = 1) {
  return ply_header("ascii", "element vertex 3\n" + xyz + "element face " + std::to_string(face_count) +
                                 "\nproperty list uchar int vertex_indices\n") +
         body;
}

const std::string ascii_vertices = "0 0 0\n1 0 0\n0 1 0\n"; // lines 10 to 12 of ascii_triangle

const std::string be_header = ply_header(
    "binary_big_endian", "element vertex 3\n" + xyz + "element face 1\nproperty list uchar int vertex_indices\n");

std::string be_floats(std::initializer_list<float> values) {
  std::string bytes;
  for (float v : values) bytes += big(v);
  return bytes;
}

INSTANTIATE_TEST_SUITE_P(
    IoPly, IoMalformed,
    ::testing::Values(
        Malformed{"empty.ply", "", ": file is empty"},
        Malformed{"not_ply.ply", "plx\nformat ascii 1.0\n", ": not a PLY file (it does not start with 'ply')"},
        Malformed{"off_content.ply", "OFF\n3 1 0\n", ": not a PLY file (it does not start with 'ply')"},
        Malformed{"middle_endian.ply", ply_header("binary_middle_endian", ""),
                  ": header: unknown format 'binary_middle_endian'"},
        Malformed{"version.ply", "ply\nformat ascii 2.0\nend_header\n", ": header: unsupported PLY version '2.0'"},
        Malformed{"no_end_header.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", ": header: no end_header line"},
        Malformed{"no_format.ply", "ply\nelement vertex 0\nend_header\n", ": header: no format line"},
        Malformed{"unknown_line.ply", ply_header("ascii", "foo bar\n"), ": header: unknown line 'foo bar'"},
        Malformed{"unknown_type.ply", ply_header("ascii", "element vertex 1\nproperty int128 x\n"),
                  ": header: unknown property type 'int128'"},
        Malformed{"property_first.ply", ply_header("ascii", "property float x\n"),
                  ": header: property before any element"},
        Malformed{"bad_count.ply", ply_header("ascii", "element vertex -1\n"), ": header: bad element count '-1'"},
        Malformed{"float_length.ply", ply_header("ascii", "element face 1\nproperty list float int vertex_indices\n"),
                  ": header: list length type 'float' is not an integer type"},
        Malformed{"no_vertex_element.ply",
                  ply_header("ascii", "element face 0\nproperty list uchar int vertex_indices\n"),
                  ": header: no vertex element"},
        Malformed{"two_vertex_elements.ply",
                  ply_header("ascii", "element vertex 0\n" + xyz + "element vertex 0\n" + xyz),
                  ": header: two vertex elements"},
        Malformed{"no_z.ply", ply_header("ascii", "element vertex 0\nproperty float x\nproperty float y\n"),
                  ": header: element vertex has no property z"},
        Malformed{
            "x_list.ply",
            ply_header("ascii", "element vertex 0\nproperty list uchar float x\nproperty float y\nproperty float z\n"),
            ": header: property x of element vertex is a list"},
        Malformed{"no_face_element.ply", ply_header("ascii", "element vertex 0\n" + xyz), ": no faces"},
        Malformed{"no_index_list.ply",
                  ply_header("ascii", "element vertex 0\n" + xyz + "element face 0\nproperty list uchar int corners\n"),
                  ": header: element face has no vertex_indices list"},
        Malformed{"float_indices.ply",
                  ply_header("ascii",
                             "element vertex 0\n" + xyz + "element face 0\nproperty list uchar float vertex_indices\n"),
                  ": header: vertex_indices must be a list of integers"},
        // Refused from the header alone, before anything is allocated.
        Malformed{"huge_count.ply",
                  ply_header("binary_little_endian", "element vertex 1000000000000\n" + xyz + face_list) + "junk",
                  ": header: too many vertices (1000000000000; at most 2147483647)"},
        Malformed{"large_claim.ply",
                  ply_header("binary_little_endian", "element vertex 2000000000\n" + xyz + face_list) +
                      little_floats({0, 0, 0}),
                  ": vertex 1: file ends early (the header claims 2000000000 vertices)"},
        Malformed{"truncated_faces.ply", le_triangles(2, le_face(3, {0, 1, 2})),
                  ": face 1: file ends early (the header claims 2 faces)"},
        Malformed{"face_cut_short.ply", le_triangles(1, le_face(3, {0, 1})),
                  ": face 0: file ends early (the header claims 1 face)"},
        Malformed{"index_negative.ply", le_triangles(1, le_face(3, {0, 1, -3})),
                  ": face 0: vertex index -3 out of range (0..2)"},
        Malformed{"index_in_second_face.ply", le_triangles(2, le_face(3, {0, 1, 2}) + le_face(3, {2, 1, 7})),
                  ": face 1: vertex index 7 out of range (0..2)"},
        // Unsigned indices above INT32_MAX are reported as written, not wrapped.
        Malformed{"index_uint.ply", le_triangles(1, le_face(3, {0, 1, -1}), "uint"),
                  ": face 0: vertex index 4294967295 out of range (0..2)"},
        Malformed{"two_vertex_face.ply", le_triangles(1, le_face(2, {0, 1})),
                  ": face 0: face with 2 vertices (at least 3 needed)"},
        // The same through the value-by-value path (ushort lengths).
        Malformed{"two_vertex_face_ushort.ply",
                  ply_header("binary_little_endian",
                             "element vertex 3\n" + xyz + "element face 1\nproperty list ushort int vertex_indices\n") +
                      le_vertices + little(uint16_t(2)) + little(0) + little(1),
                  ": face 0: face with 2 vertices (at least 3 needed)"},
        Malformed{"big_endian_index.ply",
                  be_header + be_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}) + little(uint8_t(3)) + big(0) + big(1) + big(7),
                  ": face 0: vertex index 7 out of range (0..2)"},
        Malformed{"big_endian_truncated.ply", be_header + be_floats({0, 0, 0, 1, 0, 0}),
                  ": vertex 2: file ends early (the header claims 3 vertices)"},
        Malformed{"nan.ply",
                  le_triangles(1, le_face(3, {0, 1, 2}), "int",
                               little_floats({0, 0, 0, 1, 0, 0, 0, std::numeric_limits<float>::quiet_NaN(), 0})),
                  ": vertex 2: non-finite vertex coordinate 'nan'"},
        Malformed{"double_overflow.ply",
                  ply_header("binary_little_endian",
                             "element vertex 1\nproperty double x\nproperty double y\nproperty double z\n"
                             "element face 0\nproperty list uchar int vertex_indices\n") +
                      little(1e300) + little(0.0) + little(0.0),
                  ": vertex 0: non-finite vertex coordinate '1e+300'"},
        // Elements Meander does not use are still read through, and must be whole.
        Malformed{"other_element_truncated.ply",
                  ply_header("binary_little_endian", "element vertex 3\n" + xyz +
                                                         "element face 1\nproperty list uchar int vertex_indices\n"
                                                         "element edge 2\nproperty list uchar int corners\n") +
                      le_vertices + le_face(3, {0, 1, 2}) + le_face(2, {0, 1}) + le_face(2, {1}),
                  ": edge 1: file ends early (the header claims 2 'edge' elements)"},
        Malformed{
            "negative_list_length.ply",
            ply_header("binary_little_endian", "element edge 1\nproperty list int int corners\nelement vertex 3\n" +
                                                   xyz + "element face 1\nproperty list uchar int vertex_indices\n") +
                little(-1) + le_vertices + le_face(3, {0, 1, 2}),
            ": edge 0: negative list length -1"},
        Malformed{"ascii_bad_coordinate.ply", ascii_triangle("0 0 0\nabc 0 0\n0 1 0\n3 0 1 2\n"),
                  ":11: bad vertex coordinate 'abc'"},
        Malformed{"ascii_nan.ply", ascii_triangle("0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"),
                  ":11: non-finite vertex coordinate 'nan'"},
        Malformed{"ascii_truncated.ply", ascii_triangle("0 0 0\n1 0 0\n"),
                  ":11: vertex 2: file ends early (the header claims 3 vertices)"},
        Malformed{"ascii_index.ply", ascii_triangle(ascii_vertices + "3 0 1 3\n"),
                  ":13: face 0: vertex index 3 out of range (0..2)"},
        Malformed{"ascii_bad_index.ply", ascii_triangle(ascii_vertices + "3 0 1 x\n"), ":13: bad vertex index 'x'"},
        Malformed{"ascii_two_vertex_face.ply", ascii_triangle(ascii_vertices + "2 0 1\n"),
                  ":13: face 0: face with 2 vertices (at least 3 needed)"},
        Malformed{"ascii_trailing_text.ply", ascii_triangle(ascii_vertices + "3 0 1 2\njunk\n"),
                  ":14: unexpected 'junk' after the last element"},
        // Faces before vertices are checked once the vertices are known.
        Malformed{
            "faces_first.ply",
            ply_header("ascii", "element face 1\nproperty list uchar int vertex_indices\nelement vertex 3\n" + xyz) +
                "3 0 1 5\n" + ascii_vertices,
            ": face 0: vertex index 5 out of range (0..2)"},
        Malformed{"no_faces.ply", ascii_triangle(ascii_vertices, 0), ": no faces"}),
    case_name);

const std::array<float, 9> triangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};
const std::string ascii_facet =
    "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";

INSTANTIATE_TEST_SUITE_P(
    IoStl, IoMalformed,
    ::testing::Values(
        Malformed{"empty.stl", "", ": file is empty"},
        Malformed{"short.stl", "abc", ": not an STL file (no 'solid' at the start, and too short for a binary STL)"},
        Malformed{"count_too_high.stl", binary_stl("", 1000, std::vector(12, triangle)),
                  ": binary STL claims 1000 triangles but the file holds 12"},
        // "solid" in a binary header does not make it ascii: the count's bytes are not text.
        Malformed{"solid_header_count_too_high.stl", binary_stl("solid but binary", 5, {triangle}),
                  ": binary STL claims 5 triangles but the file holds 1"},
        Malformed{"extra_bytes.stl", binary_stl("", 2, {triangle, triangle}) + "1234567",
                  ": binary STL of 2 triangles has 7 extra bytes at the end"},
        Malformed{"binary_nan.stl", binary_stl("", 2, {triangle, {0, 0, 0, 1, 0, 0, 0, 1, std::nanf("")}}),
                  ": face 1: non-finite vertex coordinate 'nan'"},
        Malformed{"binary_no_triangles.stl", binary_stl("", 0, {}), ": no faces"},
        Malformed{"ascii_no_endsolid.stl", "solid t\n" + ascii_facet, ":8: file ends before 'endsolid'"},
        Malformed{"ascii_misspelt.stl", "solid t\nfacet normal 0 0 1\nouter lop\n", ":3: expected 'loop', found 'lop'"},
        Malformed{"ascii_missing_normal.stl", "solid t\nfacet normal 0 0\nouter loop\n",
                  ":2: missing normal coordinate"},
        Malformed{"ascii_truncated.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n",
                  ":4: expected 'vertex' but the file ends"},
        Malformed{
            "ascii_two_vertices.stl",
            "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid t\n",
            ":6: face with 2 vertices (at least 3 needed)"},
        Malformed{"ascii_nan.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 nan 0\n",
                  ":4: non-finite vertex coordinate 'nan'"},
        Malformed{"ascii_bad_coordinate.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\n",
                  ":4: bad vertex coordinate 'zero'"},
        Malformed{"ascii_no_facets.stl", "solid t\nendsolid t\n", ": no faces"},
        Malformed{"ascii_junk_after_endsolid.stl", "solid t\n" + ascii_facet + "endsolid t\njunk\n",
                  ":10: expected 'solid', found 'junk'"}),
    case_name);

// A large OFF file (a grid of quads, more than 1 MiB) with comments, blank lines and CRLF
// among its vertex lines: the mesh is read whole, and an error in either section is
// reported at its own line, counted through all of them, the first one in the file.
std::string large_off(int32_t n, int32_t bad_vertex_line, int32_t bad_face) {
  std::string text = "OFF\n" + std::to_string(n * n) + " " + std::to_string((n - 1) * (n - 1)) + " 0\n";
  int64_t line = 2;
  for (int32_t i = 0; i < n * n; ++i) {
    if (i % 97 == 0) {
      text += "# a comment between vertices\n\n";
      line += 2;
    }
    ++line;
    text += line == bad_vertex_line ? "0 zero 0\n" : std::to_string(i % n) + " " + std::to_string(i / n) + " 0" + (i % 5 ? "\n" : "\r\n");
  }
  for (int32_t y = 0; y + 1 < n; ++y)
    for (int32_t x = 0; x + 1 < n; ++x) {
      const int32_t f = y * (n - 1) + x, v = y * n + x;
      text += "4 " + std::to_string(v) + " " + std::to_string(v + 1) + " " + std::to_string(f == bad_face ? n * n : v + n + 1) +
              " " + std::to_string(v + n) + "\n";
    }
  return text;
}

TEST(IoOffLarge, AGridWithCommentsAndCrlfReadsWhole) {
  const std::string text = large_off(300, -1, -1);
  ASSERT_GT(text.size(), size_t(1) << 20);
  const PolygonMesh mesh = read_mesh(test::write_file("grid_large.off", text));
  ASSERT_EQ(mesh.num_vertices(), 300 * 300);
  ASSERT_EQ(mesh.num_faces(), 299 * 299);
  EXPECT_EQ(mesh.positions[301], (Vec3{1, 1, 0}));
  const auto face = mesh.face(299 * 299 - 1);
  EXPECT_EQ(std::vector<int32_t>(face.begin(), face.end()), (std::vector<int32_t>{89698, 89699, 89999, 89998}));
}

TEST(IoOffLarge, AnErrorIsReportedOnItsLineAndTheVerticesComeFirst) {
  // Lines: 2 of header, 90000 vertex lines and 2 * ceil(90000 / 97) = 1856 comment and
  // blank lines, so face f is on line 91858 + f + 1.
  const std::filesystem::path faces = test::write_file("bad_face_large.off", large_off(300, -1, 5000));
  EXPECT_EQ(test::message_of<InputError>([&] { read_mesh(faces); }),
            faces.string() + ":96859: vertex index 90000 out of range (0..89999)");
  const std::filesystem::path both = test::write_file("bad_vertex_large.off", large_off(300, 70000, 5000));
  EXPECT_EQ(test::message_of<InputError>([&] { read_mesh(both); }), both.string() + ":70000: bad vertex coordinate 'zero'");
}

// Large OFF files are read in chunks cut at line starts, on all cores. Line ends of any
// kind (here classic Mac OS lone CRs), comment and blank lines, extra columns after a
// vertex's coordinates and a face's indices must give the mesh as written; and a file
// with an element too many or too few is still refused with the serial reader's message
// and line.
TEST(IoOffLarge, ChunksGiveTheMeshAsWrittenWhateverTheLineEnds) {
  constexpr int32_t n = 200;
  std::vector<Vec3> positions;
  std::vector<int32_t> corners;
  const auto text = [&](const std::string& eol, int32_t faces, const std::string& after) {
    std::string t = "COFF" + eol + "# made by a test" + eol + std::to_string(n * n) + " " + std::to_string(faces) + " 0" + eol;
    positions.clear();
    corners.clear();
    for (int32_t i = 0; i < n * n; ++i) {
      if (i % 1000 == 0) t += " \t" + eol + "# between vertices" + eol;
      positions.push_back({float(i % n) * 0.5f, float(i / n) * 0.25f, float(i % 7)});
      t += std::to_string(float(i % n) * 0.5f) + " " + std::to_string(float(i / n) * 0.25f) + " " + std::to_string(i % 7) +
           " 0.5 0.5 0.5 1" + eol;
    }
    for (int32_t f = 0; f < faces; ++f) {
      const int32_t v = (f / (n - 1)) * n + f % (n - 1);
      const int32_t face[] = {v, v + 1, v + n + 1};
      corners.insert(corners.end(), std::begin(face), std::end(face));
      t += "3 " + std::to_string(v) + " " + std::to_string(v + 1) + " " + std::to_string(v + n + 1) + " 255 0 0" + eol;
    }
    return t + after;
  };
  const int32_t faces = (n - 1) * (n - 1);
  for (const std::string eol : {"\r", "\r\n", "\n"}) {
    const std::string whole = text(eol, faces, "");
    ASSERT_GT(whole.size(), size_t(1) << 20);
    const PolygonMesh m = read_mesh(test::write_file("chunks.off", whole));
    EXPECT_EQ(m.positions, positions);
    EXPECT_EQ(m.face_vertices, corners);
    ASSERT_EQ(m.num_faces(), faces);
    EXPECT_EQ(m.face_start.back(), 3 * faces);
  }
  // Lines: 3 of header, 2 for each of the 40 comments, 40000 vertices, then the faces.
  const int64_t first_face_line = 3 + 2 * 40 + n * n + 1;
  const std::filesystem::path extra = test::write_file("chunks_extra.off", text("\n", faces, "extra\n"));
  EXPECT_EQ(test::message_of<InputError>([&] { read_mesh(extra); }),
            extra.string() + ":" + std::to_string(first_face_line + faces) + ": unexpected 'extra' after the last face");
  std::string short_text = text("\n", faces, "");
  short_text.resize(short_text.rfind("3 ", short_text.size() - 2)); // the last face gone
  const std::filesystem::path missing = test::write_file("chunks_missing.off", short_text);
  EXPECT_EQ(test::message_of<InputError>([&] { read_mesh(missing); }),
            missing.string() + ":" + std::to_string(first_face_line + faces - 2) + ": expected " +
                std::to_string(faces) + " faces but the file ends after " + std::to_string(faces - 1));
}

// Large OBJ files are read in chunks too: negative indices count back from the vertices
// defined before their line, whichever chunk those lie in, positive ones may point
// forward, and the statements the mesh does not need are skipped. Errors come with the
// serial reader's message and line.
TEST(IoObjLarge, ChunksCountVerticesAcrossTheirBoundaries) {
  constexpr int32_t rows = 400;
  const auto text = [&](const std::string& eol, int32_t bad_row, const std::string& bad_face) {
    std::string t = "# a grid of triangles, rows of vertices and faces interleaved" + eol + "o grid" + eol;
    for (int32_t r = 0; r < rows; ++r) {
      t += "vn 0 0 1" + eol;
      for (int32_t i = 0; i < 100; ++i)
        t += "v " + std::to_string(i) + " " + std::to_string(r) + " 0" + (i % 3 ? "" : " 1") + eol + "vt 0 0" + eol;
      if (r == 0) continue;
      // Negative: the previous row is -200..-101, this one -100..-1.
      for (int32_t i = 0; i + 1 < 100; ++i) {
        t += "f " + std::to_string(i - 200) + "/1/1 " + std::to_string(i - 199) + "//1 " + std::to_string(i - 100) + eol;
        if (r == bad_row && i == 50) t += bad_face + eol;
      }
    }
    // Forward and positive: a face naming the last vertex, written before a comment.
    return t + "f 1 2 " + std::to_string(rows * 100) + eol + "# end" + eol;
  };
  for (const std::string eol : {"\n", "\r\n", "\r"}) {
    const std::string whole = text(eol, -1, "");
    ASSERT_GT(whole.size(), size_t(1) << 20);
    const PolygonMesh m = read_mesh(test::write_file("chunks.obj", whole));
    ASSERT_EQ(m.num_vertices(), rows * 100);
    ASSERT_EQ(m.num_faces(), (rows - 1) * 99 + 1);
    EXPECT_EQ(m.positions[size_t(37 * 100 + 5)], (Vec3{5, 37, 0}));
    for (int32_t r = 1; r < rows; r += 37)
      for (int32_t i = 0; i + 1 < 100; i += 13) {
        const auto f = m.face((r - 1) * 99 + i);
        EXPECT_EQ(std::vector<int32_t>(f.begin(), f.end()),
                  (std::vector<int32_t>{(r - 1) * 100 + i, (r - 1) * 100 + i + 1, r * 100 + i}))
            << "row " << r << " face " << i;
      }
    const auto last = m.face(m.num_faces() - 1);
    EXPECT_EQ(std::vector<int32_t>(last.begin(), last.end()), (std::vector<int32_t>{0, 1, rows * 100 - 1}));
  }
  // Row 300's faces lie after 2 + 301 * 201 + 299 * 99 lines (its own vertices are
  // written before them); the bad face follows face 50.
  const int64_t bad_line = 2 + 301 * 201 + 299 * 99 + 51 + 1;
  const std::filesystem::path back = test::write_file("chunks_back.obj", text("\n", 300, "f -1 -2 -30101"));
  EXPECT_EQ(test::message_of<InputError>([&] { read_mesh(back); }),
            back.string() + ":" + std::to_string(bad_line) + ": face references vertex -30101 but only 30100 exist");
  const std::filesystem::path two = test::write_file("chunks_two.obj", text("\n", 300, "f 1 2"));
  EXPECT_EQ(test::message_of<InputError>([&] { read_mesh(two); }),
            two.string() + ":" + std::to_string(bad_line) + ": face with 2 vertices (at least 3 needed)");
  const std::filesystem::path ahead = test::write_file("chunks_ahead.obj", text("\n", 300, "f 1 2 40001"));
  EXPECT_EQ(test::message_of<InputError>([&] { read_mesh(ahead); }),
            ahead.string() + ":" + std::to_string(bad_line) + ": face references vertex 40001 but only 40000 exist");
}

} // namespace
} // namespace meander
