// Readers and writers: round trips through every format, the real meshes, the accepted
// variants of each format, and the writers' promise to leave no partial file.
#include "io_test_support.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/shapes.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <signal.h>
#include <sstream>
#include <sys/resource.h>
#include <sys/stat.h>

namespace meander {
namespace {

namespace fs = std::filesystem;
using test::output_dir;
using test::write_file;


std::vector<std::string> folder_listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A closed box of 12 vertices with triangles, quads and two hexagons (top and bottom),
// at coordinates chosen to test the text round trip: -0, a subnormal, the largest
// float, values with no short decimal form.
PolygonMesh mixed_mesh() {
  PolygonMesh m;
  const float odd = 1.0f / 3.0f;
  const float tiny = std::numeric_limits<float>::denorm_min() * 7;
  const float big = std::numeric_limits<float>::max();
  for (int i = 0; i < 6; ++i) {
    const double angle = 2 * M_PI * i / 6;
    const float x = float(std::cos(angle)) + (i == 1 ? tiny : 0), y = float(std::sin(angle)) * odd;
    m.positions.push_back({x, y, i == 0 ? -0.0f : 0.1f});
  }
  for (int i = 0; i < 6; ++i) {
    const Vec3 p = m.positions[size_t(i)];
    m.positions.push_back({p.x, p.y, i == 3 ? big : 1e-30f});
  }
  m.add_face({5, 4, 3, 2, 1, 0});
  m.add_face({6, 7, 8, 9, 10, 11});
  for (int32_t i = 0; i < 6; ++i) {
    const int32_t j = (i + 1) % 6;
    if (i % 2 == 0) {
      m.add_face({i, j, j + 6, i + 6});
    } else {
      m.add_face({i, j, j + 6});
      m.add_face({i, j + 6, i + 6});
    }
  }
  return m;
}

// Bitwise, so that -0 and +0 or two NaNs are told apart.
void expect_same_positions(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(std::bit_cast<uint32_t>((&a[i].x)[k]), std::bit_cast<uint32_t>((&b[i].x)[k]))
          << "vertex " << i << " axis " << k;
}

void expect_same_mesh(const PolygonMesh& a, const PolygonMesh& b) {
  expect_same_positions(a.positions, b.positions);
  EXPECT_EQ(a.face_start, b.face_start);
  EXPECT_EQ(a.face_vertices, b.face_vertices);
}

struct RoundTrip {
  const char* file;
  bool ascii;
};

class IoRoundTrip : public ::testing::TestWithParam<RoundTrip> {};

// Every format but STL keeps the mesh exactly: the same polygons, and floats written as
// the shortest decimal that reads back to the same bits.
TEST_P(IoRoundTrip, KeepsTheMeshExactly) {
  const PolygonMesh mesh = mixed_mesh();
  const fs::path path = output_dir() / GetParam().file;
  write_mesh(mesh, path, {.ascii = GetParam().ascii});
  expect_same_mesh(read_mesh(path), mesh);
}

INSTANTIATE_TEST_SUITE_P(IoFormats, IoRoundTrip,
                         ::testing::Values(RoundTrip{"m.obj", false}, RoundTrip{"m.off", false},
                                           RoundTrip{"m.ply", false}, RoundTrip{"m.ply", true}),
                         [](const auto& instance) {
                           return std::string(instance.param.ascii ? "ascii_" : "") + (instance.param.file + 2);
                         });

class IoStlRoundTrip : public ::testing::TestWithParam<bool> {};

// STL keeps triangles only: polygons come back fanned from their first vertex, and
// vertices come back welded, numbered in order of first use.
TEST_P(IoStlRoundTrip, KeepsTheFannedTriangles) {
  const PolygonMesh mesh = mixed_mesh();
  const fs::path path = output_dir() / "m.stl";
  write_mesh(mesh, path, {.ascii = GetParam()});
  const PolygonMesh back = read_mesh(path);
  std::vector<Vec3> expected_corners;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto face = mesh.face(f);
    for (size_t k = 1; k + 1 < face.size(); ++k)
      for (int32_t v : {face[0], face[k], face[k + 1]}) expected_corners.push_back(mesh.positions[size_t(v)]);
  }
  ASSERT_EQ(back.num_faces(), int32_t(expected_corners.size() / 3));
  EXPECT_EQ(back.num_vertices(), mesh.num_vertices()); // all 12 positions are distinct
  std::vector<Vec3> corners;
  for (int32_t f = 0; f < back.num_faces(); ++f) {
    ASSERT_EQ(back.face_size(f), 3);
    for (int32_t v : back.face(f)) corners.push_back(back.positions[size_t(v)]);
  }
  expect_same_positions(corners, expected_corners);
}

INSTANTIATE_TEST_SUITE_P(IoEncodings, IoStlRoundTrip, ::testing::Bool(),
                         [](const auto& instance) { return instance.param ? "ascii" : "binary"; });

// A face of more than 255 vertices does not fit PLY's usual uchar length: the writer
// switches to uint lengths.
TEST(IoPly, FaceLargerThan255VerticesRoundTrips) {
  PolygonMesh mesh;
  std::vector<int32_t> disk;
  for (int32_t i = 0; i < 300; ++i) {
    mesh.positions.push_back({float(std::cos(i * 0.02)), float(std::sin(i * 0.02)), 0});
    disk.push_back(i);
  }
  mesh.add_face(disk);
  for (bool ascii : {false, true}) {
    const fs::path path = output_dir() / (ascii ? "ascii.ply" : "binary.ply");
    write_mesh(mesh, path, {.ascii = ascii});
    EXPECT_NE(test::read_file(path).find("property list uint int vertex_indices"), std::string::npos);
    expect_same_mesh(read_mesh(path), mesh);
  }
}

// The same mesh gives the same bytes, whatever the format.
TEST(IoWrite, OutputIsDeterministic) {
  const PolygonMesh mesh = mixed_mesh();
  const fs::path dir = output_dir();
  for (const char* name : {"a.obj", "a.off", "a.ply", "a.stl"})
    for (bool ascii : {false, true}) {
      write_mesh(mesh, dir / name, {.ascii = ascii});
      const std::string first = test::read_file(dir / name);
      write_mesh(mesh, dir / name, {.ascii = ascii});
      EXPECT_EQ(test::read_file(dir / name), first) << name;
    }
}

// Writers reserve a file's blocks ahead of their writes (in steps of up to 64 MiB) and
// cut the file back when it closes: what is left is the bytes written, no more, also
// where a format writes its sections out of order (a PLY curve's edges before its points).
TEST(IoWrite, LargeFilesHoldTheirBytesAndNoMore) {
  const fs::path dir = output_dir();
  const PolygonMesh mesh = sphere(200000);
  write_mesh(mesh, dir / "sphere.stl");
  EXPECT_EQ(fs::file_size(dir / "sphere.stl"), 84 + 50 * uintmax_t(mesh.num_faces()));
  Polylines curve;
  for (int i = 0; i < 700000; ++i) curve.points.push_back({float(i), float(i % 7), 0});
  curve.start.push_back(int32_t(curve.points.size()));
  write_polylines(curve, dir / "curve.ply");
  const std::string bytes = test::read_file(dir / "curve.ply");
  const size_t header = bytes.find("end_header\n") + 11;
  EXPECT_EQ(bytes.size(), header + (12 + 8) * curve.points.size());
  EXPECT_EQ(read_polylines(dir / "curve.ply").points, curve.points);
}

TEST(IoWrite, TextFormatsAreAsDocumented) {
  PolygonMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1.5f, 0}, {0, 0, -2}};
  mesh.add_face({0, 1, 2});
  mesh.add_face({0, 2, 3, 1});
  const fs::path dir = output_dir();
  write_mesh(mesh, dir / "m.obj");
  EXPECT_EQ(test::read_file(dir / "m.obj"), "v 0 0 0\nv 1 0 0\nv 0 1.5 0\nv 0 0 -2\nf 1 2 3\nf 1 3 4 2\n");
  write_mesh(mesh, dir / "m.off");
  EXPECT_EQ(test::read_file(dir / "m.off"), "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1.5 0\n0 0 -2\n3 0 1 2\n4 0 2 3 1\n");
  write_mesh(mesh, dir / "m.ply", {.ascii = true});
  EXPECT_EQ(test::read_file(dir / "m.ply"),
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n0 1.5 0\n0 0 -2\n3 0 1 2\n4 0 2 3 1\n");
}

