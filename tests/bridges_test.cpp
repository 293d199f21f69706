// Bridges between a wire's neighbouring passes (issue 38): where they go, and the wire
// they make, judged by CGAL: one closed, outward solid free of self-intersection whose
// Euler characteristic is below zero (a free loop is a torus: 0).
#include "cgal_judge.h"
#include "test_support.h"

#include "meander/bridges.h"
#include "meander/check.h"
#include "meander/closest_points.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/jobs.h"
#include "meander/shapes.h"
#include "meander/solid_union.h"
#include "meander/textured_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace meander {
namespace {

struct Case {
  const char* name;
  PolygonMesh mesh;
  double spacing; // 0: the mesh's own edges
};

std::vector<Case> cases() {
  return {{"sphere", sphere(2000), 0.25},
          {"torus", torus(2000), 0.2},
          {"pretzel (genus 2)", genus_surface(2, 2000), 0.2},
          {"genus 3", genus_surface(3, 2000), 0.2},
          {"grid (a disc)", grid(1000), 0.08},
          {"torus, its own edges", torus(400), 0}};
}

// Arc length along each point's curve, and each curve's length.
struct Arcs {
  std::vector<double> at, length;
  std::vector<int32_t> curve;
  double along(int32_t i, int32_t j) const {
    const double d = std::abs(at[size_t(i)] - at[size_t(j)]);
    return std::min(d, length[size_t(curve[size_t(i)])] - d);
  }
};

Arcs arcs(const Polylines& lines) {
  Arcs a{.at = std::vector<double>(lines.points.size()), .curve = std::vector<int32_t>(lines.points.size())};
  for (int32_t c = 0; c < lines.size(); ++c) {
    double s = 0;
    for (int32_t i = lines.start[size_t(c)]; i < lines.start[size_t(c) + 1]; ++i) {
      a.at[size_t(i)] = s, a.curve[size_t(i)] = c;
      const int32_t next = i + 1 < lines.start[size_t(c) + 1] ? i + 1 : lines.start[size_t(c)];
      s += norm(lines.points[size_t(next)] - lines.points[size_t(i)]);
    }
    a.length.push_back(s);
  }
  return a;
}

// Distances by sampling, independent of the library's exact ones (and a little larger).
constexpr int kSteps = 64;
double point_distance(Vec3 x, Vec3 p, Vec3 q) {
  double best = INFINITY;
  for (int i = 0; i <= kSteps; ++i) best = std::min(best, norm(x - (p + (q - p) * (float(i) / kSteps))));
  return best;
}
double segment_distance(Vec3 p, Vec3 q, Vec3 r, Vec3 s) {
  double best = INFINITY;
  for (int i = 0; i <= kSteps; ++i) best = std::min(best, point_distance(p + (q - p) * (float(i) / kSteps), r, s));
  return best;
}

TEST(Bridges, GoBetweenNeighbouringPassesClearOfTheRestAndSpreadAlongTheCurve) {
  for (const Case& c : cases()) {
    if (c.spacing == 0) continue;
    SCOPED_TRACE(c.name);
    const CurveResult curve = make_curve(c.mesh, CurveJob{.spacing = c.spacing});
    const double radius = 0.2 * c.spacing, stretch = 4 * c.spacing, reach = 1.5 * c.spacing;
    const BridgePlan plan = plan_bridges(curve.curves, {.max_stretch = stretch, .radius = radius, .reach = reach});
    ASSERT_FALSE(plan.ends.empty());
    EXPECT_LE(plan.longest_stretch, stretch);
    EXPECT_TRUE(plan.one_piece);
    const Arcs a = arcs(curve.curves);
    std::vector<int32_t> ends;
    for (const auto& [i, j] : plan.ends) {
      const double d = norm(curve.curves.points[size_t(i)] - curve.curves.points[size_t(j)]);
      EXPECT_LE(d, reach);
      if (a.curve[size_t(i)] == a.curve[size_t(j)]) {
        EXPECT_GT(a.along(i, j), 1.4 * d); // another pass
      }
      ends.push_back(i), ends.push_back(j);
    }
    // 3 radii clear of each other and of every other part of the wire (points farther
    // along their curve than reach and 2 radii from both ends), and spread: on average at
    // least a quarter of the longest stretch apart.
    double total = 0;
    for (double l : a.length) total += l;
    EXPECT_LE(double(plan.ends.size()), total / (stretch / 4));
    for (size_t k = 0; k < plan.ends.size(); ++k) {
      const Vec3 p = curve.curves.points[size_t(plan.ends[k][0])], q = curve.curves.points[size_t(plan.ends[k][1])];
      // Bridges no longer than reach whose middles lie farther apart than reach + 3
      // radii are clear of each other; so are points farther than reach from the middle.
      for (size_t l = k + 1; l < plan.ends.size(); ++l) {
        const Vec3 r = curve.curves.points[size_t(plan.ends[l][0])], s = curve.curves.points[size_t(plan.ends[l][1])];
        if (norm((p + q) * 0.5f - (r + s) * 0.5f) < reach + 3 * radius) {
          ASSERT_GE(segment_distance(p, q, r, s), 3 * radius);
        }
      }
      for (int32_t m = 0; m < int32_t(curve.curves.points.size()); ++m) {
        const Vec3 x = curve.curves.points[size_t(m)];
        const bool joined = std::any_of(plan.ends[k].begin(), plan.ends[k].end(), [&](int32_t e) {
          return a.curve[size_t(m)] == a.curve[size_t(e)] && a.along(m, e) < reach + 2 * radius;
        });
        if (!joined && norm(x - (p + q) * 0.5f) < reach) {
          ASSERT_GE(point_distance(x, p, q), 3 * radius);
        }
      }
    }
  }
}

// One solid, judged by CGAL: closed, outward, clear of itself, one component with
// handles (a free loop is a torus), the struts adding to the free wire's volume, less
// than `most` times it.
void expect_one_rigid_solid(const PolygonMesh& bridged, const PolygonMesh& free, double most) {
  const MeshReport shape = inspect(bridged);
  ASSERT_EQ(shape.components.size(), 1u);
  EXPECT_LT(shape.components[0].euler_characteristic, 0);
  const test::CgalVerdict cgal = test::cgal_judge(bridged);
  ASSERT_TRUE(cgal.loaded);
  EXPECT_TRUE(cgal.closed);
  EXPECT_FALSE(cgal.self_intersecting);
  EXPECT_TRUE(cgal.outward);
  const double loop = test::cgal_judge(free).volume;
  EXPECT_GT(cgal.volume, loop);
  EXPECT_LT(cgal.volume, most * loop);
}

TEST(Bridges, MakeTheWireOneRigidSolid) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const double spacing = c.spacing > 0 ? c.spacing : 0.12;
    WireJob job{.curve = {.spacing = c.spacing > 0 ? std::optional(c.spacing) : std::nullopt}, .bridges = 4 * spacing};
    const CurveResult curve = make_curve(c.mesh, wire_curve_job(job));
    const WireResult free = make_wire(curve, WireJob{.curve = job.curve});
    const WireResult wire = make_wire(curve, job);
    EXPECT_GT(wire.bridges.ends.size(), 2u);
    EXPECT_TRUE(wire.bridges.one_piece);
    EXPECT_FALSE(wire.report.self_intersecting);
    EXPECT_TRUE(wire.report.watertight);
    expect_one_rigid_solid(wire.mesh, free.mesh, 1.5);
  }
}

