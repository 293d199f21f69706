// Evening out the passes of closed curves that cover a surface (issue 34, "Evenness"):
// a curve made on an even remesh has passes whose gaps still vary by a fifth (CV 0.20);
// here each point moves across the surface toward the middle of the passes on either
// side of it, half a spacing from the surface's boundary, so the gaps even out and holes
// close; parts of the surface farther than half a spacing from the curve pull the nearest
// point toward them, so branches grow into the pockets beyond their tips; no point ever
// moves more than a quarter of the way to another pass, so the curves never cross
// themselves or each other, and where a curve came crossing itself (folded by the closest
// point where the even mesh strays from the surface) the stretch between the crossing
// segments is reversed; a hairpin pinched to a needle (arms nearer than a quarter
// spacing) is cut off where its arms meet; consecutive points that the closest point put
// on two sides of a part thinner than the spacing are joined round its edge (within 3
// times their distance) instead of straight through it. Otherwise the order of the
// points stays the cycle's.
#pragma once

#include "meander/closest_points.h"
#include "meander/mesh.h"
#include "meander/progress.h"

#include <vector>

namespace meander {

struct RelaxOptions {
  double spacing = 0; // the gap wanted between neighbouring passes, > 0, in mesh units
  int iterations = 20;
};

// Closed curves whose points lie on `surface` (closest: ClosestPoints(surface)), with
// passes about options.spacing apart, relaxed and returned resampled at about a quarter of
// the spacing. Parts of the surface thinner than the spacing are told apart by their
// normals: a pass does not push the one on the other side of a thin sheet. Deterministic
// whatever the number of threads (oneTBB). O(iterations * (P + S) log F) for P points
// of the result, S = 8 area / spacing^2 surface samples and F faces, on curves whose passes
// are about a spacing apart. Throws ParameterError for a spacing that is not a positive number or
// iterations < 0, InputError for an open curve, Cancelled (checked every round).
struct RelaxedCurves {
  Polylines curves;
  std::vector<Vec3> normals; // the surface's unit normal at each point, as its face has it
};
RelaxedCurves relax_curves(const Polylines& curves, const PolygonMesh& surface, const ClosestPoints& closest,
                           const RelaxOptions& options, Progress* progress = nullptr);

} // namespace meander
