#include "io/formats.h"
#include "io/obj_indices.h"
#include "io/text_chunks.h"

#include <algorithm>
#include <optional>
#include <vector>

namespace meander::io {

namespace {

// The corners of a face line, after its keyword, appended to `corners`, `defined`
// vertices being defined before it; returns how many.
int32_t read_face(TextCursor& in, ForwardIndices& forward, int64_t defined, std::vector<int32_t>& corners) {
  const size_t first = corners.size();
  while (!in.at_line_end()) corners.push_back(forward.resolve(in, in.integer("vertex index", '/'), "face", defined));
  const size_t size = corners.size() - first;
  if (size < 3) in.fail(too_few_vertices(int64_t(size)));
  return int32_t(size);
}

// Element by element, failing at the first problem with its line.
PolygonMesh read_serially(std::string_view bytes, std::string_view name) {
  TextCursor in(bytes, name);
  PolygonMesh mesh;
  ForwardIndices forward{"vertex"};
  while (!in.at_end()) {
    if (!in.at_line_end()) {
      const std::string_view keyword = in.word();
      if (keyword == "v") {
        read_position(in, mesh.positions);
      } else if (keyword == "f") {
        read_face(in, forward, int64_t(mesh.positions.size()), mesh.face_vertices);
        mesh.face_start.push_back(int32_t(mesh.face_vertices.size()));
      }
      // Other statements (vt, vn, o, g, usemtl, l, ...) are not needed, and neither are
      // stray lines that real files carry (beveledcube.obj ends with "1 14"): every OBJ
      // reader skips them, so refusing them would refuse files that open everywhere else.
    }
    in.next_line();
  }
  forward.check(name, "face", int64_t(mesh.positions.size()));
  require_faces(mesh, name);
  return mesh;
}

// The file read in chunks (text_chunks.h): a first pass counts each chunk's vertex lines
// (first word "v", as TextCursor::word reads it), so that the second knows how many
// vertices come before each line, which negative indices count back from. Nothing when
// a chunk fails, reads other vertices than the first pass counted, or holds an index
// past the last vertex.
std::optional<PolygonMesh> read_in_chunks(std::string_view bytes, std::string_view name) {
  const char* const end = bytes.data() + bytes.size();
  std::vector<TextChunk> chunks = cut_into_chunks(bytes, 0);
  tbb::parallel_for(size_t(0), chunks.size(), [&](size_t c) {
    for_each_line(chunks[c].text, end, [&](const char* first, const char* line_end) {
      chunks[c].before += first != line_end && *first == 'v' &&
                          (first + 1 == line_end || TextCursor::is_blank(first[1]) || first[1] == '\n');
    });
  });
  int64_t vertices = 0;
  if (!count_before(chunks, vertices) || vertices > max_count) return std::nullopt;
  PolygonMesh mesh;
  mesh.positions.resize(size_t(vertices));
  std::vector<int64_t> largest(chunks.size(), 0);
  read_chunks(chunks, name, [&](size_t c, TextChunk& k, TextCursor& in) {
    ForwardIndices forward{"vertex"};
    const int64_t last = c + 1 < chunks.size() ? chunks[c + 1].before : vertices;
    int64_t defined = k.before;
    while (!in.at_end()) {
      if (!in.at_line_end()) {
        const std::string_view keyword = in.word();
        if (keyword == "v") {
          if (defined == last) in.fail("a vertex the first pass did not count");
          mesh.positions[size_t(defined++)] = read_point(in);
        } else if (keyword == "f") {
          k.sizes.push_back(read_face(in, forward, defined, k.corners));
        }
      }
      in.next_line();
    }
    if (defined != last) in.fail("vertices the first pass counted but did not find");
    largest[c] = forward.largest;
  });
  if (std::any_of(largest.begin(), largest.end(), [&](int64_t index) { return index > vertices; })) return std::nullopt;
  if (!join_faces(chunks, mesh, name)) return std::nullopt;
  return mesh;
}

} // namespace

PolygonMesh read_obj(std::string_view bytes, std::string_view name) {
  return chunked_or_serially(bytes, name, read_in_chunks, read_serially);
}

Polylines read_obj_polylines(std::string_view bytes, std::string_view name) {
  TextCursor in(bytes, name);
  std::vector<Vec3> positions;
  std::vector<int32_t> start{0}, indices;
  std::vector<uint8_t> open;
  ForwardIndices forward{"vertex"};
  while (!in.at_end()) {
    if (!in.at_line_end()) {
      const std::string_view keyword = in.word();
      if (keyword == "v") {
        read_position(in, positions);
      } else if (keyword == "l") {
        const size_t first = indices.size();
        while (!in.at_line_end())
          indices.push_back(forward.resolve(in, in.integer("vertex index", '/'), "line", int64_t(positions.size())));
        const size_t size = indices.size() - first;
        if (size < 2) in.fail("line with " + std::to_string(size) + " vertices (at least 2 needed)");
        // A repeated first index (as write_polylines writes closed loops) is the
        // closing edge, not another point; a line that does not come back is open.
        const bool closed = size > 2 && indices.back() == indices[first];
        if (closed) indices.pop_back();
        if (indices.size() > size_t(max_count)) in.fail(too_many(indices.size(), "line points"));
        start.push_back(int32_t(indices.size()));
        open.push_back(!closed);
      }
    }
    in.next_line();
  }
  forward.check(name, "line", int64_t(positions.size()));
  if (start.size() == 1) fail_no_polylines(name, "l elements");
  Polylines curves;
  curves.start = std::move(start);
  if (std::find(open.begin(), open.end(), 1) != open.end()) curves.open = std::move(open);
  curves.points.reserve(indices.size());
  for (int32_t i : indices) curves.points.push_back(positions[i]);
  return curves;
}

void write_obj(const PolygonMesh& mesh, const MeshWriteOptions& options, Sink& out) {
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