// Where a strut meets the tube at a small angle, the union's crossing points, rounded
// to floats, turned thin triangles over into their neighbours: the demo pretzel at 1,600
// faces, 2 samples a segment and bridges every 0.5 crossed itself at two places.
TEST(Bridges, ManyBridgesStayClearOnceRoundedToFloats) {
  const WireJob job{.curve = {.curve = {.samples = 2}}, .bridges = 0.5};
  const CurveResult curve = make_curve(make_shape("pretzel", 1600), wire_curve_job(job));
  const WireResult wire = make_wire(curve, job);
  EXPECT_GT(wire.bridges.ends.size(), 500u);
  EXPECT_FALSE(wire.report.self_intersecting);
  const test::CgalVerdict cgal = test::cgal_judge(wire.mesh);
  ASSERT_TRUE(cgal.loaded);
  EXPECT_TRUE(cgal.closed);
  EXPECT_FALSE(cgal.self_intersecting);
  EXPECT_TRUE(cgal.outward);
}

TEST(Bridges, SameCurveSameWire) {
  for (const WireJob& job : {WireJob{.curve = {.spacing = 0.2}, .bridges = 0.8},
                             WireJob{.curve = {.spacing = 0.2}, .method = WireMethod::variable, .bridges = 0.8, .levels = 0}}) {
    const CurveResult curve = make_curve(torus(1000), wire_curve_job(job));
    const WireResult a = make_wire(curve, job);
    std::vector<std::unique_ptr<char[]>> heap; // another heap: no order of addresses may count
    for (int i = 0; i < 3000; ++i) heap.emplace_back(new char[size_t(16 + i * 37 % 300)]);
    const WireResult b = make_wire(curve, job);
    EXPECT_FALSE(a.bridges.ends.empty());
    EXPECT_TRUE(a.mesh.positions == b.mesh.positions);
    EXPECT_TRUE(a.mesh.face_vertices == b.mesh.face_vertices);
  }
}