TEST(IoWrite, BinaryStlHasComputedNormalsAndAHeaderThatIsNotSolid) {
  PolygonMesh mesh;
  mesh.positions = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  mesh.add_face({0, 1, 2, 3});
  const fs::path path = output_dir() / "quad.stl";
  write_mesh(mesh, path);
  const std::string bytes = test::read_file(path);
  ASSERT_EQ(bytes.size(), 84u + 2 * 50);
  EXPECT_NE(bytes.substr(0, 5), "solid");
  uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  EXPECT_EQ(count, 2u);
  for (size_t t = 0; t < 2; ++t) {
    float normal[3];
    std::memcpy(normal, bytes.data() + 84 + 50 * t, sizeof normal);
    EXPECT_EQ(normal[0], 0.0f);
    EXPECT_EQ(normal[1], 0.0f);
    EXPECT_EQ(normal[2], 1.0f);
  }
}

TEST(IoWrite, ObjGroupsBecomeObjectLines) {
  PolygonMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  mesh.add_face({0, 1, 2});
  mesh.add_face({1, 3, 2});
  mesh.add_face({0, 2, 1});
  const std::vector<int32_t> groups = {0, 2, 2, 3}; // the middle group is empty: no line for it
  const fs::path path = output_dir() / "groups.obj";
  write_mesh(mesh, path, {.group_start = groups});
  const std::string text = test::read_file(path);
  EXPECT_NE(text.find("o group_0\nf 1 2 3\nf 2 4 3\no group_2\nf 1 3 2\n"), std::string::npos) << text;
  expect_same_mesh(read_mesh(path), mesh);
}

