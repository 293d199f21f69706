#include "meander/subdivide.h"

#include "meander/error.h"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <cmath>
#include <memory>
#include <span>
#include <string>

namespace meander {

namespace {

// The vertex type OpenSubdiv's PrimvarRefiner interpolates, which calls these two
// members; double so that deep levels do not accumulate float rounding.
struct Point : Vec3d {
  void Clear(void* = nullptr) { x = y = z = 0; }
  void AddWithWeight(const Point& p, float w) {
    x += w * p.x;
    y += w * p.y;
    z += w * p.z;
  }
};

// A texture coordinate as a face-varying value.
struct Uv {
  double u = 0, v = 0;
  void Clear(void* = nullptr) { u = v = 0; }
  void AddWithWeight(const Uv& p, float w) {
    u += w * p.u;
    v += w * p.v;
  }
};

// The topology of `mesh` (and of its per-corner texture coordinates, if given) refined
// uniformly `options.levels` times.
std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> refine_topology(const PolygonMesh& mesh, std::span<const TexCoord> texcoords,
                                                                  const SubdivideOptions& options) {
  using namespace OpenSubdiv;
  if (options.levels < 0) throw UsageError("subdivision levels must be >= 0 (got " + std::to_string(options.levels) + ")");
  if (double(mesh.num_corners()) * std::pow(4.0, options.levels) > 2147483647.0)
    throw UsageError(std::to_string(options.levels) + " subdivision levels would make more than 2^31 corners");

  std::vector<int> sizes(size_t(mesh.num_faces()));
  for (int32_t f = 0; f < mesh.num_faces(); ++f) sizes[size_t(f)] = mesh.face_size(f);
  Far::TopologyDescriptor desc;
  desc.numVertices = mesh.num_vertices();
  desc.numFaces = mesh.num_faces();
  desc.numVertsPerFace = sizes.data();
  desc.vertIndicesPerFace = mesh.face_vertices.data();
  // Every corner its own value: the texture may jump across any edge (an atlas).
  std::vector<int> corner_values;
  Far::TopologyDescriptor::FVarChannel channel;
  if (!texcoords.empty()) {
    corner_values.resize(texcoords.size());
    for (size_t i = 0; i < corner_values.size(); ++i) corner_values[i] = int(i);
    channel.numValues = int(texcoords.size());
    channel.valueIndices = corner_values.data();
    desc.numFVarChannels = 1;
    desc.fvarChannels = &channel;
  }

  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  sdc.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_ALL);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> refiner(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, sdc)));
  if (!refiner) throw TopologyError("OpenSubdiv refused the mesh topology (is it manifold?)");
  Far::TopologyRefiner::UniformOptions uniform(options.levels);
  uniform.fullTopologyInLastLevel = true; // Limit() needs it
  refiner->RefineUniform(uniform);
  return refiner;
}

// The finest level's positions for these control positions, on the limit surface if
// `limit_surface`.
void interpolate_positions(const OpenSubdiv::Far::TopologyRefiner& refiner, bool limit_surface,
                           std::span<const Vec3> control, std::vector<Vec3>& out) {
  using namespace OpenSubdiv;
  const int levels = refiner.GetMaxLevel();
  std::vector<Point> points(size_t(refiner.GetNumVerticesTotal()));
  for (size_t v = 0; v < control.size(); ++v) points[v] = {to_double(control[v])};
  Far::PrimvarRefiner primvar(refiner);
  Point* src = points.data();
  for (int level = 1; level <= levels; ++level) {
    Point* dst = src + refiner.GetLevel(level - 1).GetNumVertices();
    primvar.Interpolate(level, src, dst);
    src = dst;
  }
  const Far::TopologyLevel& finest = refiner.GetLevel(levels);
  std::vector<Point> limit;
  if (limit_surface && levels > 0) {
    limit.resize(size_t(finest.GetNumVertices()));
    Point* dst = limit.data();
    primvar.Limit(src, dst);
    src = limit.data();
  }
  out.resize(size_t(finest.GetNumVertices()));
  for (size_t v = 0; v < out.size(); ++v) out[v] = to_float(src[v]);
}