// The variable wire is a slab thinner than it is wide: its struts are sized by the ball
// inside the slab at their ends, and kept clear of the slabs beside them by their width.
TEST(Bridges, MakeTheVariableWireOneRigidSolid) {
  const Case shapes[] = {{"sphere", sphere(500), 0},
                         {"torus", torus(500), 0},
                         {"pretzel (genus 2)", genus_surface(2, 700), 0},
                         {"genus 3", genus_surface(3, 900), 0},
                         {"grid (a disc)", grid(300), 0}};
  for (const Case& c : shapes) {
    SCOPED_TRACE(c.name);
    WireJob job{.method = WireMethod::variable, .levels = 1};
    const CurveResult curve = make_curve(c.mesh, wire_curve_job(job));
    const WireResult free = make_wire(curve, job);
    // Passes about the covered area over the curve's length apart; a bridge every 4.
    const Polylines centre = cycle_curves(curve.quads, curve.cycle, job.curve.curve);
    double area = 0;
    for (const auto& q : curve.quads.quads)
      area += 0.5 * (norm(cross(curve.quads.positions[size_t(q[1])] - curve.quads.positions[size_t(q[0])],
                                curve.quads.positions[size_t(q[2])] - curve.quads.positions[size_t(q[0])])) +
                     norm(cross(curve.quads.positions[size_t(q[2])] - curve.quads.positions[size_t(q[0])],
                                curve.quads.positions[size_t(q[3])] - curve.quads.positions[size_t(q[0])])));
    job.bridges = 4 * area / total_length(centre);
    const WireResult wire = make_wire(curve, job);
    EXPECT_GT(wire.bridges.ends.size(), 2u);
    EXPECT_TRUE(wire.bridges.every_pass_tied) << "longest stretch " << wire.bridges.longest_stretch << " of " << *job.bridges;
    EXPECT_FALSE(wire.report.self_intersecting);
    EXPECT_TRUE(wire.report.watertight);
    // Each strut is thinner than the slab it starts in: its caps lie inside the wire.
    ASSERT_EQ(wire.bridges.radii.size(), wire.bridges.ends.size());
    const ClosestPoints slab(free.mesh);
    std::vector<Vec3> ends;
    for (const auto& bridge : wire.bridges.ends)
      for (const int32_t e : bridge) ends.push_back(centre.points[size_t(e)]);
    const std::vector<uint8_t> inside = inside_solid(free.mesh, ends);
    for (size_t k = 0; k < ends.size(); ++k) {
      ASSERT_TRUE(inside[k]) << "bridge " << k / 2 << " ends outside the wire";
      ASSERT_LT(wire.bridges.radii[k / 2], norm(slab.closest(to_double(ends[k])) - to_double(ends[k])))
          << "bridge " << k / 2 << " is thicker than the slab";
    }
    expect_one_rigid_solid(wire.mesh, free.mesh, 1.2);
  }
}

TEST(Bridges, RefuseRibbonsAndBadLengths) {
  const CurveResult curve = make_curve(torus(600), CurveJob{});
  EXPECT_THROW(make_wire(curve, WireJob{.shape = WireShape::ribbon, .bridges = 1.0}), ParameterError);
  EXPECT_THROW(make_wire(curve, WireJob{.method = WireMethod::variable, .shape = WireShape::ribbon, .bridges = 1.0}),
               ParameterError);
  EXPECT_THROW(make_wire(curve, WireJob{.bridges = 0.0}), ParameterError);
  EXPECT_THROW(make_wire(curve, WireJob{.bridges = -1.0}), ParameterError);
  EXPECT_THROW(plan_bridges(curve.curves, {.max_stretch = 1, .radius = 0.1, .reach = 0.1}), ParameterError);
}

