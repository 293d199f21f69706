// Wire and ribbon sculptures from the Hamiltonian cycle (paper Section 4): meshes that
// can be rendered and 3D printed.
//
// Both methods follow the cycle as a ladder: two rails, left and right of the direction
// of travel seen from the surface's outside. On an orientable surface the left rail
// stays left all the way round, so every cycle gives a closed tube (a torus) or a closed
// band (an annulus) whose faces point away from the surface's inside. On a
// non-orientable surface the rails swap once per orientation-reversing loop; the tube
// then closes with its cross-section turned half a turn (still a torus, still
// consistently oriented) and the band becomes a Moebius band.
#pragma once

#include "meander/curve.h"
#include "meander/hamiltonian.h"
#include "meander/mesh.h"
#include "meander/progress.h"
#include "meander/quadrangulate.h"

#include <optional>
#include <string_view>
#include <vector>

namespace meander {

enum class WireShape {
  wire,   // a closed solid tube: what a printer makes
  ribbon, // a band lying on the surface (open: two boundary loops per cycle)
};

// Parses "wire" | "ribbon"; throws UsageError otherwise.
WireShape parse_wire_shape(std::string_view name);

// Constant diameter (Section 4, first method): a regular polygon (wire) or a line
// segment (ribbon) swept along the smooth curve of the cycle.
struct ConstantWireOptions {
  WireShape shape = WireShape::wire;
  // Tube radius, or half the ribbon's width; > 0, in mesh units. None (the default):
  // `--radius auto`, the largest without self-intersection (auto_wire_radius).
  std::optional<double> radius;
  int sides = 8; // sides of the swept polygon (wire only), >= 3
  CurveOptions curve;
};

struct ConstantWire {
  PolygonMesh mesh; // empty when no radius avoids a self-intersection
  double radius = 0; // the radius used: options.radius, or the automatic one (0: none exists)
};

// Sweeps along cycle_curves(quads, cycle, options.curve). The frame at each point of
// the curve comes from the surface normal (the weighted normals of the cycle's
// triangles, blended like the control points), made perpendicular to the curve: the
// curve lies on the surface, so this frame does not twist (Section 1.1), and because it
// is computed per point rather than transported, the tube closes without a seam twist.
// Wire: `sides` vertices and `sides` quads per curve point; ribbon: two vertices and one
// quad per curve point. Without options.radius, the radius is auto_wire_radius's, found
// on the same curve and frames as the wire (computed once); if the curve touches itself
// the result is {empty mesh, radius 0}. Throws UsageError for a radius that is not a
// positive number or sides < 3. O(output), plus the radius search for auto.
ConstantWire constant_wire(const QuadMesh& quads, const TriangleCycle& cycle, const ConstantWireOptions& options);

// The same along closed curves given with the surface's normal at each point (either
// orientation: they are made to agree along each curve, a curve whose last normal then
// disagrees with its first is taken for one on a Möbius band), as relax_curves makes them
// about a quarter of `spacing` apart; options.curve is not used. The normals are
// smoothed along the curve first (they come from the faces). Throws ParameterError as
// constant_wire does, and for normals not one per point.
ConstantWire constant_wire(const Polylines& centre, std::span<const Vec3> normals, const ConstantWireOptions& options);

// The largest radius for which the constant-diameter tube around `centre` (closed
// polylines) does not run into itself: half the distance between parts of the curves
// that are not neighbours along them (segments whose distance d is less than 2/pi of
// the arc between them are parts that meet again, not a bend), and no larger than the
// radius of curvature (of the circle through each point and its two neighbours), where
// the inside of a bend would fold. This is the thickness of a smooth curve (Gonzalez and
// Maddocks) taken on the points; `meander wire` checks the result. Returns a bound
// no larger than two control-polygon segments' length, since a wider tube would swallow
// the surface's detail anyway. Expected O(points) with a uniform grid.
double max_wire_radius(const Polylines& centre, int samples_per_segment);

// `--radius auto`: the largest radius for constant_wire(quads, cycle, options) without
// self-intersection. Starts from max_wire_radius (a bound that holds, but up to about a
// third below the truth) and grows it in steps of 10% while the tube, checked where the
// bound is tight (printability.h), stays clear: so 1.1 times the result collides, or
// the result is a third above the bound. `options.radius` is ignored. Returns 0 if the
// curve touches itself. constant_wire without a radius finds the same radius; this is
// for a caller who wants the radius alone.
double auto_wire_radius(const QuadMesh& quads, const TriangleCycle& cycle, const ConstantWireOptions& options);

// Variable diameter (Section 4, second method). s and t in [0, 1] size the trapezoid
// drawn inside each triangle of the cycle with the paper's bilinear formula (the
// triangle read as a quad whose apex is doubled): s across the direction of travel (the
// ribbon's width), t along it. s = t = 0 shrinks each trapezoid to the triangle's
// control point; s = t = 1 gives the triangle itself.
struct VariableWireOptions {
  WireShape shape = WireShape::wire;
  double s = 0.6, t = 0.6;
  // Wire only: the slab's thickness perpendicular to the surface, centred on it, in mesh
  // units; 0 = automatic: half the ribbon's local width, so that it too follows the
  // triangles, less where the slabs would run into each other (variable_wire).
  double thickness = 0;
  int levels = 2; // Catmull-Clark levels (OpenSubdiv), >= 0; 0 gives the control mesh
  // Search the result for self-intersections and clear them (variable_wire); false: the
  // local estimates alone, for a quick look (the studio's preview), which may cross itself.
  bool clear = true;
  // Rungs per triangle of the cycle: 2, the trapezoid's two ends, joined to the next
  // triangle's by a connector; or 1, its middle (where t = 0 puts both ends), joined
  // straight to the next triangle's: half the faces, t not used, for a quick look at
  // many triangles (the studio's preview).
  int rungs = 2;
};

struct VariableWire {
  PolygonMesh mesh;
  // The mesh was searched for self-intersections after its last change and none was
  // found (a ribbon, or a wire of automatic thickness; see variable_wire): a report can
  // take this instead of searching again (PrintabilityOptions::known_clear).
  bool clear = false;
};

// Trapezoids joined by quad connectors into a closed quad strip (ribbon); for wires each
// trapezoid is extruded along the surface normal into a prism and the prisms joined by
// hexahedral connectors into a closed toroidal quad mesh; then smoothed with
// Catmull-Clark (subdivide.h) and each quad split in two triangles. Control mesh: per
// triangle of the cycle 2 quads (ribbon) or 8 quads (wire); each level multiplies the
// quads by 4. A wire of automatic thickness is then searched for self-intersections
// (printability.h), and where it has some its slabs are thinned (then also narrowed)
// around them and smoothed again, a few rounds while that helps; a ribbon likewise, but
// narrowed from the first round (it has no thickness), unless s or t is 1: then its
// trapezoids meet along the triangles' sides by design. Throws UsageError for
// s or t outside [0, 1], thickness < 0 or levels < 0. `progress`, if given, may cancel
// the search and the clearing rounds (Cancelled).
VariableWire variable_wire(const QuadMesh& quads, const TriangleCycle& cycle, const VariableWireOptions& options,
                           Progress* progress = nullptr);

// The triangles constant_wire and variable_wire make from a cycle of `cycle_triangles`
// triangles (TriangleCycle::num_triangles), known before they are made: what a caller
// weighs against its memory (docs/wires.md, "How large a wire gets", says how much a
// triangle takes while it is made and checked). constant_wire and variable_wire refuse
// (UsageError) more than 2^31 - 1, which a mesh cannot index, before making anything.
int64_t constant_wire_triangles(int64_t cycle_triangles, const ConstantWireOptions& options);
int64_t variable_wire_triangles(int64_t cycle_triangles, const VariableWireOptions& options);

// The cycle's triangles (numbered as cycle_triangles() lists them) that cross others of
// them: where the surface a wire follows crosses itself, so that no wire following it can
// be clear. Empty on an embedded surface. What `meander wire` and the studio tell a
// maker whose wire self-intersects.
std::vector<int32_t> crossing_cycle_triangles(const QuadMesh& quads, const TriangleCycle& cycle);

} // namespace meander