TEST(IoWrite, BadGroupsAreAUsageErrorAndWriteNothing) {
  PolygonMesh mesh = mixed_mesh();
  const std::vector<int32_t> groups = {0, 5, 3};
  const fs::path dir = output_dir();
  EXPECT_EQ(test::message_of<UsageError>([&] { write_mesh(mesh, dir / "g.obj", {.group_start = groups}); }),
            (dir / "g.obj").string() + ": group_start must be non-decreasing face numbers in 0.." +
                std::to_string(mesh.num_faces()));
  EXPECT_TRUE(folder_listing(dir).empty());
}

// New files get the usual permissions (0666 minus the umask), not mkstemp's 0600.
TEST(IoWrite, NewFilesGetTheUsualPermissions) {
  const mode_t mask = ::umask(022);
  const fs::path path = output_dir() / "m.off";
  write_mesh(mixed_mesh(), path);
  ::umask(mask);
  struct stat info {};
  ASSERT_EQ(::stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0644u);
}

TEST(IoWrite, MissingFolderIsAnIOErrorAndCreatesNothing) {
  const fs::path dir = output_dir();
  const fs::path path = dir / "no_such_folder" / "m.ply";
  EXPECT_EQ(test::message_of<IOError>([&] { write_mesh(mixed_mesh(), path); }),
            path.string() + ": cannot create file: No such file or directory");
  EXPECT_FALSE(fs::exists(dir / "no_such_folder"));
  EXPECT_TRUE(folder_listing(dir).empty());
}

TEST(IoWrite, UnknownExtensionIsAUsageErrorAndCreatesNothing) {
  const fs::path dir = output_dir();
  EXPECT_EQ(test::message_of<UsageError>([&] { write_mesh(mixed_mesh(), dir / "m.xyz"); }),
            (dir / "m.xyz").string() + ": unknown mesh format '.xyz' (Meander reads .obj, .ply, .stl, .off, .gltf and .glb, and writes those and .3mf)");
  EXPECT_EQ(test::message_of<UsageError>([&] { write_mesh(mixed_mesh(), dir / "m"); }),
            (dir / "m").string() + ": unknown mesh format '' (Meander reads .obj, .ply, .stl, .off, .gltf and .glb, and writes those and .3mf)");
  EXPECT_EQ(test::message_of<UsageError>([&] { write_polylines(Polylines{}, dir / "c.txt"); }),
            (dir / "c.txt").string() + ": unknown curve format '.txt' (expected .obj, .ply or .json)");
  EXPECT_EQ(test::message_of<UsageError>([&] { write_polylines(Polylines{}, dir / "c.svg"); }),
            (dir / "c.svg").string() + ": unknown curve format '.svg' (expected .obj, .ply or .json; an SVG is a drawing (drawing.h))");
  EXPECT_TRUE(folder_listing(dir).empty());
}

