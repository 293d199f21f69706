// Catmull-Clark subdivision surfaces through OpenSubdiv.
#pragma once

#include "meander/mesh.h"

namespace meander {

struct SubdivideOptions {
  int levels = 1;     // uniform refinement steps, >= 0 (each multiplies quads by 4)
  bool limit = true;  // move the finest vertices onto the limit surface
};

// Refines a manifold polygon mesh `levels` times with Catmull-Clark (boundaries keep
// their edges and corners) and returns the finest level as quads. O(output).
// Throws UsageError for levels < 0 or an output above 2^31 corners, TopologyError if
// OpenSubdiv refuses the topology.
PolygonMesh subdivide(const PolygonMesh& mesh, const SubdivideOptions& options = {});

} // namespace meander
