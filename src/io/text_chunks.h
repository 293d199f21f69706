// Large text meshes read on all cores: the text cut into chunks at line starts, each read
// by a TextCursor of its own, and the faces of the chunks joined in their order. Readers
// take this way for what well-formed files hold and read the file again serially when a
// chunk meets anything else, so that every message is the serial reader's (file, line and
// problem): chunks never report.
#pragma once

#include "io/reader_support.h"
#include "io/text_cursor.h"
#include "meander/error.h"
#include "meander/mesh.h"

#include <algorithm>
#include <cstring>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

namespace meander::io {

struct TextChunk {
  std::string_view text; // whole lines
  int64_t before = 0;    // a reader's count (elements, vertices): the chunk's own, then the chunks' before it
  std::vector<int32_t> sizes, corners; // the faces read, in order
  bool failed = false;
};

// text[from ..) cut after line ends into chunks of about equal size, at least 64 KiB
// (one for less) and at most 64. A chunk after the first that starts with a byte order
// mark is failed: its TextCursor would skip what the serial one reads.
inline std::vector<TextChunk> cut_into_chunks(std::string_view text, size_t from) {
  const char* const end = text.data() + text.size();
  const size_t body = text.size() - from;
  const size_t chunks = std::clamp<size_t>(body / (size_t(64) << 10), 1, 64);
  std::vector<TextChunk> out(chunks);
  const char* begin = text.data() + from;
  for (size_t c = 0; c < chunks; ++c) {
    const char* q = c + 1 == chunks ? end : std::max(begin, text.data() + from + body / chunks * (c + 1));
    while (q != end && !is_line_end(q, end)) ++q;
    const char* cut = q == end ? end : q + 1;
    out[c].text = std::string_view(begin, size_t(cut - begin));
    out[c].failed = c > 0 && out[c].text.starts_with("\xEF\xBB\xBF");
    begin = cut;
  }
  return out;
}

// Calls line(first, line_end) for each line of `chunk`, `first` at its first byte that is
// neither a blank nor its end; `end` is the whole text's end. Line ends are found with
// memchr, and a chunk without a CR is not searched for one line by line: testing every
// byte was a large share of reading an OBJ (docs/curve.md, "Large meshes").
template <class Line>
void for_each_line(std::string_view chunk, const char* end, Line&& line) {
  const char* q = chunk.data();
  const char* const last = chunk.data() + chunk.size();
  const bool carriage_returns = std::memchr(q, '\r', chunk.size()) != nullptr;
  while (q != last) {
    while (q != last && TextCursor::is_blank(*q) && !is_line_end(q, end)) ++q;
    const char* const first = q;
    const char* const line_end = find_line_end(q, last, end, carriage_returns);
    line(first, line_end);
    q = line_end == last ? last : line_end + 1;
  }
}

// The chunks' counts made counts before each; false if a chunk failed. Returns the total.
inline bool count_before(std::vector<TextChunk>& chunks, int64_t& total) {
  total = 0;
  for (TextChunk& k : chunks) {
    if (k.failed) return false;
    total += std::exchange(k.before, total);
  }
  return true;
}

// Runs read(c, chunk c, a cursor on it) on every chunk in parallel, a chunk whose cursor
// fails being marked failed.
template <class Read>
void read_chunks(std::vector<TextChunk>& chunks, std::string_view name, Read&& read) {
  tbb::parallel_for(size_t(0), chunks.size(), [&](size_t c) {
    TextCursor in(chunks[c].text, name);
    try {
      read(c, chunks[c], in);
    } catch (const InputError&) {
      chunks[c].failed = true;
    }
  });
}

// The faces of the chunks, in order, as `mesh`'s faces, which readers check on the way
// out (require_faces); false if a chunk failed or the corners are too many.
inline bool join_faces(const std::vector<TextChunk>& chunks, PolygonMesh& mesh, std::string_view name) {
  std::vector<size_t> first_face(chunks.size() + 1, 0), first_corner(chunks.size() + 1, 0);
  for (size_t c = 0; c < chunks.size(); ++c) {
    if (chunks[c].failed) return false;
    first_face[c + 1] = first_face[c] + chunks[c].sizes.size();
    first_corner[c + 1] = first_corner[c] + chunks[c].corners.size();
  }
  if (!too_many(first_corner.back(), "face corners").empty()) return false;
  mesh.face_start.resize(first_face.back() + 1);
  mesh.face_start[0] = 0;
  mesh.face_vertices.resize(first_corner.back());
  tbb::parallel_for(size_t(0), chunks.size(), [&](size_t c) {
    const TextChunk& k = chunks[c];
    std::copy(k.corners.begin(), k.corners.end(), mesh.face_vertices.begin() + ptrdiff_t(first_corner[c]));
    int32_t at = int32_t(first_corner[c]);
    for (size_t f = 0; f < k.sizes.size(); ++f) mesh.face_start[first_face[c] + f + 1] = at += k.sizes[f];
  });
  require_faces(mesh, name);
  return true;
}

// What `chunked` reads, or, when it gives nothing, what `serially` reads.
inline PolygonMesh chunked_or_serially(std::string_view bytes, std::string_view name,
                                       std::optional<PolygonMesh> (*chunked)(std::string_view, std::string_view),
                                       PolygonMesh (*serially)(std::string_view, std::string_view)) {
  if (std::optional<PolygonMesh> mesh = chunked(bytes, name)) return std::move(*mesh);
  return serially(bytes, name);
}

} // namespace meander::io
