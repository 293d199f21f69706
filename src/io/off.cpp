#include "io/formats.h"
#include "io/reader_support.h"
#include "io/text_cursor.h"

#include <algorithm>

namespace meander::io {
namespace {

// Headers are [ST][C][N]OFF: texture coordinates, colours and normals follow the
// coordinates on a vertex line and go with the rest of it. 4OFF and nOFF vertices have
// other than three coordinates, and binary OFF is another format: both are refused.
void read_header(TextCursor& in) {
  in.skip_space();
  const std::string_view magic = in.word();
  if (!magic.ends_with("OFF"))
    in.fail(magic.empty() ? "not an OFF file (no header)"
                          : "not an OFF file (expected 'OFF', found " + quoted(magic) + ")");
  std::string_view variant = magic.substr(0, magic.size() - 3);
  for (std::string_view option : {"ST", "C", "N"})
    if (variant.starts_with(option)) variant.remove_prefix(option.size());
  if (!variant.empty()) in.fail("unsupported OFF variant " + quoted(magic) + " (only [ST][C][N]OFF)");
  if (in.accept("BINARY")) in.fail("binary OFF is not supported");
}

int64_t read_count(TextCursor& in, std::string_view what, std::string_view things) {
  const int64_t count = in.integer(what);
  if (count < 0) in.fail("negative " + std::string(what));
  if (const std::string message = too_many(uint64_t(count), things); !message.empty()) in.fail(message);
  return count;
}

[[noreturn]] void fail_ends(TextCursor& in, int64_t expected, std::string_view things, int64_t found) {
  in.fail("expected " + std::to_string(expected) + " " + std::string(things) + " but the file ends after " +
          std::to_string(found));
}

} // namespace

PolygonMesh read_off(std::string_view bytes, std::string_view name) {
  TextCursor in(bytes, name);
  read_header(in);
  in.skip_space();
  const int64_t vertex_count = read_count(in, "vertex count", "vertices");
  const int64_t face_count = read_count(in, "face count", "faces");
  if (!in.at_line_end()) in.integer("edge count");
  in.next_line();

  PolygonMesh mesh;
  // The counts are only claims: reserve no more than the bytes left can hold (a vertex
  // line takes at least 6 bytes, "0 0 0\n", a face line at least 8).
  mesh.positions.reserve(size_t(std::min<int64_t>(vertex_count, int64_t(in.bytes_left() / 6))));
  for (int64_t i = 0; i < vertex_count; ++i) {
    in.skip_space();
    if (in.at_end()) fail_ends(in, vertex_count, "vertices", i);
    const float x = in.real("vertex coordinate");
    const float y = in.real("vertex coordinate");
    const float z = in.real("vertex coordinate");
    mesh.positions.push_back({x, y, z});
    in.next_line();
  }
  const size_t face_room = size_t(std::min<int64_t>(face_count, int64_t(in.bytes_left() / 8)));
  mesh.face_start.reserve(face_room + 1);
  mesh.face_vertices.reserve(3 * face_room);
  for (int64_t f = 0; f < face_count; ++f) {
    in.skip_space();
    if (in.at_end()) fail_ends(in, face_count, "faces", f);
    const int64_t size = in.integer("face size");
    if (size < 3) in.fail(too_few_vertices(size));
    for (int64_t k = 0; k < size; ++k) {
      const int64_t index = in.integer("vertex index");
      if (index < 0 || index >= vertex_count) in.fail(index_out_of_range(index, vertex_count));
      mesh.face_vertices.push_back(int32_t(index));
    }
    mesh.face_start.push_back(int32_t(mesh.face_vertices.size()));
    // Whatever follows the indices is a colour.
    in.next_line();
  }
  in.skip_space();
  if (!in.at_end()) in.fail("unexpected " + quoted(in.word()) + " after the last face");
  require_faces(mesh, name);
  return mesh;
}

void write_off(const PolygonMesh& mesh, AtomicFile& out) {
  out.text("OFF\n");
  out.integer(mesh.num_vertices());
  out.put(' ');
  out.integer(mesh.num_faces());
  out.text(" 0\n");
  for (const Vec3& p : mesh.positions) write_point_line(out, p);
  for (int32_t f = 0; f < mesh.num_faces(); ++f) write_counted_indices(out, mesh.face(f));
}

} // namespace meander::io