// The finest level's faces.
void finest_faces(const OpenSubdiv::Far::TopologyRefiner& refiner, PolygonMesh& out) {
  const OpenSubdiv::Far::TopologyLevel& finest = refiner.GetLevel(refiner.GetMaxLevel());
  out.face_start.reserve(size_t(finest.GetNumFaces()) + 1);
  out.face_vertices.reserve(size_t(finest.GetNumFaceVertices()));
  for (int f = 0; f < finest.GetNumFaces(); ++f) {
    const OpenSubdiv::Far::ConstIndexArray corners = finest.GetFaceVertices(f);
    for (int i = 0; i < corners.size(); ++i) out.face_vertices.push_back(corners[i]);
    out.face_start.push_back(int32_t(out.face_vertices.size()));
  }
}

// Refines the mesh and, if given, its per-corner texture coordinates and per-face
// materials (empty: none).
TexturedMesh refine(const PolygonMesh& mesh, std::span<const TexCoord> texcoords, std::span<const int32_t> face_material,
                    const SubdivideOptions& options) {
  using namespace OpenSubdiv;
  const std::unique_ptr<Far::TopologyRefiner> refiner = refine_topology(mesh, texcoords, options);
  TexturedMesh result;
  PolygonMesh& out = result.mesh;
  interpolate_positions(*refiner, options.limit, mesh.positions, out.positions);
  finest_faces(*refiner, out);
  const Far::TopologyLevel& finest = refiner->GetLevel(options.levels);
  Far::PrimvarRefiner primvar(*refiner);
  if (!texcoords.empty()) {
    // Bilinear face-varying values have their limit where they are refined to.
    std::vector<Uv> uv(size_t(refiner->GetNumFVarValuesTotal(0)));
    for (size_t i = 0; i < texcoords.size(); ++i) uv[i] = {texcoords[i].u, texcoords[i].v};
    Uv* uv_src = uv.data();
    for (int level = 1; level <= options.levels; ++level) {
      Uv* dst = uv_src + refiner->GetLevel(level - 1).GetNumFVarValues(0);
      primvar.InterpolateFaceVarying(level, uv_src, dst, 0);
      uv_src = dst;
    }
    result.appearance.texcoords.reserve(out.face_vertices.size());
    for (int f = 0; f < finest.GetNumFaces(); ++f)
      for (int value : finest.GetFaceFVarValues(f, 0))
        result.appearance.texcoords.push_back({float(uv_src[value].u), float(uv_src[value].v)});
  }
  if (!face_material.empty()) {
    result.appearance.face_material.resize(size_t(finest.GetNumFaces()));
    for (int f = 0; f < finest.GetNumFaces(); ++f) {
      int parent = f;
      for (int level = options.levels; level > 0; --level) parent = refiner->GetLevel(level).GetFaceParentFace(parent);
      result.appearance.face_material[size_t(f)] = face_material[size_t(parent)];
    }
  }
  return result;
}

} // namespace

PolygonMesh subdivide(const PolygonMesh& mesh, const SubdivideOptions& options) {
  return std::move(refine(mesh, {}, {}, options).mesh);
}

TexturedMesh subdivide(const TexturedMesh& mesh, const SubdivideOptions& options) {
  check_appearance(mesh.mesh, mesh.appearance, "subdivide");
  TexturedMesh result = refine(mesh.mesh, mesh.appearance.texcoords, mesh.appearance.face_material, options);
  result.appearance.materials = mesh.appearance.materials;
  return result;
}

struct CatmullClark::Refiner {
  std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> topology;
  bool limit = true;
};

CatmullClark::CatmullClark(const PolygonMesh& control, const SubdivideOptions& options)
    : refiner_(new Refiner{refine_topology(control, {}, options), options.limit}) {
  finest_faces(*refiner_->topology, faces_);
}

CatmullClark::~CatmullClark() = default;

PolygonMesh CatmullClark::refine(std::span<const Vec3> control_positions) const {
  PolygonMesh out = faces_;
  interpolate_positions(*refiner_->topology, refiner_->limit, control_positions, out.positions);
  return out;
}

} // namespace meander