// The rename over a folder fails after all was written: the temporary file must go
// and the folder must stay as it was.
TEST(IoWrite, TargetThatIsAFolderIsAnIOErrorAndLeavesNoTemporaryFile) {
  const fs::path dir = output_dir();
  fs::create_directories(dir / "taken.obj" / "inside");
  EXPECT_EQ(test::message_of<IOError>([&] { write_mesh(mixed_mesh(), dir / "taken.obj"); }),
            (dir / "taken.obj").string() + ": cannot write: Is a directory");
  EXPECT_EQ(folder_listing(dir), std::vector<std::string>{"taken.obj"});
  EXPECT_EQ(folder_listing(dir / "taken.obj"), std::vector<std::string>{"inside"});
}

// A write that fails halfway (here the file size limit, as a full disk would) leaves the
// old file as it was and no temporary file.
TEST(IoWrite, FailedWriteLeavesThePreviousFileUntouched) {
  const fs::path dir = output_dir();
  const fs::path path = dir / "big.ply";
  const std::string previous = "the previous content";
  std::ofstream(path, std::ios::binary) << previous;
  PolygonMesh mesh;
  for (int i = 0; i < 200000; ++i) mesh.positions.push_back({float(i), 0, 0});
  for (int32_t i = 0; i + 2 < 200000; i += 3) mesh.add_face({i, i + 1, i + 2});

  rlimit old_limit{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old_limit), 0);
  rlimit limit = old_limit;
  limit.rlim_cur = 100000;
  const auto old_handler = ::signal(SIGXFSZ, SIG_IGN);
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limit), 0);
  EXPECT_EQ(test::message_of<IOError>([&] { write_mesh(mesh, path); }),
            path.string() + ": cannot write: File too large");
  ::setrlimit(RLIMIT_FSIZE, &old_limit);
  ::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(test::read_file(path), previous);
  EXPECT_EQ(folder_listing(dir), std::vector<std::string>{"big.ply"});
}

TEST(IoRead, CannotOpenIsAnIOError) {
  const fs::path dir = output_dir();
  EXPECT_EQ(test::message_of<IOError>([&] { read_mesh(dir / "missing.obj"); }),
            (dir / "missing.obj").string() + ": cannot open: No such file or directory");
  fs::create_directories(dir / "folder.off");
  EXPECT_EQ(test::message_of<IOError>([&] { read_mesh(dir / "folder.off"); }),
            (dir / "folder.off").string() + ": is a directory");
}

TEST(IoRead, UnreadableFileIsAnIOError) {
  if (::geteuid() == 0) GTEST_SKIP() << "root reads every file";
  const fs::path path = write_file("locked.obj", "v 0 0 0\n");
  fs::permissions(path, fs::perms::none);
  EXPECT_EQ(test::message_of<IOError>([&] { read_mesh(path); }), path.string() + ": cannot open: Permission denied");
}

// A file of 32 MiB or more is paged in by a second thread while the parser reads it
// (src/io/mapped_file.cpp): the mesh must be the one the same bytes give from memory.
TEST(IoRead, LargeFileReadsAsItsBytes) {
  const fs::path path = output_dir() / "large.obj";
  write_mesh(sphere(1000000), path);
  ASSERT_GE(fs::file_size(path), uintmax_t(32) << 20);
  const PolygonMesh from_file = read_mesh(path);
  const PolygonMesh from_memory = read_mesh(test::read_file(path), MeshFormat::obj, path.string());
  EXPECT_EQ(from_file.positions, from_memory.positions);
  EXPECT_EQ(from_file.face_vertices, from_memory.face_vertices);
  EXPECT_EQ(from_file.face_start, from_memory.face_start);
}

