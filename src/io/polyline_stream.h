// Polylines whose points are made when a writer asks for them, a block at a time, so that
// curves too large to hold (docs/curve.md, "Large meshes") are written without
// ever existing whole: write_cycle_curves in curve.h.
#pragma once

#include "io/sink.h"
#include "meander/io.h"
#include "meander/mesh.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

namespace meander::io {

// `start` and `open` as in Polylines; points(begin, end, out) writes the points [begin,
// end) of all the polylines, counted in order, to out[0 .. end - begin). It gives the same
// points whenever asked and may be called from several threads at once for disjoint ranges.
struct PolylineStream {
  std::vector<int32_t> start{0};
  std::vector<uint8_t> open;
  std::function<void(int64_t begin, int64_t end, Vec3* out)> points;

  int32_t size() const { return int32_t(start.size()) - 1; }
  bool closed(int32_t k) const { return open.empty() || open[k] == 0; }
};

// What write_polylines (meander/io.h) writes for the same points held in Polylines, byte
// for byte (write_polylines is this with the points copied out of the Polylines); no more
// than a few blocks of points exist at once.
void write_polylines(const PolylineStream& curves, const std::filesystem::path& path);

// write_polylines' PLY in two steps, for a writer that knows the polylines' sizes before
// their points: write_ply_layout writes the header and the edges, which depend on
// curves.start and curves.open alone (8 bytes an edge, a GB for a 10M-triangle curve),
// leaving room for the points and returning where they go; write_ply_points fills it,
// all of it or the points [begin, end) (a writer that gets its points a part at a time).
// write_ply_edges writes the edges again, for polylines of the same number of points.
uint64_t write_ply_layout(const PolylineStream& curves, Sink& out);
void write_ply_edges(const PolylineStream& curves, Sink& out, uint64_t points_at);
void write_ply_points(const PolylineStream& curves, Sink& out, uint64_t points_at);
void write_ply_points(const PolylineStream& curves, Sink& out, uint64_t points_at, int64_t begin, int64_t end);

} // namespace meander::io
