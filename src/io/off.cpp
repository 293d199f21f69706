#include "io/formats.h"
#include "meander/error.h"
#include "io/reader_support.h"
#include "io/text_cursor.h"

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

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
  const float x = in.real("vertex coordinate");
  const float y = in.real("vertex coordinate");
  const float z = in.real("vertex coordinate");
  in.next_line();
  return {x, y, z};
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

bool is_blank(char c) { return TextCursor::is_blank(c) && c != '\r'; }

// A line ends at LF, CRLF or a lone CR, as TextCursor reads it.
bool is_line_end(const char* q, const char* end) { return *q == '\n' || (*q == '\r' && (q + 1 == end || q[1] != '\n')); }

// The bytes after the counts line cut into chunks at line starts, read on all cores: each
// line holds one element (TextCursor reads an element's numbers on its line and skips the
// rest), so a first pass counts each chunk's lines and elements (lines with a word that
// is not a comment), and a second reads them knowing which element comes first. Anything
// unusual (too few or too many elements, a bad number, a byte order mark at a chunk's
// start) returns nothing, and the file is read again serially, which names the problem
// as it always has.
std::optional<PolygonMesh> read_in_chunks(std::string_view bytes, std::string_view name) {
  TextCursor header(bytes, name);
  const Counts counts = read_counts(header);
  const size_t body_at = bytes.size() - header.bytes_left();
  const int64_t body_line = header.line();
  const char* const end = bytes.data() + bytes.size();
  constexpr size_t min_chunk = size_t(64) << 10;
  const size_t body = bytes.size() - body_at;
  const int chunks = int(std::clamp<size_t>(body / min_chunk, 1, 64));
  // Chunk c: bytes [cut[c], cut[c + 1]), each cut just after a line end.
  std::vector<const char*> cut(size_t(chunks) + 1, end);
  cut[0] = bytes.data() + body_at;
  for (int c = 1; c < chunks; ++c) {
    const char* q = std::max(cut[size_t(c) - 1], cut[0] + body / size_t(chunks) * size_t(c));
    while (q != end && !is_line_end(q, end)) ++q;
    cut[size_t(c)] = q == end ? end : q + 1;
  }
  struct Chunk {
    int64_t lines = 0, elements = 0; // counted in pass 1; then where the chunk's first ones are
    std::vector<int32_t> sizes, corners;
    bool failed = false;
  };
  std::vector<Chunk> chunk(static_cast<size_t>(chunks));
  tbb::parallel_for(0, chunks, [&](int c) {
    Chunk& k = chunk[size_t(c)];
    const char* q = cut[size_t(c)];
    const char* const last = cut[size_t(c) + 1];
    if (c > 0 && last - q >= 3 && std::string_view(q, 3) == "\xEF\xBB\xBF") k.failed = true;
    while (q != last) {
      while (q != last && is_blank(*q)) ++q;
      if (q != last && !is_line_end(q, end) && *q != '#') ++k.elements;
      while (q != last && !is_line_end(q, end)) ++q;
      if (q != last) {
        ++k.lines;
        ++q;
      }
    }
  });
  int64_t elements = 0, lines = body_line;
  for (Chunk& k : chunk) {
    if (k.failed) return std::nullopt;
    elements += std::exchange(k.elements, elements);
    lines += std::exchange(k.lines, lines);
  }
  if (elements != counts.vertices + counts.faces) return std::nullopt;
  PolygonMesh mesh;
  mesh.positions.resize(size_t(counts.vertices));
  tbb::parallel_for(0, chunks, [&](int c) {
    Chunk& k = chunk[size_t(c)];
    TextCursor in(std::string_view(cut[size_t(c)], size_t(cut[size_t(c) + 1] - cut[size_t(c)])), name, k.lines);
    try {
      for (int64_t e = k.elements;; ++e) {
        in.skip_space();
        if (in.at_end()) break;
        if (e < counts.vertices)
          mesh.positions[size_t(e)] = read_vertex(in);
        else
          read_face(in, counts.vertices, k.corners, [&](int32_t size) { k.sizes.push_back(size); });
      }
    } catch (const InputError&) {
      k.failed = true;
    }
  });
  size_t corners = 0;
  for (const Chunk& k : chunk) {
    if (k.failed) return std::nullopt;
    corners += k.corners.size();
  }
  if (!too_many(corners, "face corners").empty()) return std::nullopt;
  mesh.face_start.resize(size_t(counts.faces) + 1);
  mesh.face_vertices.resize(corners);
  std::vector<size_t> first_face(size_t(chunks) + 1, 0), first_corner(size_t(chunks) + 1, 0);
  for (int c = 0; c < chunks; ++c) {
    first_face[size_t(c) + 1] = first_face[size_t(c)] + chunk[size_t(c)].sizes.size();
    first_corner[size_t(c) + 1] = first_corner[size_t(c)] + chunk[size_t(c)].corners.size();
  }
  tbb::parallel_for(0, chunks, [&](int c) {
    const Chunk& k = chunk[size_t(c)];
    std::copy(k.corners.begin(), k.corners.end(), mesh.face_vertices.begin() + ptrdiff_t(first_corner[size_t(c)]));
    int32_t at = int32_t(first_corner[size_t(c)]);
    for (size_t f = 0; f < k.sizes.size(); ++f) mesh.face_start[first_face[size_t(c)] + f + 1] = at += k.sizes[f];
  });
  require_faces(mesh, name);
  return mesh;
}

} // namespace

PolygonMesh read_off(std::string_view bytes, std::string_view name) {
  if (std::optional<PolygonMesh> mesh = read_in_chunks(bytes, name)) return std::move(*mesh);
  return read_serially(bytes, name);
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
