// Polylines in files: what write_polylines writes reads back point for point (OBJ `l`
// elements and PLY edges, closed loops and open polylines), PLY edges in any order,
// direction and encoding chain into loops and open chains, and malformed edge lists are
// refused naming the element.
#include "io_test_support.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/jobs.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace meander {
namespace {

namespace fs = std::filesystem;
using test::big;
using test::little;
using test::message_of;
using test::output_dir;

// A closed square, an open zig-zag, a closed loop of two points and an open segment.
Polylines mixed_polylines() {
  Polylines c;
  c.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},              // closed
              {5, 0, 0}, {6, 1, 0}, {7, 0, 0.5f}, {8, 1, 0},          // open
              {1, 2, 3}, {4, 5, 6},                                   // closed, two points
              {-1, -1, -1}, {-2, -2, -2.25f}};                        // open, two points
  c.start = {0, 4, 8, 10, 12};
  c.open = {0, 1, 0, 1};
  return c;
}

void expect_same(const Polylines& a, const Polylines& b) {
  EXPECT_EQ(a.start, b.start);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.open, b.open);
}

TEST(Polylines, PlyAndObjRoundTripClosedAndOpenPolylines) {
  const Polylines curves = mixed_polylines();
  for (const char* name : {"c.ply", "c.obj"}) {
    const fs::path path = output_dir() / name;
    write_polylines(curves, path);
    expect_same(read_polylines(path), curves);
  }
}

// Hundreds of thousands of edges in a binary PLY, over polylines of many sizes, open
// and closed, with empty and single-point ones among them (which have no edge): every
// edge must join the right points (the edge list is compared with one made here).
TEST(Polylines, PlyEdgesOfManyPolylinesWithEmptyOnes) {
  Polylines curves;
  std::vector<int32_t> expected;
  for (int32_t k = 0; k < 400; ++k) {
    const int32_t n = k % 7 == 0 ? 0 : k % 7 == 1 ? 1 : 1 + (k * 7919) % 2500;
    const bool open = k % 3 == 0;
    const int32_t first = int32_t(curves.points.size());
    for (int32_t i = 0; i < n; ++i) curves.points.push_back({float(k), float(i), 0});
    curves.start.push_back(int32_t(curves.points.size()));
    curves.open.push_back(open);
    if (n >= 2)
      for (int32_t i = 0; i < (open ? n - 1 : n); ++i) {
        expected.push_back(first + i);
        expected.push_back(i + 1 == n ? first : first + i + 1);
      }
  }
  ASSERT_GT(expected.size() / 2, size_t(2) << 17);
  const fs::path path = output_dir() / "blocks.ply";
  write_polylines(curves, path);
  const std::string bytes = test::read_file(path);
  const std::string header_end = "end_header\n";
  const size_t body = bytes.find(header_end) + header_end.size();
  ASSERT_EQ(bytes.size(), body + curves.points.size() * 12 + expected.size() * 4);
  std::vector<int32_t> edges(expected.size());
  std::memcpy(edges.data(), bytes.data() + body + curves.points.size() * 12, edges.size() * 4);
  EXPECT_EQ(edges, expected);
}

TEST(Polylines, AllClosedReadsBackWithoutOpenFlags) {
  Polylines curves;
  curves.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {3, 3, 3}, {4, 3, 3}, {4, 4, 3}};
  curves.start = {0, 3, 6};
  const fs::path path = output_dir() / "c.ply";
  write_polylines(curves, path);
  const Polylines back = read_polylines(path);
  expect_same(back, curves);
  EXPECT_TRUE(back.open.empty());
}

TEST(Polylines, WritersLeaveOpenPolylinesOpen) {
  const Polylines curves = mixed_polylines();
  const fs::path dir = output_dir();
  write_polylines(curves, dir / "c.obj");
  const std::string obj = test::read_file(dir / "c.obj");
  EXPECT_NE(obj.find("\nl 1 2 3 4 1\nl 5 6 7 8\nl 9 10 9\nl 11 12\n"), std::string::npos) << obj;
  write_polylines(curves, dir / "c.json");
  EXPECT_NE(test::read_file(dir / "c.json").find("{\"closed\": false, \"points\": [[5,0,0]"), std::string::npos);
  // A drawing's paths too: only the two closed ones end with Z.
  const std::string svg = curve_svg(curves, {}, false);
  EXPECT_EQ(std::count(svg.begin(), svg.end(), 'Z'), 2);
}

