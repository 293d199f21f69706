// write_cycle_curves samples the curve while it writes it, so that the points never all
// exist at once; its file must be the one write_polylines writes from cycle_curves, byte
// for byte, whatever the format, the smoothing, the samples and the number of curves.
#include "test_support.h"

#include "meander/curve.h"
#include "meander/curve_writer.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/pipeline.h"
#include "meander/shapes.h"

#include <chrono>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace meander::test {
namespace {

// A sphere and a torus side by side: one mesh, two components, two curves.
PolygonMesh sphere_and_torus(int32_t sphere_faces = 300, int32_t torus_faces = 400) {
  PolygonMesh m = sphere(sphere_faces);
  const PolygonMesh t = torus(torus_faces);
  const int32_t offset = m.num_vertices();
  for (const Vec3& p : t.positions) m.positions.push_back(p + Vec3{5, 0, 0});
  for (int32_t f = 0; f < t.num_faces(); ++f) {
    std::vector<int32_t> face(t.face(f).begin(), t.face(f).end());
    for (int32_t& v : face) v += offset;
    m.add_face(face);
  }
  return m;
}

// Separate triangles, a curve each: more curves than a writer patches one by one.
PolygonMesh triangle_soup(int32_t triangles) {
  PolygonMesh m;
  for (int32_t t = 0; t < triangles; ++t) {
    const Vec3 at{float(t % 50) * 2, float(t / 50) * 2, 0};
    for (const Vec3 corner : {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0.5f}}) m.positions.push_back(at + corner);
    m.add_face({3 * t, 3 * t + 1, 3 * t + 2});
  }
  return m;
}

std::vector<std::pair<std::string, PolygonMesh>> meshes() {
  std::vector<std::pair<std::string, PolygonMesh>> out = {
      {"sphere", sphere(200)},
      {"moebius", moebius(300)},
      {"genus 2", genus_surface(2, 2000)},
      {"sphere and torus", sphere_and_torus()},
      // 45,000 quads, 90,000 control points: with 3 samples a segment straddles the
      // writers' 65,536-point blocks.
      {"large sphere", sphere(30000)},
      {"triangle soup", triangle_soup(1500)},
  };
  if (std::filesystem::is_directory(shared_meshes()))
    out.emplace_back("platonic_shelf.obj (5 components)", read_mesh(shared_meshes() / "platonic_shelf.obj"));
  return out;
}

TEST(CurveStream, WritesTheSameBytesAsTheSampledCurve) {
  const auto dir = output_dir();
  const CurveOptions options[] = {{Smoothing::bspline, 4}, {Smoothing::bspline, 1}, {Smoothing::catmull_rom, 3},
                                  {Smoothing::none, 4}};
  for (const auto& [name, mesh] : meshes()) {
    const CurveResult made = make_curve(mesh, {.cycle = {.seed = 7}});
    for (const CurveOptions& option : options)
      for (const std::string extension : {".ply", ".obj", ".json"}) {
        const std::string what = name + ", smoothing " + std::to_string(int(option.smoothing)) + ", samples " +
                                 std::to_string(option.samples) + ", " + extension;
        const Polylines curves = cycle_curves(made.quads, made.cycle, option);
        write_polylines(curves, dir / ("held" + extension));
        const int64_t points = write_cycle_curves(made.quads, made.cycle, option, dir / ("streamed" + extension));
        EXPECT_EQ(points, int64_t(curves.points.size())) << what;
        const std::string held = read_file(dir / ("held" + extension));
        ASSERT_FALSE(held.empty()) << what;
        EXPECT_TRUE(held == read_file(dir / ("streamed" + extension))) << what;
      }
  }
}

TEST(CurveStream, PipelineCanLeaveTheSamplingToTheWriter) {
  const CurveResult sampled = make_curve(genus_surface(2, 2000), {.cycle = {.seed = 3}});
  const CurveResult unsampled = make_curve(genus_surface(2, 2000), {.cycle = {.seed = 3}, .sample = false});
  EXPECT_EQ(unsampled.curves.size(), 0);
  EXPECT_TRUE(unsampled.curves.points.empty());
  EXPECT_EQ(unsampled.cycle.order, sampled.cycle.order);
  EXPECT_EQ(unsampled.cycle.cycle_start, sampled.cycle.cycle_start);
}

