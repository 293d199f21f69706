// Catmull-Clark subdivision surfaces through OpenSubdiv.
#pragma once

#include "meander/mesh.h"
#include "meander/textured_mesh.h"

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

// The same for a textured mesh (check_appearance must accept it, else UsageError): the
// texture coordinates are carried along as OpenSubdiv face-varying data interpolated
// bilinearly inside each face (Sdc FVAR_LINEAR_ALL), so whatever the texture draws on a
// face stays on the part of the smooth surface refined from that face, and two faces'
// drawings meet where the faces meet (duotone tiles show no seams). Each refined face
// keeps its parent's material. O(output).
TexturedMesh subdivide(const TexturedMesh& mesh, const SubdivideOptions& options = {});

} // namespace meander