// An ascii file whose edges come in no particular order or direction: the open chain's
// first edge is in its middle, and the loop's edges point both ways.
TEST(Polylines, AsciiPlyEdgesInAnyOrderChainIntoLoopsAndOpenChains) {
  const auto path = test::write_file("edges.ply",
                                     "ply\nformat ascii 1.0\ncomment a loop 0-1-2 and a chain 3-4-5-6\n"
                                     "element vertex 8\nproperty double x\nproperty double y\nproperty double z\n"
                                     "element edge 5\nproperty uchar red\nproperty uint vertex1\nproperty short vertex2\n"
                                     "end_header\n"
                                     "0 0 0\n1 0 0\n1 1 0\n3 0 0\n4 0 0\n5 0 0\n6 0 0\n9 9 9\n"
                                     "7 4 5\n7 1 0\n7 3 4\n7 1 2\n7 6 5\n"
                                     "7 0 2\n");
  // The header claims 5 edges and there are 6 lines: the last is one too many.
  EXPECT_EQ(message_of<InputError>([&] { read_polylines(path); }),
            path.string() + ":26: unexpected '7' after the last element");
  const auto good = test::write_file("good.ply",
                                     "ply\nformat ascii 1.0\n"
                                     "element vertex 8\nproperty double x\nproperty double y\nproperty double z\n"
                                     "element edge 6\nproperty uchar red\nproperty uint vertex1\nproperty short vertex2\n"
                                     "end_header\n"
                                     "0 0 0\n1 0 0\n1 1 0\n3 0 0\n4 0 0\n5 0 0\n6 0 0\n9 9 9\n"
                                     "7 4 5\n7 1 0\n7 3 4\n7 1 2\n7 6 5\n7 0 2\n");
  const Polylines c = read_polylines(good);
  ASSERT_EQ(c.size(), 2);
  // The chain is found first (its edge 4-5 comes first), walked back to its end 3.
  EXPECT_EQ(c.start, (std::vector<int32_t>{0, 4, 7}));
  EXPECT_EQ(c.open, (std::vector<uint8_t>{1, 0}));
  EXPECT_EQ(c.points[0].x, 3);
  EXPECT_EQ(c.points[3].x, 6);
  // The loop starts at its first edge 1-0, in that direction; vertex 7 is in no edge.
  EXPECT_EQ(c.points[4], (Vec3{1, 0, 0}));
  EXPECT_EQ(c.points[5], (Vec3{0, 0, 0}));
  EXPECT_EQ(c.points[6], (Vec3{1, 1, 0}));
}

TEST(Polylines, BigEndianPlyEdgesBeforeTheVertices) {
  std::string bytes = "ply\nformat binary_big_endian 1.0\nelement edge 2\nproperty int vertex1\nproperty int vertex2\n"
                      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (int32_t v : {0, 1, 1, 2}) bytes += big(v);
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 2.f, 0.f}) bytes += big(v);
  const auto path = test::write_file("big.ply", bytes);
  const Polylines c = read_polylines(path);
  EXPECT_EQ(c.start, (std::vector<int32_t>{0, 3}));
  EXPECT_EQ(c.open, (std::vector<uint8_t>{1}));
  EXPECT_EQ(c.points[2], (Vec3{1, 2, 0}));
}

std::string little_edge_file(std::initializer_list<int32_t> ends, int32_t claimed_edges, int32_t vertices = 4) {
  std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertices) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement edge " +
                      std::to_string(claimed_edges) + "\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  for (int32_t i = 0; i < 3 * vertices; ++i) bytes += little(float(i));
  for (int32_t v : ends) bytes += little(v);
  return bytes;
}

// Each refusal names the edge (the element and its number) and what is wrong with it.
TEST(Polylines, MalformedEdgesAreRefusedNamingTheElement) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      // A vertex with three edges is a branch, which no polyline has.
      {little_edge_file({0, 1, 1, 2, 1, 3}, 3), "edge 2: vertex 1 already joins edges 0 and 1 (a polyline does not branch)"},
      {little_edge_file({0, 1, 2, 2}, 2), "edge 1: joins vertex 2 to itself"},
      {little_edge_file({0, 1, 1, 9}, 2), "edge 1: vertex index 9 out of range (0..3)"},
      {little_edge_file({0, 1, -1, 2}, 2), "edge 1: vertex index -1 out of range (0..3)"},
      {little_edge_file({0, 1, 1}, 2), "edge 1: file ends early (the header claims 2 'edge' elements)"},
      {little_edge_file({}, 0), "no polylines (no edges)"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
       "no polylines (edge elements)"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
       "element edge 0\nproperty int vertex1\nproperty int vertex_2\nend_header\n0 0 0\n",
       "header: element edge has no property vertex2"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
       "element edge 0\nproperty float vertex1\nproperty int vertex2\nend_header\n0 0 0\n",
       "header: property vertex1 of element edge must be an integer"},
  };
  for (const auto& [bytes, message] : cases) {
    const auto path = test::write_file("bad.ply", bytes);
    EXPECT_EQ(message_of<InputError>([&] { read_polylines(path); }), path.string() + ": " + message);
    // Only a file without polylines may be taken for a mesh by `meander render`.
    bool no_polylines = false;
    try {
      read_polylines(path);
    } catch (const NoPolylinesError&) {
      no_polylines = true;
    } catch (const InputError&) {
    }
    EXPECT_EQ(no_polylines, message.starts_with("no polylines")) << message;
  }
}

TEST(Polylines, AMeshReadsAsAMeshEvenWithEdges) {
  // Tricky: a PLY with faces and edges is a mesh to read_mesh and polylines to
  // read_polylines; each reader skips the other's element.
  const auto path = test::write_file("both.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                     "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                     "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
                                     "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0 2\n");
  EXPECT_EQ(read_mesh(path).num_faces(), 1);
  const Polylines c = read_polylines(path);
  EXPECT_EQ(c.start, (std::vector<int32_t>{0, 2}));
}

} // namespace
} // namespace meander