// With an output, make_curve writes the file itself, laying a PLY out while the cycle
// is made; sampled or not, it holds what write_polylines writes of the held curve.
TEST(CurveStream, PipelineWritesTheOutputWhileMakingTheCycle) {
  const auto dir = output_dir();
  const PolygonMesh mesh = sphere_and_torus();
  const CurveResult held = make_curve(mesh, {.cycle = {.seed = 5}});
  for (const std::string extension : {".ply", ".obj"}) {
    write_polylines(held.curves, dir / ("held" + extension));
    for (const bool sample : {false, true}) {
      const auto out = dir / ("made" + extension);
      StageTimes times;
      const CurveResult made = make_curve(mesh, {.cycle = {.seed = 5}, .sample = sample, .output = out}, &times);
      EXPECT_EQ(made.points_written, int64_t(held.curves.points.size()));
      EXPECT_TRUE(read_file(out) == read_file(dir / ("held" + extension))) << extension << " " << sample;
      EXPECT_EQ(times.back().first, sample ? "write curve" : "smooth + write");
    }
  }
}

// The points a writer may write of a walk shown up to `walked` triangles: every segment
// of the closed cycles, and of the open one those with their control points before and
// two after walked, which leaves out its first segment and its last two.
int64_t settled_points(const TriangleCycle& cycle, int64_t walked, int k) {
  int64_t segments = 0;
  for (int32_t c = 0; c < cycle.num_cycles(); ++c) {
    const int64_t first = cycle.cycle_start[size_t(c)], end = cycle.cycle_start[size_t(c) + 1];
    if (end <= walked) segments += end - first;
    else if (walked - first >= 4) segments += walked - first - 3;
  }
  return segments * k;
}

// The writer's thread writes what the walk has settled while the walk goes on. Shown a
// walk in steps, it writes exactly the settled points before finish(), and the file is
// the same as ever.
TEST(CurveStream, WriterWritesThePointsOfTheWalkSoFar) {
  const auto dir = output_dir();
  for (const auto& [name, mesh] : meshes()) {
    const CurveResult made = make_curve(mesh, {.cycle = {.seed = 7}, .sample = false});
    for (const CurveOptions& option : {CurveOptions{Smoothing::bspline, 4}, CurveOptions{Smoothing::catmull_rom, 3}}) {
      write_polylines(cycle_curves(made.quads, made.cycle, option), dir / "held.ply");
      CycleCurveWriter writer(made.quads, option, dir / "walked.ply");
      const WalkObserver* observer = writer.observer();
      ASSERT_NE(observer, nullptr);
      // Steps of a thirteenth of the triangles, as the walk tells them.
      const int64_t total = made.cycle.num_triangles(), step = total / 13 + 1;
      for (int64_t walked = 0; walked < total;) {
        walked = std::min(walked + step, total);
        const auto closed = std::upper_bound(made.cycle.cycle_start.begin(), made.cycle.cycle_start.end(), int32_t(walked));
        observer->seen(std::span<const int32_t>(made.cycle.order.data(), size_t(walked)),
                       std::span<const int32_t>(made.cycle.cycle_start.begin(), closed));
        const int64_t settled = settled_points(made.cycle, walked, option.samples);
        // However long the thread takes (a stuck one is ctest's timeout to find).
        while (writer.points_written_while_walking() < settled) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        ASSERT_EQ(writer.points_written_while_walking(), settled) << name << " walked " << walked;
      }
      EXPECT_EQ(writer.finish(made.cycle), total * option.samples);
      EXPECT_TRUE(read_file(dir / "held.ply") == read_file(dir / "walked.ply")) << name;
    }
  }
}

