// Bridges between neighbouring passes of a wire (issue 38; the paper's Section 6: a
// wire "may not have enough stability to hold their shape"). A wire is a closed tube that
// touches itself nowhere, so that printed it is a loose loop; short struts between
// neighbouring passes, where they come closest, make it one rigid lattice.
#pragma once

#include "meander/mesh.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace meander {

struct BridgeOptions {
  double max_stretch = 0; // > 0: along each curve, the longest stretch wanted without a bridge's end
  double radius = 0;      // > 0: the farthest the wire's surface lies from its centre line
  double reach = 0;       // > 2 radius: the farthest apart two passes' centres are bridged
  // Per centre point, the radius of the largest ball about it inside the wire (a
  // variable wire's slab is thinner than it is wide), 0 where the point lies outside:
  // no bridge ends there; and the farthest the wire reaches from it across the line
  // (the slab's half width). Empty: `radius` everywhere (the constant wire's tube).
  std::span<const double> inscribed, extent;
};

struct BridgePlan {
  std::vector<std::array<int32_t, 2>> ends; // per bridge: its two ends, indices into centre.points
  // Per bridge: its strut's radius, `strut` times the inscribed radius at its thinner end.
  std::vector<double> radii;
  // Along the curves, the longest stretch between consecutive bridge ends (a curve
  // without any: its length).
  double longest_stretch = 0;
  bool one_piece = false; // every curve joined to the others by bridges (one curve: true)
  // One piece, and no stretch longer than asked: every pass is tied to the rest.
  bool every_pass_tied = false;
};

// Where to bridge a wire of closed centre lines `centre` (its passes about a spacing
// apart, points a fraction of it apart, as the wire is swept). A bridge joins a point to
// the nearest point of another pass (another curve, or a point of the same one farther
// along it than 1.4 times their distance, as evenness.h counts a gap) within
// options.reach. Bridges go where passes come closest first, their ends at least
// max_stretch / 2 apart along each curve, then into each stretch still longer than
// max_stretch, at least an eighth of it from its ends; a bridge whose axis comes nearer
// another part of the wire than its extent there, the strut and a gap of 1.2 times the
// ball at the strut's thinner end, or nearer another bridge than 1.5 times the sum of
// their balls (3 radii for a tube), is left out.
// Deterministic. Throws ParameterError for options out of range, InputError for an open
// curve. About O(n log n) for n points, plus O(b) a candidate for b bridges.
BridgePlan plan_bridges(const Polylines& centre, const BridgeOptions& options);

// The bridges as closed, outward solids (prisms of `sides` sides of the plan's radii, a
// ring of vertices at both ends and in the middle, capped by fans), each from one end's
// centre point to the other's, so that both caps lie inside the wire (within the
// inscribed ball at each end): to unite with the wire (unite_solids).
inline constexpr double strut = 0.8;
PolygonMesh bridge_solids(const Polylines& centre, const BridgePlan& plan, int sides);

} // namespace meander
