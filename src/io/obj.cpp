#include "io/formats.h"
#include "io/reader_support.h"
#include "io/text_cursor.h"

namespace meander::io {
namespace {

std::string missing_vertex(int64_t index, int64_t vertex_count) {
  return "face references vertex " + std::to_string(index) + " but only " + std::to_string(vertex_count) + " exist";
}

} // namespace

PolygonMesh read_obj(std::string_view bytes, std::string_view name) {
  TextCursor in(bytes, name);
  PolygonMesh mesh;
  // A positive index may point forward, to a vertex defined further down, so positive
  // indices are checked once at the end against the final count: the largest one and
  // its line are enough to report the problem.
  int64_t largest_index = 0, largest_index_line = 0;
  while (!in.at_end()) {
    if (!in.at_line_end()) {
      const std::string_view keyword = in.word();
      if (keyword == "v") {
        if (int64_t(mesh.positions.size()) == max_count) in.fail(too_many(uint64_t(max_count) + 1, "vertices"));
        const float x = in.real("vertex coordinate");
        const float y = in.real("vertex coordinate");
        const float z = in.real("vertex coordinate");
        mesh.positions.push_back({x, y, z});
      } else if (keyword == "f") {
        const int64_t vertex_count = int64_t(mesh.positions.size());
        const size_t first = mesh.face_vertices.size();
        while (!in.at_line_end()) {
          const int64_t index = in.integer("vertex index", '/');
          if (index > 0) {
            if (index > largest_index) {
              largest_index = index;
              largest_index_line = in.line();
            }
            mesh.face_vertices.push_back(int32_t(index - 1));
          } else if (index < 0 && index >= -vertex_count) {
            mesh.face_vertices.push_back(int32_t(vertex_count + index));
          } else {
            in.fail(index == 0 ? "vertex index 0 is invalid (OBJ indices start at 1)"
                               : missing_vertex(index, vertex_count));
          }
        }
        if (const size_t size = mesh.face_vertices.size() - first; size < 3) in.fail(too_few_vertices(int64_t(size)));
        mesh.face_start.push_back(int32_t(mesh.face_vertices.size()));
      }
      // Other statements (vt, vn, o, g, usemtl, l, ...) are not needed, and neither are
      // stray lines that real files carry (beveledcube.obj ends with "1 14"): every OBJ
      // reader skips them, so refusing them would refuse files that open everywhere else.
    }
    in.next_line();
  }
  if (largest_index > int64_t(mesh.positions.size()))
    fail_at_line(name, largest_index_line, missing_vertex(largest_index, int64_t(mesh.positions.size())));
  require_faces(mesh, name);
  return mesh;
}

void write_obj(const PolygonMesh& mesh, const MeshWriteOptions& options, AtomicFile& out) {
  for (const Vec3& p : mesh.positions) {
    out.text("v ");
    write_point_line(out, p);
  }
  const std::span<const int32_t> group_start = options.group_start;
  size_t group = 0;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    // Empty groups are left out: an `o` line with no faces carries nothing.
    for (; group + 1 < group_start.size() && group_start[group] == f; ++group) {
      if (group_start[group + 1] == f) continue;
      out.text("o group_");
      out.integer(int64_t(group));
      out.put('\n');
    }
    out.put('f');
    for (int32_t v : mesh.face(f)) {
      out.put(' ');
      out.integer(int64_t(v) + 1);
    }
    out.put('\n');
  }
}

} // namespace meander::io