// Only a PLY's thread writes points while the walk goes on.
TEST(CurveStream, OnlyAPlyWriterObservesTheWalk) {
  const CurveResult made = make_curve(sphere(200), {.sample = false});
  CycleCurveWriter obj(made.quads, {}, output_dir() / "observed.obj");
  EXPECT_EQ(obj.observer(), nullptr);
}

// A writer destroyed before finish() (the cycle failed) leaves neither the file nor its
// temporary, though its thread was writing the PLY's edges.
TEST(CurveStream, UnfinishedWriterLeavesNoFile) {
  const auto dir = output_dir() / "unfinished";
  std::filesystem::create_directories(dir);
  const CurveResult made = make_curve(sphere(30000), {.sample = false});
  for (const std::string name : {"curve.ply", "curve.obj"}) {
    { CycleCurveWriter writer(made.quads, {}, dir / name); }
    EXPECT_TRUE(std::filesystem::is_empty(dir)) << name;
  }
}

// A curve file of more than 250 MB is written with its points a part at a time as the
// walk shows them; the writer then seeks back to close each of the two curves. Read
// back, it is still the curve in memory.
TEST(CurveStream, LargeFileReadsBackAsTheCurve) {
  const CurveResult made = make_curve(sphere_and_torus(12000, 12000), {.cycle = {.seed = 2}, .sample = false});
  const int64_t triangles = made.cycle.num_triangles();
  const CurveOptions options{Smoothing::bspline, int(14'000'000 / triangles + 1)};
  const auto out = output_dir() / "behind.ply";
  {
    CycleCurveWriter writer(made.quads, options, out);
    writer.observer()->seen(made.cycle.order, made.cycle.cycle_start);
    ASSERT_EQ(writer.finish(made.cycle), triangles * options.samples);
  }
  ASSERT_GT(std::filesystem::file_size(out), uintmax_t(250) << 20);
  const Polylines expected = cycle_curves(made.quads, made.cycle, options), read = read_polylines(out);
  ASSERT_EQ(read.size(), 2);
  EXPECT_TRUE(read.closed(0) && read.closed(1));
  EXPECT_EQ(read.start, expected.start);
  EXPECT_TRUE(read.points == expected.points);
  std::filesystem::remove(out);
}

TEST(CurveStream, RefusesBadSamplesBeforeAnyFile) {
  const CurveResult made = make_curve(sphere(200), {});
  const auto out = output_dir() / "curve.ply";
  EXPECT_THROW(write_cycle_curves(made.quads, made.cycle, {.samples = 0}, out), UsageError);
  EXPECT_FALSE(std::filesystem::exists(out));
}

// The CLI streams the curve unless it also renders it (--png needs the points in
// memory): both ways give the same file.
TEST(CurveStream, CliStreamedFileEqualsTheHeldOne) {
  const auto dir = output_dir();
  const auto in = dir / "in.ply";
  write_mesh(sphere_and_torus(), in);
  for (const std::vector<std::string>& flags : {std::vector<std::string>{}, {"--smooth", "catmull-rom", "--samples", "2"},
                                               {"--smooth", "none"}})
    for (const std::string extension : {".ply", ".obj"}) {
      std::vector<std::string> streamed = {"curve", in.string(), "-o", (dir / ("s" + extension)).string()};
      std::vector<std::string> held = {"curve", in.string(), "-o", (dir / ("h" + extension)).string(),
                                       "--png", (dir / "h.png").string(), "--size", "64x48"};
      streamed.insert(streamed.end(), flags.begin(), flags.end());
      held.insert(held.end(), flags.begin(), flags.end());
      const CommandResult s = run_cli(streamed), h = run_cli(held);
      ASSERT_EQ(s.exit_code, 0) << s.err;
      ASSERT_EQ(h.exit_code, 0) << h.err;
      const std::string held_bytes = read_file(dir / ("h" + extension));
      ASSERT_FALSE(held_bytes.empty());
      EXPECT_TRUE(held_bytes == read_file(dir / ("s" + extension))) << extension << " " << flags.size();
    }
}

} // namespace
} // namespace meander::test