TEST(Bridges, TheCliSaysWhereTheyAreAndCgalAgrees) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = test::output_dir();
  const auto out = dir / "bridged.stl";
  const test::CommandResult r = test::run_cli({"wire", (test::shared_meshes() / "genus3hexa1.obj").string(), "-o", out.string(),
                                               "--spacing", "0.1", "--bridges", "0.4", "--png", (dir / "bridged.png").string(),
                                               "--size", "400x300"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The picture shows the bridges in their own colour, blue beside the copper wire.
  const Texture picture = read_texture(dir / "bridged.png");
  const auto blue = [](const Texture& t) {
    size_t n = 0;
    for (size_t i = 0; i + 3 < t.rgba.size(); i += 4) n += t.rgba[i + 2] > t.rgba[i] + 40;
    return n;
  };
  EXPECT_GT(blue(picture), 50u);
  EXPECT_NE(r.err.find("Bridges: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("every pass is tied to the rest"), std::string::npos) << r.err;
  const PolygonMesh wire = read_mesh(out);
  EXPECT_EQ(inspect(wire).components.size(), 1u);
  const test::CgalVerdict cgal = test::cgal_judge(wire);
  EXPECT_TRUE(cgal.closed);
  EXPECT_FALSE(cgal.self_intersecting);
  EXPECT_TRUE(cgal.outward);

  const test::CommandResult ribbon = test::run_cli({"wire", (test::shared_meshes() / "genus3hexa1.obj").string(), "-o",
                                                    (dir / "ribbon.stl").string(), "--shape", "ribbon", "--bridges", "0.4"});
  EXPECT_EQ(ribbon.exit_code, 2);
  const test::CommandResult free = test::run_cli({"wire", (test::shared_meshes() / "genus3hexa1.obj").string(), "-o",
                                                  (dir / "free.stl").string(), "--spacing", "0.1", "--png",
                                                  (dir / "free.png").string(), "--size", "400x300"});
  ASSERT_EQ(free.exit_code, 0) << free.err;
  EXPECT_EQ(blue(read_texture(dir / "free.png")), 0u);
  EXPECT_NE(ribbon.err.find("bridges"), std::string::npos) << ribbon.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "ribbon.stl"));

  MEANDER_REQUIRE(test::prusa_slicer_found(), "prusa-slicer is not installed (Debian's prusa-slicer; make test installs it)");
  const test::SlicerInfo info = test::prusa_slicer_info(out);
  ASSERT_EQ(info.status, 0) << info.text;
  EXPECT_TRUE(info.manifold) << info.text;
  EXPECT_EQ(info.parts, 1) << info.text; // one rigid piece
}

TEST(Bridges, TheVariableWireFromTheCliIsOnePiece) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = test::output_dir();
  const auto out = dir / "variable_bridged.stl";
  const std::vector<std::string> args = {"wire", (test::shared_meshes() / "genus3hexa1.obj").string(), "--method", "variable",
                                         "--levels", "1", "-o"};
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> all = args;
    all.insert(all.end(), more.begin(), more.end());
    return all;
  };
  const test::CommandResult r = test::run_cli(with({out.string(), "--bridges", "0.4"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("every pass is tied to the rest"), std::string::npos) << r.err;
  const test::CommandResult free = test::run_cli(with({(dir / "variable_free.stl").string()}));
  ASSERT_EQ(free.exit_code, 0) << free.err;
  expect_one_rigid_solid(read_mesh(out), read_mesh(dir / "variable_free.stl"), 1.2);
  MEANDER_REQUIRE(test::prusa_slicer_found(), "prusa-slicer is not installed (Debian's prusa-slicer; make test installs it)");
  const test::SlicerInfo info = test::prusa_slicer_info(out);
  ASSERT_EQ(info.status, 0) << info.text;
  EXPECT_TRUE(info.manifold) << info.text;
  EXPECT_EQ(info.parts, 1) << info.text;
}

} // namespace
} // namespace meander
