// Progress (progress.h): the stages a job shows, and its cancel seen between stages and
// inside the long loops (relaxation, the printability report).
#include "meander/connectivity.h"
#include "meander/jobs.h"
#include "meander/printability.h"
#include "meander/progress.h"
#include "meander/shapes.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace meander {
namespace {

TEST(Progress, ShowsTheStageAndItsFractionAndThrowsOnceCancelled) {
  Progress progress;
  EXPECT_EQ(progress.state().stage, "");
  progress.begin("cycle");
  EXPECT_EQ(progress.state().stage, "cycle");
  EXPECT_EQ(progress.state().fraction, -1);
  progress.advance(0.25);
  EXPECT_EQ(progress.state().fraction, 0.25);
  progress.begin("smooth");
  EXPECT_EQ(progress.state().fraction, -1) << "a new stage starts with no fraction";
  progress.cancel();
  EXPECT_TRUE(progress.cancelled());
  EXPECT_THROW(progress.check(), Cancelled);
  EXPECT_THROW(progress.advance(0.5), Cancelled);
  EXPECT_THROW(progress.begin("relax"), Cancelled);
}

TEST(Progress, AnAbandonedJobIsCancelled) {
  bool gone = false;
  Progress progress([&] { return gone; });
  progress.begin("cycle");
  gone = true;
  EXPECT_THROW(progress.begin("smooth"), Cancelled);
}

// The progress names the stages StageTimes records, in their order.
TEST(Progress, TheStagesAreThoseTheTimesName) {
  const PolygonMesh mesh = make_shape("torus", 600);
  StageTimes times;
  Progress progress;
  // Read after the job, the progress shows the last stage; the times list them all.
  const CurveResult made = make_curve(mesh, {.spacing = 0.5, .relax = 3}, &times, &progress);
  ASSERT_FALSE(times.empty());
  EXPECT_EQ(progress.state().stage, times.back().first);
  std::vector<std::string> names;
  for (const auto& [name, seconds] : times) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"remesh", "connectivity", "quadrangulate", "cycle", "smooth", "relax"}));
  EXPECT_EQ(made.curves.size(), 1);
}

TEST(Progress, ACancelledJobThrowsAtItsFirstCheck) {
  const PolygonMesh mesh = make_shape("torus", 600);
  Progress cancelled;
  cancelled.cancel();
  EXPECT_THROW(make_curve(mesh, {}, nullptr, &cancelled), Cancelled);
  const CurveResult curve = make_curve(mesh, {});
  EXPECT_THROW(make_wire(curve, {}, nullptr, &cancelled), Cancelled);
  EXPECT_THROW(make_duotone(mesh, build_connectivity(mesh), DuotoneJob{}, &cancelled), Cancelled);
}

// Inside the long loops: relaxation checks every round, the self-intersection search
// (the report's, the variable wire's) every block of triangles, the variable wire's
// clearing every round.
TEST(Progress, TheLongLoopsSeeACancel) {
  const PolygonMesh mesh = make_shape("torus", 600);
  const CurveResult curve = make_curve(mesh, {});
  const ClosestPoints closest(mesh);
  Progress relaxing;
  EXPECT_NO_THROW(relax_curves(curve.curves, mesh, closest, {.spacing = 0.5, .iterations = 2}, &relaxing));
  EXPECT_EQ(relaxing.state().fraction, 0.5) << "the second of 2 rounds began half way";
  relaxing.cancel();
  EXPECT_THROW(relax_curves(curve.curves, mesh, closest, {.spacing = 0.5, .iterations = 2}, &relaxing), Cancelled);

  // A wire far thicker than the gaps: every triangle's box meets many others.
  const WireResult thick = make_wire(curve, {.radius = 0.5, .report = false});
  Progress searching;
  const PrintabilityReport report = check_printability(thick.mesh, {.thickness = false}, &searching);
  EXPECT_TRUE(report.self_intersecting);
  EXPECT_GT(searching.state().fraction, 0) << "the search went block by block";
  Progress stopped;
  stopped.cancel();
  EXPECT_THROW(check_printability(thick.mesh, {.thickness = false}, &stopped), Cancelled);
  EXPECT_THROW(self_intersecting_faces(thick.mesh, {}, &stopped), Cancelled);

  // A variable ribbon's clearing rounds and their search, which take seconds on a large mesh.
  const VariableWireOptions ribbon{.shape = WireShape::ribbon, .levels = 1};
  Progress clearing;
  EXPECT_NO_THROW(variable_wire(curve.quads, curve.cycle, ribbon, &clearing));
  clearing.cancel();
  EXPECT_THROW(variable_wire(curve.quads, curve.cycle, ribbon, &clearing), Cancelled);
}

} // namespace
} // namespace meander
