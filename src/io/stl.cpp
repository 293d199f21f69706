#include "io/binary.h"
#include "io/block_writer.h"
#include "io/formats.h"
#include "io/reader_support.h"
#include "io/text_cursor.h"
#include "io/welder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

namespace meander::io {
namespace {

// An ascii STL starts with "solid" and is text. A binary one may start with "solid" as
// well (many exporters put it in the header), but its triangle count and floats bring
// control bytes within the first kilobyte.
bool is_ascii_stl(std::string_view bytes) {
  const size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start == std::string_view::npos || bytes.substr(start, 5) != "solid") return false;
  const std::string_view head = bytes.substr(0, 1024);
  return std::all_of(head.begin(), head.end(), [](unsigned char c) { return c >= 0x20 || (c >= '\t' && c <= '\r'); });
}

PolygonMesh read_binary_stl(std::string_view bytes, size_t count, std::string_view name) {
  if (const std::string message = too_many(3 * count, "face corners"); !message.empty()) fail_input(name, message);
  PolygonMesh mesh;
  mesh.face_start.resize(count + 1);
  mesh.face_vertices.resize(3 * count);
  // A closed triangle mesh has about half as many vertices as triangles.
  Welder welder(mesh.positions, count / 2, name);
  for (size_t t = 0; t < count; ++t) {
    const char* corner = bytes.data() + 84 + 50 * t + 12; // past the normal
    for (size_t k = 0; k < 3; ++k, corner += 12) {
      const Vec3 p{load_little_endian<float>(corner), load_little_endian<float>(corner + 4),
                   load_little_endian<float>(corner + 8)};
      if (!is_finite(p)) fail_input(name, "face " + std::to_string(t) + ": " + non_finite_coordinate(p));
      mesh.face_vertices[3 * t + k] = welder.add(p);
    }
    mesh.face_start[t + 1] = int32_t(3 * (t + 1));
  }
  return mesh;
}

// solid, then facets of "facet normal n n n / outer loop / vertex x y z ... / endloop /
// endfacet", then endsolid; several solids may follow one another. Keywords are
// matched ignoring case, and a facet may hold more than three vertices.
PolygonMesh read_ascii_stl(std::string_view bytes, std::string_view name) {
  TextCursor in(bytes, name);
  PolygonMesh mesh;
  // An ascii facet takes about 250 bytes, and a closed mesh has half as many vertices as facets.
  Welder welder(mesh.positions, bytes.size() / 500, name);
  in.expect("solid");
  in.next_line();
  while (true) {
    if (in.accept("endsolid")) {
      in.next_line();
      in.skip_space();
      if (in.at_end()) break;
      in.expect("solid");
      in.next_line();
      continue;
    }
    if (in.at_end()) in.fail("file ends before 'endsolid'");
    in.expect("facet");
    in.expect("normal");
    for (int k = 0; k < 3; ++k) in.skip_number("normal coordinate");
    in.expect("outer");
    in.expect("loop");
    const size_t first = mesh.face_vertices.size();
    while (!in.accept("endloop")) {
      in.expect("vertex");
      mesh.face_vertices.push_back(welder.add(read_point(in)));
    }
    if (const size_t size = mesh.face_vertices.size() - first; size < 3) in.fail(too_few_vertices(int64_t(size)));
    in.expect("endfacet");
    mesh.face_start.push_back(int32_t(mesh.face_vertices.size()));
  }
  return mesh;
}

// Fans each face from its first vertex and calls f(a, b, c) for every triangle.
template <class F> void for_each_triangle(const PolygonMesh& mesh, F f) {
  for (int32_t face = 0; face < mesh.num_faces(); ++face) {
    const std::span<const int32_t> v = mesh.face(face);
    const Vec3 a = mesh.positions[size_t(v[0])];
    for (size_t k = 1; k + 1 < v.size(); ++k) f(a, mesh.positions[size_t(v[k])], mesh.positions[size_t(v[k + 1])]);
  }
}

// In float, which is what the file stores and cheaper than double; in double only for
// the triangles whose squared doubled area would underflow or overflow a float.
// Inlined: called out of line, the Vec3 arguments went through the stack and the
// shuffles took most of the binary writer's time.
[[gnu::always_inline]] inline Vec3 unit_normal(Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 n{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
  const float squared = n.x * n.x + n.y * n.y + n.z * n.z;
  if (squared >= 1e-30f && squared <= 1e30f) return n * (1 / std::sqrt(squared));
  const Vec3 precise = cross(e1, e2);
  const double length = norm(precise);
  return length > 0 ? precise * float(1 / length) : Vec3{};
}

} // namespace

PolygonMesh read_stl(std::string_view bytes, std::string_view name) {
  const uint64_t count = bytes.size() >= 84 ? load_little_endian<uint32_t>(bytes.data() + 80) : 0;
  PolygonMesh mesh;
  if (bytes.size() >= 84 && bytes.size() - 84 == 50 * count) {
    mesh = read_binary_stl(bytes, size_t(count), name);
  } else if (is_ascii_stl(bytes)) {
    mesh = read_ascii_stl(bytes, name);
  } else if (bytes.size() < 84) {
    fail_input(name, "not an STL file (no 'solid' at the start, and too short for a binary STL)");
  } else if (const uint64_t held = (bytes.size() - 84) / 50; held != count) {
    fail_input(name,
               "binary STL claims " + std::to_string(count) + " triangles but the file holds " + std::to_string(held));
  } else {
    fail_input(name, "binary STL of " + std::to_string(count) + " triangles has " +
                         std::to_string(bytes.size() - 84 - 50 * count) + " extra bytes at the end");
  }
  require_faces(mesh, name);
  return mesh;
}

void write_stl(const PolygonMesh& mesh, const MeshWriteOptions& options, Sink& out) {
  if (options.ascii) {
    out.text("solid meander\n");
    for_each_triangle(mesh, [&](Vec3 a, Vec3 b, Vec3 c) {
      out.text("facet normal ");
      write_point_line(out, unit_normal(a, b, c));
      out.text("outer loop\n");
      for (Vec3 p : {a, b, c}) {
        out.text("vertex ");
        write_point_line(out, p);
      }
      out.text("endloop\nendfacet\n");
    });
    out.text("endsolid meander\n");
    return;
  }
  // Not "solid...": readers that trust the first word would take the file for ascii.
  char header[80] = "binary STL written by Meander";
  out.bytes(header, sizeof header);
  uint32_t triangles = 0;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) triangles += uint32_t(std::max(mesh.face_size(f) - 2, 0));
  out.little_endian(triangles);
  write_blocks(out, mesh.num_faces(), 1 << 15, [&](int64_t begin, int64_t end, std::vector<char>& bytes) {
    size_t records = 0;
    for (int64_t f = begin; f < end; ++f) records += size_t(std::max(mesh.face_size(int32_t(f)) - 2, 0));
    bytes.resize(50 * records);
    char* at = bytes.data();
    for (int64_t f = begin; f < end; ++f) {
      const std::span<const int32_t> v = mesh.face(int32_t(f));
      const Vec3 a = mesh.positions[size_t(v[0])];
      for (size_t k = 1; k + 1 < v.size(); ++k) {
        const Vec3 b = mesh.positions[size_t(v[k])], c = mesh.positions[size_t(v[k + 1])];
        const Vec3 n = unit_normal(a, b, c);
        const float record[12] = {n.x, n.y, n.z, a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z};
        for (const float x : record) {
          store_little_endian(at, x);
          at += 4;
        }
        store_little_endian(at, uint16_t(0)); // attribute byte count
        at += 2;
      }
    }
  });
}

} // namespace meander::io
