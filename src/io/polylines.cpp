#include "io/atomic_file.h"
#include "io/formats.h"
#include "io/polyline_stream.h"
#include "io/reader_support.h"
#include "meander/error.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string>

#include <tbb/parallel_for.h>

namespace meander {
namespace {

// Points per block when a writer asks a PolylineStream for them: 768 KB, small beside
// the curves it is for and large enough that the per-block cost does not show.
constexpr int64_t block_points = 1 << 16;

// Calls f(points) for the points [begin, end) of the stream, in order, a block at a time.
template <class F> void for_each_block(const io::PolylineStream& curves, int64_t begin, int64_t end, F&& f) {
  std::vector<Vec3> block(size_t(std::clamp<int64_t>(end - begin, 0, block_points)));
  for (int64_t b = begin; b < end; b += block_points) {
    const int64_t e = std::min(end, b + block_points);
    curves.points(b, e, block.data());
    f(std::span<const Vec3>(block.data(), size_t(e - b)));
  }
}

void write_obj_polylines(const io::PolylineStream& curves, io::Sink& out) {
  for_each_block(curves, 0, curves.start.back(), [&](std::span<const Vec3> points) {
    for (const Vec3& p : points) {
      out.text("v ");
      io::write_point_line(out, p);
    }
  });
  for (int32_t k = 0; k < curves.size(); ++k) {
    const int32_t first = curves.start[k], end = curves.start[k + 1];
    // An empty polyline has no element to write, and an open one of one point no line.
    if (first == end || (!curves.closed(k) && end - first < 2)) continue;
    out.put('l');
    for (int32_t i = first; i < end; ++i) {
      out.put(' ');
      out.integer(int64_t(i) + 1);
    }
    // The first index repeated is what tells a reader that the line closes.
    if (curves.closed(k)) {
      out.put(' ');
      out.integer(int64_t(first) + 1);
    }
    out.put('\n');
  }
}

void write_ply_polylines(const io::PolylineStream& curves, io::Sink& out) {
  io::write_ply_points(curves, out, io::write_ply_layout(curves, out));
}

void write_json_polylines(const io::PolylineStream& curves, io::Sink& out) {
  out.text("{\"polylines\": [");
  for (int32_t k = 0; k < curves.size(); ++k) {
    out.text(k == 0 ? "\n  " : ",\n  ");
    out.text(curves.closed(k) ? "{\"closed\": true, \"points\": [" : "{\"closed\": false, \"points\": [");
    bool first = true;
    for_each_block(curves, curves.start[k], curves.start[k + 1], [&](std::span<const Vec3> points) {
      for (const Vec3& p : points) {
        out.text(first ? "[" : ", [");
        first = false;
        out.real(p.x);
        out.put(',');
        out.real(p.y);
        out.put(',');
        out.real(p.z);
        out.put(']');
      }
    });
    out.text("]}");
  }
  out.text(curves.size() > 0 ? "\n]}\n" : "]}\n");
}

} // namespace

namespace {

// A closed polyline of n >= 2 points has n edges, an open one n - 1; a single point has
// none. Entry k: the first edge of polyline k.
std::vector<int64_t> ply_edge_start(const io::PolylineStream& curves) {
  std::vector<int64_t> edge_start(size_t(curves.size()) + 1, 0);
  for (int32_t k = 0; k < curves.size(); ++k) {
    const int32_t n = curves.start[k + 1] - curves.start[k];
    edge_start[size_t(k) + 1] = edge_start[size_t(k)] + (n < 2 ? 0 : curves.closed(k) ? n : n - 1);
  }
  return edge_start;
}

} // namespace

uint64_t io::write_ply_layout(const PolylineStream& curves, Sink& out) {
  const std::vector<int64_t> edge_start = ply_edge_start(curves);
  out.text("ply\nformat binary_little_endian 1.0\nelement vertex ");
  out.integer(curves.start.back());
  out.text("\nproperty float x\nproperty float y\nproperty float z\nelement edge ");
  out.integer(edge_start.back());
  out.text("\nproperty int vertex1\nproperty int vertex2\nend_header\n");
  const uint64_t points_at = out.position();
  write_ply_edges(curves, out, points_at);
  return points_at;
}

namespace {

// Bytes [offset, offset + size) of records of `record` bytes at dst: make(first, count,
// at) writes the records [first, first + count) at `at`, which may have any alignment;
// a record that the range cuts is made apart and its part copied. Whole records are made
// in parallel blocks.
template <class Make> void fill_records(uint64_t offset, size_t size, char* dst, size_t record, Make&& make) {
  std::array<char, 16> one;
  int64_t r = int64_t(offset / record);
  if (const size_t skip = size_t(offset % record); skip > 0 && size > 0) {
    make(r++, 1, one.data());
    const size_t n = std::min(record - skip, size);
    std::memcpy(dst, one.data() + skip, n);
    dst += n;
    size -= n;
  }
  const int64_t whole = int64_t(size / record);
  tbb::parallel_for(int64_t(0), (whole + block_points - 1) / block_points, [&](int64_t b) {
    const int64_t first = b * block_points, count = std::min(block_points, whole - first);
    make(r + first, count, dst + size_t(first) * record);
  });
  if (const size_t rest = size - size_t(whole) * record; rest > 0) {
    make(r + whole, 1, one.data());
    std::memcpy(dst + size_t(whole) * record, one.data(), rest);
  }
}

} // namespace

void io::write_ply_edges(const PolylineStream& curves, Sink& out, uint64_t points_at) {
  const std::vector<int64_t> edge_start = ply_edge_start(curves);
  out.seek(points_at + 12 * uint64_t(curves.start.back()));
  // Edges [begin, begin + count) at `at`.
  const auto edges = [&](int64_t begin, int64_t count, char* at) {
    const int64_t end = begin + count;
    // Edge i of polyline k joins points first + i and first + i + 1, the last of a closed
    // one back to its first.
    // A run of a polyline's edges is a loop the compiler vectorises (120M edges for a
    // 10M-triangle curve).
    size_t k = size_t(std::upper_bound(edge_start.begin(), edge_start.end(), begin) - edge_start.begin()) - 1;
    for (int64_t e = begin; e < end;) {
      while (e >= edge_start[k + 1]) ++k;
      const int32_t first = curves.start[k], last = curves.start[k + 1] - 1;
      const int32_t from = first + int32_t(e - edge_start[k]);
      const int32_t n = int32_t(std::min(end, edge_start[k + 1]) - e);
      for (int32_t j = 0; j < n; ++j) {
        io::store_little_endian(at + 8 * size_t(j), from + j);
        io::store_little_endian(at + 8 * size_t(j) + 4, from + j + 1);
      }
      at += 8 * size_t(n);
      e += n;
      if (from + n - 1 == last) io::store_little_endian(at - 4, first); // a closed one's last edge
    }
  };
  out.fill(8 * uint64_t(edge_start.back()), [&](uint64_t offset, size_t size, char* dst) {
    fill_records(offset, size, dst, 8, edges);
  });
}

void io::write_ply_points(const PolylineStream& curves, Sink& out, uint64_t points_at) {
  write_ply_points(curves, out, points_at, 0, curves.start.back());
}

void io::write_ply_points(const PolylineStream& curves, Sink& out, uint64_t points_at, int64_t begin, int64_t end) {
  out.seek(points_at + 12 * uint64_t(begin));
  // Points [first, first + count) of the range at `at`. A point's three floats are its
  // record: on a little-endian host sampled straight into place where `at` is aligned for
  // floats, else through a small buffer.
  const auto points = [&](int64_t first, int64_t count, char* at) {
    if (host_is_little_endian && sizeof(Vec3) == 12 && reinterpret_cast<uintptr_t>(at) % alignof(Vec3) == 0) {
      curves.points(begin + first, begin + first + count, reinterpret_cast<Vec3*>(at));
      return;
    }
    std::array<Vec3, 1024> some;
    for (int64_t i = 0; i < count; i += int64_t(some.size())) {
      const int64_t n = std::min<int64_t>(count - i, int64_t(some.size()));
      curves.points(begin + first + i, begin + first + i + n, some.data());
      for (int64_t j = 0; j < n; ++j, at += 12) {
        io::store_little_endian(at, some[size_t(j)].x);
        io::store_little_endian(at + 4, some[size_t(j)].y);
        io::store_little_endian(at + 8, some[size_t(j)].z);
      }
    }
  };
  out.fill(12 * uint64_t(end - begin), [&](uint64_t offset, size_t size, char* dst) {
    fill_records(offset, size, dst, 12, points);
  });
}

Polylines io::chain_edges(std::span<const Vec3> positions, std::span<const int32_t> edges, std::string_view name) {
  const int32_t num_edges = int32_t(edges.size() / 2);
  // The two edges a polyline vertex may have (-1: none); a third would be a branch.
  std::vector<int32_t> incident(2 * positions.size(), -1);
  for (int32_t e = 0; e < num_edges; ++e) {
    const int32_t a = edges[2 * size_t(e)], b = edges[2 * size_t(e) + 1];
    if (a == b) fail_input(name, "edge " + std::to_string(e) + ": joins vertex " + std::to_string(a) + " to itself");
    for (const int32_t v : {a, b}) {
      int32_t* slot = &incident[2 * size_t(v)];
      if (slot[0] < 0)
        slot[0] = e;
      else if (slot[1] < 0)
        slot[1] = e;
      else
        fail_input(name, "edge " + std::to_string(e) + ": vertex " + std::to_string(v) + " already joins edges " +
                             std::to_string(slot[0]) + " and " + std::to_string(slot[1]) +
                             " (a polyline does not branch)");
    }
  }
  const auto other_edge = [&](int32_t v, int32_t e) { return incident[2 * size_t(v)] == e ? incident[2 * size_t(v) + 1] : incident[2 * size_t(v)]; };
  const auto other_end = [&](int32_t e, int32_t v) { return edges[2 * size_t(e)] == v ? edges[2 * size_t(e) + 1] : edges[2 * size_t(e)]; };

  Polylines out;
  std::vector<uint8_t> used(size_t(num_edges), 0);
  bool any_open = false;
  for (int32_t first = 0; first < num_edges; ++first) {
    if (used[size_t(first)]) continue;
    // Each chain starts at its first edge in the file, in that edge's direction, so that
    // what write_polylines wrote reads back point for point; an open chain is first
    // walked back to its end.
    int32_t start = edges[2 * size_t(first)], e = first;
    bool closed = false;
    for (int32_t back = other_edge(start, e); back >= 0; back = other_edge(start, e)) {
      if (back == first) {
        closed = true;
        start = edges[2 * size_t(first)], e = first;
        break;
      }
      start = other_end(back, start), e = back;
    }
    for (int32_t v = start;;) {
      out.points.push_back(positions[size_t(v)]);
      used[size_t(e)] = 1;
      v = other_end(e, v);
      if (v == start) break;
      e = other_edge(v, e);
      if (e < 0) {
        out.points.push_back(positions[size_t(v)]);
        break;
      }
    }
    out.start.push_back(int32_t(out.points.size()));
    out.open.push_back(!closed);
    any_open |= !closed;
  }
  if (out.size() == 0) fail_no_polylines(name, "no edges");
  if (!any_open) out.open.clear();
  return out;
}

namespace {

// The writer of a curve file's format, by its extension.
using PolylineWriter = void (*)(const io::PolylineStream&, io::Sink&);
PolylineWriter polyline_writer(const std::filesystem::path& path) {
  const std::string extension = io::lowercase_extension(path);
  if (extension == ".obj") return write_obj_polylines;
  if (extension == ".ply") return write_ply_polylines;
  if (extension == ".json") return write_json_polylines;
  throw UsageError(path.string() + ": unknown curve format '" + extension + "' (expected .obj, .ply or .json" +
                   (extension == ".svg" ? "; an SVG is a drawing (drawing.h)" : "") + ")");
}

io::PolylineStream stream_of(const Polylines& curves) {
  return {.start = curves.start, .open = curves.open, .points = [&](int64_t begin, int64_t end, Vec3* out) {
            std::copy(curves.points.begin() + begin, curves.points.begin() + end, out);
          }};
}

} // namespace

void io::write_polylines(const io::PolylineStream& curves, const std::filesystem::path& path) {
  const PolylineWriter write = polyline_writer(path);
  io::AtomicFile out(path);
  write(curves, out);
  out.commit();
}

void write_polylines(const Polylines& curves, const std::filesystem::path& path) {
  io::write_polylines(stream_of(curves), path);
}

std::string polylines_file_bytes(const Polylines& curves, const std::filesystem::path& name) {
  const PolylineWriter write = polyline_writer(name);
  io::MemorySink out;
  write(stream_of(curves), out);
  return out.take();
}

} // namespace meander
