// Catmull-Clark subdivision surfaces through OpenSubdiv.
#pragma once

#include "meander/mesh.h"
#include "meander/textured_mesh.h"

#include <memory>
#include <span>
#include <vector>

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

// Catmull-Clark refinement of one control topology, kept for new positions: refining the
// topology is most of OpenSubdiv's work, and a caller that moves the control points
// again and again (variable_wire's clearing rounds) pays for it once. Faces come out as
// subdivide() makes them: the finest level's, each control face's children consecutive.
class CatmullClark {
public:
  // Throws as subdivide() does. `control`'s positions are not used.
  CatmullClark(const PolygonMesh& control, const SubdivideOptions& options);
  ~CatmullClark();
  CatmullClark(const CatmullClark&) = delete;
  CatmullClark& operator=(const CatmullClark&) = delete;

  // The refined mesh for these positions of the control vertices: subdivide() of the
  // control mesh moved there. O(output).
  PolygonMesh refine(std::span<const Vec3> control_positions) const;

private:
  struct Refiner;
  std::unique_ptr<Refiner> refiner_;
  PolygonMesh faces_; // the finest level's faces, no positions
};

} // namespace meander