// A refusal on the first line of a large file comes while the second thread is still
// paging it in: the file is closed without a crash (the thread stopped and joined), and
// the error is the one a small file gives.
TEST(IoRead, LargeFileRefusedEarlyNamesTheLine) {
  const fs::path path = output_dir() / "large_bad.obj";
  {
    std::ofstream out(path, std::ios::binary);
    out << "v 0 0 x\n";
    const std::string comment = "# " + std::string(1 << 20, '#') + "\n";
    for (int i = 0; i < 40; ++i) out << comment;
  }
  ASSERT_GE(fs::file_size(path), uintmax_t(32) << 20);
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(test::message_of<InputError>([&] { read_mesh(path); }), path.string() + ":1: bad vertex coordinate 'x'");
}

TEST(IoRead, UnknownExtensionIsAUsageErrorNamingThePath) {
  const fs::path path = write_file("mesh.txt", "v 0 0 0\n");
  EXPECT_EQ(test::message_of<UsageError>([&] { read_mesh(path); }),
            path.string() + ": unknown mesh format '.txt' (Meander reads .obj, .ply, .stl, .off, .gltf and .glb, and writes those and .3mf)");
}

TEST(IoRead, ExtensionIsCaseInsensitive) {
  EXPECT_EQ(mesh_format_from_path("A.OBJ"), MeshFormat::obj);
  EXPECT_EQ(mesh_format_from_path("b.Ply"), MeshFormat::ply);
  EXPECT_EQ(mesh_format_from_path("dir.x/c.STL"), MeshFormat::stl);
  EXPECT_EQ(mesh_format_from_path("d.oFf"), MeshFormat::off);
  const fs::path path = write_file("TRI.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(read_mesh(path).num_faces(), 1);
}

TEST(IoRead, FromMemoryNamesTheGivenName) {
  const PolygonMesh m = read_mesh("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::off, "memory");
  EXPECT_EQ(m.num_faces(), 1);
  EXPECT_EQ(test::message_of<InputError>([] { read_mesh("", MeshFormat::ply, "memory"); }), "memory: file is empty");
}

// The real meshes, with the counts of ../shared/meshes/INDEX.md (STL: welded).
struct RealMesh {
  const char* file;
  int32_t vertices;
  int32_t faces;
};

constexpr RealMesh real_meshes[] = {
    {"bunny_closed.off", 34835, 69666},
    {"spot_triangulated.obj", 2930, 5856},
    {"spot_quadrangulated.obj", 2930, 2928},
    {"spot_control_mesh.obj", 188, 180},
    {"tetrahedron.obj", 4, 4},
    {"icosahedron_binary.stl", 12, 20},
    {"sphere.obj", 642, 1280},
    {"torus.obj", 2304, 4608},
    {"kitten.off", 10000, 20000},
    {"bob_small.ply", 250, 500},
    {"eight.off", 766, 1536},
    {"genus3hexa1.obj", 161, 82},
    {"fertility.off", 4494, 9000},
    {"fandisk_quads.off", 766, 764},
    {"stanford-bunny_original_holes.obj", 35947, 69451},
    {"face.obj", 25905, 51712},
    {"grid.off", 145, 256},
    {"camelhead.off", 11381, 22704},
    {"hourglass_ico.obj", 23, 40},
    {"triple_vierbein.obj", 75, 108},
    {"platonic_shelf.obj", 50, 50},
    {"degtri_four.off", 5, 4},
    {"conrod.stl", 3223, 6442},
    {"beveledcube.obj", 24, 26},
    {"moebius.obj", 280, 224},
};

TEST(IoRealMeshes, EveryMeshReadsWithItsIndexedCounts) {
  MEANDER_REQUIRE_SHARED_MESHES();
  for (const RealMesh& real : real_meshes) {
    SCOPED_TRACE(real.file);
    const PolygonMesh m = read_mesh(test::shared_meshes() / real.file);
    EXPECT_EQ(m.num_vertices(), real.vertices);
    EXPECT_EQ(m.num_faces(), real.faces);
    EXPECT_EQ(m.face_start.back(), m.num_corners());
  }
}

// A mesh added to the folder must be added to the table above too.
TEST(IoRealMeshes, TableCoversTheFolder) {
  MEANDER_REQUIRE_SHARED_MESHES();
  for (const auto& entry : fs::directory_iterator(test::shared_meshes())) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".obj" && extension != ".ply" && extension != ".stl" && extension != ".off") continue;
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(std::any_of(std::begin(real_meshes), std::end(real_meshes), [&](const RealMesh& r) {
      return name == r.file;
    })) << name;
  }
}

