#include "io/formats.h"
#include "io/reader_support.h"
#include "io/text_chunks.h"
#include "io/text_cursor.h"

#include <algorithm>
#include <optional>
#include <vector>

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

struct Counts {
  int64_t vertices = 0, faces = 0;
};

// The header and the counts line; leaves `in` at the first line after them.
Counts read_counts(TextCursor& in) {
  read_header(in);
  in.skip_space();
  Counts counts;
  counts.vertices = read_count(in, "vertex count", "vertices");
  counts.faces = read_count(in, "face count", "faces");
  if (!in.at_line_end()) in.integer("edge count");
  in.next_line();
  return counts;
}

// One vertex line (three coordinates, then whatever follows: colours, texture
// coordinates, normals) and one face line (a size, the indices, then a colour).
Vec3 read_vertex(TextCursor& in) {
  const Vec3 p = read_point(in);
  in.next_line();
  return p;
}

template <class Put>
void read_face(TextCursor& in, int64_t vertex_count, std::vector<int32_t>& corners, Put&& put_size) {
  const int64_t size = in.integer("face size");
  if (size < 3) in.fail(too_few_vertices(size));
  for (int64_t k = 0; k < size; ++k) {
    const int64_t index = in.integer("vertex index");
    if (index < 0 || index >= vertex_count) in.fail(index_out_of_range(index, vertex_count));
    corners.push_back(int32_t(index));
  }
  put_size(int32_t(size));
  in.next_line();
}

// Element by element, failing at the first problem with its line.
PolygonMesh read_serially(std::string_view bytes, std::string_view name) {
  TextCursor in(bytes, name);
  const Counts counts = read_counts(in);
  PolygonMesh mesh;
  // The counts are only claims: reserve no more than the bytes left can hold (a vertex
  // line takes at least 6 bytes, "0 0 0\n", a face line at least 8).
  mesh.positions.reserve(size_t(std::min<int64_t>(counts.vertices, int64_t(in.bytes_left() / 6))));
  for (int64_t i = 0; i < counts.vertices; ++i) {
    in.skip_space();
    if (in.at_end()) fail_ends(in, counts.vertices, "vertices", i);
    mesh.positions.push_back(read_vertex(in));
  }
  const size_t face_room = size_t(std::min<int64_t>(counts.faces, int64_t(in.bytes_left() / 8)));
  mesh.face_start.reserve(face_room + 1);
  mesh.face_vertices.reserve(3 * face_room);
  for (int64_t f = 0; f < counts.faces; ++f) {
    in.skip_space();
    if (in.at_end()) fail_ends(in, counts.faces, "faces", f);
    read_face(in, counts.vertices, mesh.face_vertices,
              [&](int32_t) { mesh.face_start.push_back(int32_t(mesh.face_vertices.size())); });
  }
  in.skip_space();
  if (!in.at_end()) in.fail("unexpected " + quoted(in.word()) + " after the last face");
  require_faces(mesh, name);
  return mesh;
}

// The bytes after the counts line read in chunks (text_chunks.h): each line holds one
// element (TextCursor reads an element's numbers on its line and skips the rest), so a
// first pass counts each chunk's elements (lines with a word that is not a comment) and
// a second reads them knowing which element comes first. Nothing when the elements are
// not those the counts claim, or a chunk fails.
std::optional<PolygonMesh> read_in_chunks(std::string_view bytes, std::string_view name) {
  TextCursor header(bytes, name);
  const Counts counts = read_counts(header);
  const char* const end = bytes.data() + bytes.size();
  std::vector<TextChunk> chunks = cut_into_chunks(bytes, bytes.size() - header.bytes_left());
  tbb::parallel_for(size_t(0), chunks.size(), [&](size_t c) {
    for_each_line(chunks[c].text, end, [&](const char* first, const char* line_end) {
      chunks[c].before += first != line_end && *first != '#';
    });
  });
  int64_t elements = 0;
  if (!count_before(chunks, elements) || elements != counts.vertices + counts.faces) return std::nullopt;
  PolygonMesh mesh;
  mesh.positions.resize(size_t(counts.vertices));
  read_chunks(chunks, name, [&](size_t, TextChunk& k, TextCursor& in) {
    for (int64_t e = k.before;; ++e) {
      in.skip_space();
      if (in.at_end()) break;
      if (e < counts.vertices)
        mesh.positions[size_t(e)] = read_vertex(in);
      else
        read_face(in, counts.vertices, k.corners, [&](int32_t size) { k.sizes.push_back(size); });
    }
  });
  if (!join_faces(chunks, mesh, name)) return std::nullopt;
  return mesh;
}

} // namespace

PolygonMesh read_off(std::string_view bytes, std::string_view name) {
  return chunked_or_serially(bytes, name, read_in_chunks, read_serially);
}

void write_off(const PolygonMesh& mesh, Sink& out) {
  out.text("OFF\n");
  out.integer(mesh.num_vertices());
  out.put(' ');
  out.integer(mesh.num_faces());
  out.text(" 0\n");
  for (const Vec3& p : mesh.positions) write_point_line(out, p);
  for (int32_t f = 0; f < mesh.num_faces(); ++f) write_counted_indices(out, mesh.face(f));
}

} // namespace meander::io
