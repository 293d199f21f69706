#include "meander/curve_writer.h"

#include "io/atomic_file.h"
#include "io/formats.h"
#include "io/polyline_stream.h"
#include "meander/error.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <tbb/task_arena.h>
#include <thread>
#include <utility>
#include <vector>

namespace meander {

namespace {

// The curves of the cycles as a stream that samples them when asked, k points a segment.
io::PolylineStream cycle_stream(const QuadMesh& quads, const TriangleCycle& cycle, const CurveOptions& options) {
  const int k = points_per_segment(cycle.cycle_start.back(), options);
  io::PolylineStream out;
  out.start = cycle.cycle_start;
  for (int32_t& s : out.start) s *= k;
  out.points = [&quads, order = std::span<const int32_t>(cycle.order), start = std::span<const int32_t>(cycle.cycle_start),
                options](int64_t begin, int64_t end, Vec3* dst) {
    sample_cycle_curves(quads, order, start, options, begin, end, dst);
  };
  return out;
}

} // namespace

constexpr int32_t kMostPatchedCurves = 1024;

struct CycleCurveWriter::File {
  const QuadMesh& quads;
  std::filesystem::path path;
  CurveOptions options;
  int k = 1;
  int32_t points = 0;
  // A PLY's layout, written by `thread` as if the points made one closed curve: where the
  // points go, and the edges, of which only the last of each curve differs when there
  // are several. The thread then writes the points the walk has settled.
  std::optional<io::AtomicFile> ply;
  uint64_t points_at = 0;
  std::exception_ptr failure;
  std::thread thread;
  WalkObserver observer;
  // What the walk has shown, under `mutex`: the triangles walked, and where the cycles
  // walked start, the last start being the open cycle's (or the end of the last).
  std::mutex mutex;
  std::condition_variable changed;
  std::span<const int32_t> walked;
  std::vector<int32_t> starts{0};
  bool done = false;
  // How far the thread got, for finish() once it has stopped: the segments (one a
  // control point) before `next` are written, except segment `pending_first`, the first
  // of a cycle that was open when the thread reached it (-1: none).
  int64_t next = 0;
  int64_t pending_first = -1;
  std::atomic<int64_t> streamed{0};