TEST(IoRealMeshes, MixedPolygonsKeepTheirSizes) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const PolygonMesh m = read_mesh(test::shared_meshes() / "spot_control_mesh.obj");
  std::map<int32_t, int32_t> sizes;
  for (int32_t f = 0; f < m.num_faces(); ++f) ++sizes[m.face_size(f)];
  EXPECT_EQ(sizes, (std::map<int32_t, int32_t>{{3, 4}, {4, 160}, {5, 16}}));
}

// Each real mesh written in every format and read back; STL compares welded.
TEST(IoRealMeshes, EveryMeshRoundTripsThroughEveryFormat) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const fs::path dir = output_dir();
  for (const RealMesh& real : real_meshes) {
    SCOPED_TRACE(real.file);
    const PolygonMesh m = read_mesh(test::shared_meshes() / real.file);
    for (const char* extension : {".obj", ".off", ".ply"})
      for (bool ascii : {false, true}) {
        const fs::path path = dir / (std::string("copy") + extension);
        write_mesh(m, path, {.ascii = ascii});
        expect_same_mesh(read_mesh(path), m);
      }
    bool triangles = true;
    for (int32_t f = 0; f < m.num_faces(); ++f) triangles &= m.face_size(f) == 3;
    write_mesh(m, dir / "copy.stl");
    const PolygonMesh stl = read_mesh(dir / "copy.stl");
    if (triangles) {
      EXPECT_EQ(stl.num_faces(), m.num_faces());
    }
    EXPECT_LE(stl.num_vertices(), m.num_vertices()); // unused and repeated positions go
  }
}

TEST(IoPolylines, ObjHasClosedLineElements) {
  Polylines curves;
  curves.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {5, 5, 5}, {6, 5, 5}, {6, 6, 5}, {5, 6, 5}};
  curves.start = {0, 3, 3, 7}; // the middle polyline is empty
  const fs::path path = output_dir() / "c.obj";
  write_polylines(curves, path);
  EXPECT_EQ(test::read_file(path), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 5 5 5\nv 6 5 5\nv 6 6 5\nv 5 6 5\n"
                         "l 1 2 3 1\nl 4 5 6 7 4\n");
}

TEST(IoPolylines, PlyHasClosingEdges) {
  Polylines curves;
  curves.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {7, 7, 7}};
  curves.start = {0, 3, 4}; // a single point has no edge
  const fs::path path = output_dir() / "c.ply";
  write_polylines(curves, path);
  const std::string bytes = test::read_file(path);
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
                             "property float y\nproperty float z\nelement edge 3\nproperty int vertex1\n"
                             "property int vertex2\nend_header\n";
  ASSERT_EQ(bytes.size(), header.size() + 4 * 12 + 3 * 8);
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  float p[12];
  std::memcpy(p, bytes.data() + header.size(), sizeof p);
  EXPECT_EQ(p[9], 7.0f);
  int32_t edges[6];
  std::memcpy(edges, bytes.data() + header.size() + sizeof p, sizeof edges);
  EXPECT_EQ(std::vector<int32_t>(edges, edges + 6), (std::vector<int32_t>{0, 1, 1, 2, 2, 0}));
}

TEST(IoPolylines, JsonListsThePoints) {
  Polylines curves;
  curves.points = {{0, 0.5f, 0}, {1, 0, -1e-7f}, {1, 1, 0}, {2, 2, 2}, {3, 2, 2}};
  curves.start = {0, 3, 5};
  const fs::path path = output_dir() / "c.json";
  write_polylines(curves, path);
  const nlohmann::json json = nlohmann::json::parse(test::read_file(path));
  ASSERT_EQ(json["polylines"].size(), 2u);
  EXPECT_EQ(json["polylines"][0]["closed"], true);
  ASSERT_EQ(json["polylines"][0]["points"].size(), 3u);
  EXPECT_EQ(json["polylines"][0]["points"][1][2].get<float>(), -1e-7f);
  EXPECT_EQ(json["polylines"][1]["points"][1], nlohmann::json::parse("[3,2,2]"));
  write_polylines(Polylines{}, path);
  EXPECT_EQ(nlohmann::json::parse(test::read_file(path))["polylines"].size(), 0u);
}

} // namespace
} // namespace meander