  void stream_points();
  void write_segments(std::span<const int32_t> order, std::vector<int32_t> bounds, int64_t begin, int64_t end);
  void stop() {
    {
      std::lock_guard lock(mutex);
      done = true;
    }
    changed.notify_one();
    if (thread.joinable()) thread.join();
  }
};

// The points of segments [begin, end) of the cycles whose control points start at
// `bounds` (the last maybe only the part walked so far, whose end no segment reaches).
void CycleCurveWriter::File::write_segments(std::span<const int32_t> order, std::vector<int32_t> bounds, int64_t begin,
                                            int64_t end) {
  io::PolylineStream part;
  part.points = [&](int64_t from, int64_t to, Vec3* dst) {
    sample_cycle_curves(quads, order, bounds, options, from, to, dst);
  };
  // The walk has the other core.
  tbb::task_arena(1).execute([&] { io::write_ply_points(part, *ply, points_at, begin * k, end * k); });
  streamed += (end - begin) * k;
}

// A segment needs its cycle's control point before it and the two after it: the first
// segment of a cycle still open waits for the cycle to close, the last two for the walk
// to go on.
void CycleCurveWriter::File::stream_points() {
  constexpr int64_t most = int64_t(1) << 20; // segments between looks at `done`
  // The starts of the closed cycles that segments [begin, end) lie in, and their end.
  const auto bounds = [&](int64_t begin, int64_t end) {
    const auto from = std::upper_bound(starts.begin(), starts.end(), int32_t(begin)) - 1;
    const auto to = std::lower_bound(from, starts.end(), int32_t(end));
    return std::vector<int32_t>(from, to + 1);
  };
  std::unique_lock lock(mutex);
  for (;;) {
    if (done) return;
    const int64_t closed = starts.back(), open = int64_t(walked.size()) - closed;
    if (pending_first < 0 && next == closed && open >= 4) pending_first = next++;
    // The next segments to write, and the starts of the cycles they lie in.
    const bool closes_pending = pending_first >= 0 && pending_first < closed;
    const int64_t begin = closes_pending ? pending_first : next;
    int64_t end = 0;
    std::vector<int32_t> around;
    if (closes_pending || next < closed) {
      end = closes_pending ? begin + 1 : std::min(closed, next + most);
      around = bounds(begin, end);
    } else if (next > closed && next < closed + open - 2) {
      end = std::min(closed + open - 2, next + most);
      around = {int32_t(closed), int32_t(closed + open)};
    } else {
      changed.wait(lock);
      continue;
    }
    const std::span<const int32_t> order = walked;
    lock.unlock();
    write_segments(order, std::move(around), begin, end);
    if (closes_pending)
      pending_first = -1;
    else
      next = end;
    lock.lock();
  }
}

CycleCurveWriter::CycleCurveWriter(const QuadMesh& quads, const CurveOptions& options, const std::filesystem::path& path)
    : file_(new File{.quads = quads, .path = path, .options = options}) {
  int64_t triangles = 0;
  for (int32_t q = 0; q < quads.num_quads(); ++q) triangles += quads.is_half(q) ? 1 : 2;
  file_->k = points_per_segment(triangles, options);
  file_->points = int32_t(triangles * file_->k);
  if (io::lowercase_extension(path) != ".ply") return;
  file_->ply.emplace(path);
  file_->observer.seen = [f = file_.get()](std::span<const int32_t> walked, std::span<const int32_t> cycle_start) {
    {
      std::lock_guard lock(f->mutex);
      f->walked = walked;
      f->starts.insert(f->starts.end(), cycle_start.begin() + std::ptrdiff_t(f->starts.size()), cycle_start.end());
    }
    f->changed.notify_one();
  };
  file_->thread = std::thread([f = file_.get()] {
    try {
      f->points_at = io::write_ply_layout({.start = {0, f->points}}, *f->ply);
      f->stream_points();
    } catch (...) {
      f->failure = std::current_exception();
    }
  });
}

CycleCurveWriter::~CycleCurveWriter() { file_->stop(); }

const WalkObserver* CycleCurveWriter::observer() const { return file_->ply ? &file_->observer : nullptr; }

int64_t CycleCurveWriter::points_written_while_walking() const { return file_->streamed; }

int64_t CycleCurveWriter::finish(const TriangleCycle& cycle) {
  File& f = *file_;
  f.stop();
  if (f.failure) std::rethrow_exception(std::exchange(f.failure, nullptr));
  const io::PolylineStream out = cycle_stream(f.quads, cycle, f.options);
  if (out.start.back() != f.points)
    throw Error("internal error: the cycles of " + f.path.string() + " hold " + std::to_string(cycle.num_triangles()) +
                " triangles, not the " + std::to_string(f.points / f.k) + " laid out");
  if (!f.ply) {
    io::write_polylines(out, f.path);
  } else {
    if (f.pending_first >= 0) io::write_ply_points(out, *f.ply, f.points_at, f.pending_first * f.k, (f.pending_first + 1) * f.k);
    io::write_ply_points(out, *f.ply, f.points_at, f.next * f.k, f.points);
    // The last edge of each curve goes back to its own first point: patched one by one
    // while that costs less than writing all the edges again (a triangle soup has a
    // curve per triangle).
    if (out.size() > kMostPatchedCurves)
      io::write_ply_edges(out, *f.ply, f.points_at);
    else if (out.size() > 1)
      for (int32_t c = 0; c < out.size(); ++c) {
        const int32_t last = out.start[size_t(c) + 1] - 1;
        f.ply->seek(f.points_at + 12 * uint64_t(f.points) + 8 * uint64_t(last));
        f.ply->little_endian(last);
        f.ply->little_endian(out.start[size_t(c)]);
      }
    f.ply->commit();
  }
  return out.start.back();
}

// The cycles are known here: the file needs no writer of its own.
int64_t write_cycle_curves(const QuadMesh& quads, const TriangleCycle& cycle, const CurveOptions& options,
                           const std::filesystem::path& path) {
  const io::PolylineStream out = cycle_stream(quads, cycle, options);
  io::write_polylines(out, path);
  return out.start.back();
}

} // namespace meander
