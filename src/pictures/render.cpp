#include "meander/render.h"

#include "meander/error.h"
#include "meander/io.h"
#include "embree/embree_scene.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>

namespace meander {
namespace {

constexpr int32_t max_side = 16384;
constexpr double pi = 3.14159265358979323846;

// Positions, directions and linear colours in double (Vec3d).
Vec3d normalized(Vec3d a) {
  const double n = norm(a);
  return n > 0 ? a * (1 / n) : Vec3d{0, 0, 0};
}
// A colour filtered by another, channel by channel.
Vec3d filtered(Vec3d a, Vec3d b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }

// Shading is done in linear light; colours arrive and leave as sRGB (gamma 2.2 is close
// enough for pictures, and cheaper than the exact curve).
Vec3d linear(Rgb c) { return {std::pow(c.r, 2.2), std::pow(c.g, 2.2), std::pow(c.b, 2.2)}; }
uint8_t to_byte(double linear_value) {
  const double v = std::pow(std::clamp(linear_value, 0.0, 1.0), 1 / 2.2);
  return uint8_t(std::lround(v * 255));
}

// A hash of the pixel, sample and use, so that every random number is fixed by where it
// is used and not by the order threads run in: the same bytes on every run.
float random01(uint32_t x, uint32_t y, uint32_t sample, uint32_t use) {
  uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ sample * 0xcb1ab31fu ^ use * 0x165667b1u;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return float(h >> 8) * (1.0f / 16777216.0f);
}

// Geometry masks: primary rays see everything; occlusion rays skip occluder-only
// meshes, which must leave no trace in the picture, not even a darker contact.
constexpr unsigned drawn_mask = 1, curve_mask = 2, occluder_mask = 4;

// What shading needs of each Embree geometry, indexed by its id.
struct GeometryInfo {
  Vec3d albedo;
  bool curve = false;
  MeshStyle style = MeshStyle::shaded;
  std::vector<uint32_t> triangles; // 3 vertex ids per triangle
  std::vector<Vec3> normals;       // per vertex, unnormalised area-weighted
  // A mesh with materials: the face of each triangle and its 3 corners (for the texture
  // coordinates); the appearance lives in the scene, which outlives the rendering.
  const Appearance* appearance = nullptr;
  std::vector<int32_t> faces, corners;
};

// The colour of a mesh with materials at barycentric (u, v) of triangle t, in linear light.
Vec3d surface_albedo(const GeometryInfo& g, unsigned t, double u, double v) {
  const Appearance& a = *g.appearance;
  const Material& m = a.materials[a.face_material.empty() ? 0 : size_t(a.face_material[size_t(g.faces[t])])];
  Vec3d colour{m.base_color[0], m.base_color[1], m.base_color[2]};
  if (m.texture.empty()) return colour;
  const int32_t* c = &g.corners[3 * size_t(t)];
  const TexCoord t0 = a.texcoords[size_t(c[0])], t1 = a.texcoords[size_t(c[1])], t2 = a.texcoords[size_t(c[2])];
  const TexCoord uv{float(t0.u * (1 - u - v) + t1.u * u + t2.u * v), float(t0.v * (1 - u - v) + t1.v * u + t2.v * v)};
  const LinearRgb texel = sample_texture(m.texture, uv);
  return filtered(colour, Vec3d{texel[0], texel[1], texel[2]});
}

struct Camera {
  Vec3d eye, forward, right, up;
  double tan_half_height = 0, aspect = 1;
};

// Throws UsageError for a camera given that no picture can be taken with.
Camera fit_camera(const Scene& scene, const RenderOptions& o) {
  if (const std::optional<CameraPose>& given = o.camera) {
    const Vec3d forward = given->target - given->eye;
    const bool finite = std::isfinite(norm(given->eye) + norm(given->target) + norm(given->up) + given->fov_degrees);
    if (!finite || norm(forward) == 0 || norm(cross(forward, given->up)) == 0 ||
        !(given->fov_degrees > 0 && given->fov_degrees < 180))
      throw UsageError("camera: expected finite positions, the eye apart from the target, an up direction not along the "
                       "view, and a field of view between 0 and 180 degrees");
  }
  if (o.camera) {
    Camera c;
    c.eye = o.camera->eye;
    c.forward = normalized(o.camera->target - o.camera->eye);
    c.right = normalized(cross(c.forward, o.camera->up));
    c.up = cross(c.right, c.forward);
    c.aspect = double(o.width) / o.height;
    c.tan_half_height = std::tan(o.camera->fov_degrees * pi / 180 / 2);
    return c;
  }
  const double az = o.view.azimuth * pi / 180, el = std::clamp(o.view.elevation, -89.9, 89.9) * pi / 180;
  Camera c;
  const Vec3d from{std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)};
  c.forward = from * -1;
  // Looking straight down, the world's up is along the view: then "up" on the picture
  // is the direction the azimuth faces away from.
  const Vec3d world_up = std::abs(o.view.elevation) > 89.9 ? Vec3d{-std::sin(az), 0, -std::cos(az)} : Vec3d{0, 1, 0};
  c.right = normalized(cross(c.forward, world_up));
  c.up = cross(c.right, c.forward);
  c.aspect = double(o.width) / o.height;
  c.tan_half_height = std::tan(25 * pi / 180 / 2);

  Box3 box;
  auto each_point = [&](auto&& f) {
    for (const SceneMesh& m : scene.meshes)
      for (Vec3 p : m.mesh.positions) f(to_double(p));
    for (const SceneCurves& k : scene.curves)
      for (Vec3 p : k.curves.points) f(to_double(p));
  };
  each_point([&](Vec3d p) { box.extend({float(p.x), float(p.y), float(p.z)}); });
  if (box.empty()) box.extend({0, 0, 0});
  const Vec3d centre = (to_double(box.min) + to_double(box.max)) * 0.5;
  if (o.framing == Framing::sphere) {
    // The sphere's outline is a circle of half-angle asin(R / distance) around the view
    // axis: it fits the narrower side of the picture with a 6% margin.
    const double radius = std::max(0.5 * box.diagonal(), 1e-6);
    const double half_angle = std::atan(0.88 * c.tan_half_height * std::min(1.0, c.aspect));
    c.eye = centre - c.forward * (radius / std::sin(half_angle));
    return c;
  }
  if (o.framing == Framing::silhouette) {
    // A point p is inside the picture's right edge when n . (p - eye) >= 0 with
    // n = forward * tan_x - right; the edge plane touches the points when
    // n . eye = min over p of n . p. The left and right planes together fix the eye's
    // sideways and forward coordinates, the top and bottom planes its upward and forward
    // ones; the eye takes the forward coordinate further back, which leaves the other
    // pair of planes equally clear of the points on both sides.
    const double tan_y = c.tan_half_height * 0.94, tan_x = tan_y * c.aspect;
    double right_min = INFINITY, left_min = INFINITY, top_min = INFINITY, bottom_min = INFINITY;
    each_point([&](Vec3d p) {
      const Vec3d d = p - centre;
      const double x = dot(d, c.right), y = dot(d, c.up), z = dot(d, c.forward);
      right_min = std::min(right_min, z * tan_x - x), left_min = std::min(left_min, z * tan_x + x);
      top_min = std::min(top_min, z * tan_y - y), bottom_min = std::min(bottom_min, z * tan_y + y);
    });
    const double along = std::min((right_min + left_min) / (2 * tan_x), (top_min + bottom_min) / (2 * tan_y));
    c.eye = centre + c.right * ((left_min - right_min) / 2) + c.up * ((bottom_min - top_min) / 2) + c.forward * along;
    // A single point (or points along the view axis) would put the eye on them.
    double farthest = 0;
    each_point([&](Vec3d p) { farthest = std::max(farthest, dot(p - c.eye, c.forward)); });
    if (farthest <= 1e-9 * std::max(box.diagonal(), 1.0)) c.eye = c.eye - c.forward;
    // The pair of planes that do not touch are equally clear of the points, but their
    // extreme points lie at different depths, so the picture is not quite centred between
    // them: move the eye sideways and upwards until the extremes' projections are
    // symmetric (exact once the extreme points stop changing; a few rounds do).
    for (int round = 0; round < 4; ++round) {
      struct Extreme {
        double lo = INFINITY, hi = -INFINITY, lo_depth = 1, hi_depth = 1, lo_at = 0, hi_at = 0;
      } across, upward;
      each_point([&](Vec3d p) {
        const Vec3d d = p - c.eye;
        const double depth = dot(d, c.forward);
        if (depth <= 0) return;
        for (auto [extreme, axis] : {std::pair{&across, c.right}, std::pair{&upward, c.up}}) {
          const double at = dot(d, axis), t = at / depth;
          if (t < extreme->lo) extreme->lo = t, extreme->lo_depth = depth, extreme->lo_at = at;
          if (t > extreme->hi) extreme->hi = t, extreme->hi_depth = depth, extreme->hi_at = at;
        }
      });
      // The shift s that makes (lo_at - s) / lo_depth = -(hi_at - s) / hi_depth.
      auto shift = [](const Extreme& e) {
        return (e.lo_at / e.lo_depth + e.hi_at / e.hi_depth) / (1 / e.lo_depth + 1 / e.hi_depth);
      };
      c.eye = c.eye + c.right * shift(across) + c.up * shift(upward);
    }
    return c;
  }

  // Centre on the extent of the points across the view, then back off until every
  // point is inside the frame with a 6% margin on each side.
  double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
  each_point([&](Vec3d p) {
    const Vec3d d = p - centre;
    lo_x = std::min(lo_x, dot(d, c.right)), hi_x = std::max(hi_x, dot(d, c.right));
    lo_y = std::min(lo_y, dot(d, c.up)), hi_y = std::max(hi_y, dot(d, c.up));
  });
  const Vec3d target = centre + c.right * ((lo_x + hi_x) / 2) + c.up * ((lo_y + hi_y) / 2);
  const double tan_y = c.tan_half_height * 0.88, tan_x = tan_y * c.aspect;
  double distance = 0;
  each_point([&](Vec3d p) {
    const Vec3d d = p - target;
    const double depth = dot(d, c.forward);
    distance = std::max({distance, std::abs(dot(d, c.right)) / tan_x - depth, std::abs(dot(d, c.up)) / tan_y - depth});
  });
  if (distance <= 0) distance = 1;
  c.eye = target - c.forward * distance;
  return c;
}

} // namespace

CameraPose picture_camera(const Scene& scene, const RenderOptions& options) {
  const Camera c = fit_camera(scene, options);
  return {.eye = c.eye, .target = c.eye + c.forward, .up = c.up, .fov_degrees = 2 * std::atan(c.tan_half_height) * 180 / pi};
}

namespace {

double mesh_area(const PolygonMesh& m) {
  double area = 0;
  for (int32_t f = 0; f < m.num_faces(); ++f) {
    const auto face = m.face(f);
    for (size_t i = 1; i + 1 < face.size(); ++i)
      area += 0.5 * norm(meander::cross(m.positions[face[i]] - m.positions[face[0]],
                                        m.positions[face[i + 1]] - m.positions[face[0]]));
  }
  return area;
}

void add_mesh(EmbreeScene& rtc, const SceneMesh& m, std::vector<GeometryInfo>& info) {
  GeometryInfo g{.albedo = linear(m.color), .style = m.style};
  const PolygonMesh& mesh = m.mesh;
  check_appearance(mesh, m.appearance, "render: scene mesh");
  if (!m.appearance.materials.empty() && m.style != MeshStyle::hidden) g.appearance = &m.appearance;
  g.normals.assign(mesh.positions.size(), Vec3{});
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto face = mesh.face(f);
    for (size_t i = 1; i + 1 < face.size(); ++i) {
      const uint32_t a = face[0], b = face[i], c = face[i + 1];
      g.triangles.insert(g.triangles.end(), {a, b, c});
      if (g.appearance) {
        const int32_t first = mesh.face_start[f];
        g.faces.push_back(f);
        g.corners.insert(g.corners.end(), {first, first + int32_t(i), first + int32_t(i) + 1});
      }
      if (m.style == MeshStyle::hidden) continue;
      // The cross product's length is twice the area: area-weighted for free.
      const Vec3 n = meander::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
      for (uint32_t v : {a, b, c}) g.normals[v] = g.normals[v] + n;
    }
  }
  if (g.triangles.empty()) return;
  RTCGeometry geometry = rtcNewGeometry(rtc.device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  set_vertices(geometry, mesh.positions);
  auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(uint32_t), g.triangles.size() / 3));
  std::copy(g.triangles.begin(), g.triangles.end(), indices);
  rtcSetGeometryMask(geometry, m.style == MeshStyle::shaded ? drawn_mask : occluder_mask);
  const unsigned id = rtc.attach(geometry);
  info.resize(std::max<size_t>(info.size(), id + 1));
  info[id] = std::move(g);
}

// `radius` gives the curve's radius at each point: one value for tubes, growing with the
// depth for ribbons of constant screen width (linear along a segment, as depth is).
template <class Radius>
void add_curves(EmbreeScene& rtc, const SceneCurves& k, CurveStyle style, Radius radius,
                std::vector<GeometryInfo>& info) {
  // A closed loop of n points is n segments: the first point is repeated at the end.
  // An open polyline of n points is n - 1 segments.
  size_t points = 0, segments = 0;
  for (int32_t i = 0; i < k.curves.size(); ++i)
    if (const size_t n = k.curves.polyline(i).size(); n >= 2)
      points += k.curves.closed(i) ? n + 1 : n, segments += k.curves.closed(i) ? n : n - 1;
  if (segments == 0) return;
  RTCGeometry geometry = rtcNewGeometry(
      rtc.device(), style == CurveStyle::tube ? RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE : RTC_GEOMETRY_TYPE_FLAT_LINEAR_CURVE);
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), points));
  auto* indices = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(uint32_t), segments));
  size_t p = 0, s = 0;
  for (int32_t i = 0; i < k.curves.size(); ++i) {
    const auto loop = k.curves.polyline(i);
    if (loop.size() < 2) continue;
    const size_t ends = k.curves.closed(i) ? loop.size() : loop.size() - 1;
    for (size_t j = 0; j <= ends; ++j) {
      const Vec3 q = loop[j % loop.size()];
      if (j < ends) indices[s++] = uint32_t(p);
      vertices[4 * p] = q.x, vertices[4 * p + 1] = q.y, vertices[4 * p + 2] = q.z, vertices[4 * p + 3] = radius(q);
      ++p;
    }
  }
  rtcSetGeometryMask(geometry, curve_mask);
  const unsigned id = rtc.attach(geometry);
  info.resize(std::max<size_t>(info.size(), id + 1));
  info[id] = GeometryInfo{.albedo = linear(k.color), .curve = true};
}

struct Hit {
  bool found = false;
  unsigned geometry = 0;
  Vec3d position, normal;
  Vec3d albedo; // linear colour of the surface there
};

// How far behind a surface a curve still shows: curves are drawn over the surfaces they
// lie on, so a surface hides a curve only if it is more than `absolute` + `relative` *
// (the surface's distance) in front of it.
struct CurveSlack {
  double absolute = 0, relative = 0;
};

class Tracer {
public:
  // ribbons: the curves are ribbons, which face each ray and stand for marks on the
  // picture rather than objects in the scene.
  Tracer(RTCScene scene, const std::vector<GeometryInfo>& info, bool has_curves, CurveSlack slack, bool ribbons)
      : scene_(scene), info_(info), has_curves_(has_curves), slack_(slack), ribbons_(ribbons) {}

  Hit trace(Vec3d origin, Vec3d direction) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    set_ray(rh.ray, origin, direction, 0, std::numeric_limits<float>::infinity(), drawn_mask | occluder_mask);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &rh);
    if (has_curves_) {
      RTCRayHit curve{};
      const float far = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID
                            ? std::numeric_limits<float>::infinity()
                            : float(rh.ray.tfar * (1 + slack_.relative) + slack_.absolute);
      set_ray(curve.ray, origin, direction, 0, far, curve_mask);
      curve.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      curve.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene_, &context, &curve);
      if (curve.hit.geomID != RTC_INVALID_GEOMETRY_ID) rh = curve;
    }
    Hit h;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    h.found = true;
    h.geometry = rh.hit.geomID;
    h.position = origin + direction * rh.ray.tfar;
    const GeometryInfo& g = info_[h.geometry];
    Vec3d n = normalized(Vec3d{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
    if (!g.curve && g.style != MeshStyle::hidden) {
      const uint32_t* t = &g.triangles[3 * size_t(rh.hit.primID)];
      const double u = rh.hit.u, v = rh.hit.v;
      const Vec3d smooth = normalized(to_double(g.normals[t[0]]) * (1 - u - v) + to_double(g.normals[t[1]]) * u + to_double(g.normals[t[2]]) * v);
      // Meshes are drawn from both sides: the normal faces the viewer. A smooth normal
      // that disagrees with the face's own side (at silhouettes) would shade black.
      if (dot(n, direction) > 0) n = n * -1;
      if (dot(smooth, smooth) > 0) n = dot(smooth, n) < 0 ? smooth * -1 : smooth;
    } else if (dot(n, direction) > 0) {
      n = n * -1;
    }
    h.normal = n;
    h.albedo = g.appearance ? surface_albedo(g, rh.hit.primID, rh.hit.u, rh.hit.v) : g.albedo;
    return h;
  }

  bool occluded(Vec3d origin, Vec3d direction, float far) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    // Ribbons face each ray's origin, so they would cast odd shadows: they are drawn on
    // the picture rather than standing in the scene.
    set_ray(ray, origin, direction, 0, far, ribbons_ ? drawn_mask : drawn_mask | curve_mask);
    rtcOccluded1(scene_, &context, &ray);
    return ray.tfar < 0;
  }

private:
  static void set_ray(RTCRay& r, Vec3d o, Vec3d d, float near, float far, unsigned mask) {
    r.org_x = float(o.x), r.org_y = float(o.y), r.org_z = float(o.z);
    r.dir_x = float(d.x), r.dir_y = float(d.y), r.dir_z = float(d.z);
    r.tnear = near, r.tfar = far, r.mask = mask, r.flags = 0, r.time = 0;
  }
  RTCScene scene_;
  const std::vector<GeometryInfo>& info_;
  bool has_curves_;
  CurveSlack slack_;
  bool ribbons_;
};

} // namespace

View parse_view(std::string_view text) {
  if (text == "front") return {0, 0};
  if (text == "back") return {180, 0};
  if (text == "right") return {90, 0};
  if (text == "left") return {-90, 0};
  if (text == "top") return {0, 90};
  if (text == "iso") return {};
  View v;
  const size_t comma = text.find(',');
  const char* end = text.data() + text.size();
  if (comma != std::string_view::npos) {
    const auto [az_end, az_error] = std::from_chars(text.data(), text.data() + comma, v.azimuth);
    const auto [el_end, el_error] = std::from_chars(text.data() + comma + 1, end, v.elevation);
    if (az_error == std::errc{} && az_end == text.data() + comma && el_error == std::errc{} && el_end == end &&
        std::isfinite(v.azimuth) && std::abs(v.elevation) <= 90)
      return v;
  }
  throw UsageError("view '" + std::string(text) +
                   "': expected front, back, left, right, top, iso or AZ,EL in degrees (elevation -90..90)");
}

Background parse_background(std::string_view text) {
  if (text == "white") return {};
  if (text == "transparent") return {.transparent = true};
  auto hex = [](char c) { return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1; };
  if (text.size() == 7 && text[0] == '#' &&
      std::all_of(text.begin() + 1, text.end(), [&](char c) { return hex(c) >= 0; })) {
    auto channel = [&](int i) { return float(hex(text[i]) * 16 + hex(text[i + 1])) / 255; };
    return {.color = {channel(1), channel(3), channel(5)}};
  }
  throw UsageError("background '" + std::string(text) + "': expected white, transparent or #rrggbb");
}

void parse_size(std::string_view text, int32_t& width, int32_t& height) {
  const size_t x = text.find('x');
  const char* end = text.data() + text.size();
  if (x != std::string_view::npos) {
    int32_t w = 0, h = 0;
    const auto [w_end, w_error] = std::from_chars(text.data(), text.data() + x, w);
    const auto [h_end, h_error] = std::from_chars(text.data() + x + 1, end, h);
    if (w_error == std::errc{} && w_end == text.data() + x && h_error == std::errc{} && h_end == end && w >= 1 &&
        h >= 1 && w <= max_side && h <= max_side) {
      width = w, height = h;
      return;
    }
  }
  throw UsageError("size '" + std::string(text) + "': expected WIDTHxHEIGHT, each 1.." + std::to_string(max_side) +
                   " pixels");
}

Image render(const Scene& scene, const RenderOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > max_side || o.height > max_side)
    throw UsageError("image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                     ": width and height must be 1.." + std::to_string(max_side) + " pixels");
  if (o.samples < 1 || o.samples > 1024)
    throw UsageError("samples " + std::to_string(o.samples) + ": expected 1..1024 rays per pixel");
  const Camera camera = fit_camera(scene, o);
  Box3 box;
  for (const SceneMesh& m : scene.meshes)
    for (Vec3 p : m.mesh.positions) box.extend(p);
  for (const SceneCurves& k : scene.curves)
    for (Vec3 p : k.curves.points) box.extend(p);
  const double diagonal = std::max(box.diagonal(), 1e-6);
  const Vec3d centre = box.empty() ? Vec3d{} : (to_double(box.min) + to_double(box.max)) * 0.5;
  // The size of a pixel at the scene's centre, in scene units.
  const double pixel_size = 2 * camera.tan_half_height * dot(centre - camera.eye, camera.forward) / o.height;

  double area = 0, length = 0;
  for (const SceneMesh& m : scene.meshes) area += mesh_area(m.mesh);
  for (const SceneCurves& k : scene.curves) length += total_length(k.curves);
  // A curve that covers a surface passes at about area / length from its neighbours;
  // a curve that covers little of a large surface would get a tube as thick as a limb.
  const double radius = o.curve_width > 0 ? o.curve_width * pixel_size / 2
                  : area > 0 && length > 0 ? std::max(std::min(0.25 * area / length / 2, 0.004 * diagonal), 0.75 * pixel_size)
                                           : pixel_size;

  // Robust: without it, a ray through a shared edge can slip between two triangles and
  // shade the inside of the far side, a dark speck on a closed surface.
  EmbreeScene rtc("render", RTC_SCENE_FLAG_ROBUST, RTC_BUILD_QUALITY_MEDIUM);
  std::vector<GeometryInfo> info;
  for (const SceneMesh& m : scene.meshes) add_mesh(rtc, m, info);
  // A ribbon's radius grows with the depth so that it keeps the width it has at the
  // centre in pixels; the smallest depth keeps points behind the eye well-formed.
  const double centre_depth = std::max(dot(centre - camera.eye, camera.forward), 1e-9);
  const bool ribbons = o.curve_style == CurveStyle::ribbon;
  for (const SceneCurves& k : scene.curves) {
    if (ribbons)
      add_curves(rtc, k, o.curve_style, [&](Vec3 q) {
        return float(radius * std::max(dot(to_double(q) - camera.eye, camera.forward), 1e-6 * centre_depth) / centre_depth);
      }, info);
    else
      add_curves(rtc, k, o.curve_style, [&](Vec3) { return float(radius); }, info);
  }
  rtc.commit();
  // Two tube widths, or four ribbon widths at the surface's depth (a ribbon turned to
  // face the eye dips further into a slanted surface than a tube does): enough for a
  // curve a little under the surface it covers (a B-spline cuts the corners of its
  // control polygon, and a tube's core is inside the surface), far too little for a
  // curve on the far side of a solid.
  const CurveSlack slack = ribbons ? CurveSlack{.relative = 8 * radius / centre_depth} : CurveSlack{.absolute = 4 * radius};
  const Tracer tracer(rtc.scene(), info, !scene.curves.empty(), slack, ribbons);

  const Vec3d key = normalized(camera.forward * -0.75 + camera.up * 0.55 + camera.right * -0.35);
  const Vec3d background = linear(o.background.color);
  const double ao_distance = 0.08 * diagonal, offset = 1e-4 * diagonal;
  const int ao_rays = o.samples >= 4 ? 2 : 4;

  Image image{.width = o.width, .height = o.height, .has_alpha = o.background.transparent};
  image.rgba.resize(size_t(o.width) * o.height * 4);
  constexpr int tile = 16;
  const int tiles_x = (o.width + tile - 1) / tile, tiles_y = (o.height + tile - 1) / tile;
  tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y), [&](const tbb::blocked_range<int>& range) {
    for (int t = range.begin(); t != range.end(); ++t) {
      const int x0 = t % tiles_x * tile, y0 = t / tiles_x * tile;
      for (int y = y0; y < std::min(y0 + tile, o.height); ++y)
        for (int x = x0; x < std::min(x0 + tile, o.width); ++x) {
          Vec3d sum;
          double coverage = 0;
          for (int s = 0; s < o.samples; ++s) {
            // Stratified along a rank-1 lattice (the R2 sequence), shifted per pixel:
            // even coverage of the pixel without visible patterns.
            const double jx = std::fmod(0.5 + s * 0.7548776662 + random01(x, y, 0, 0), 1.0);
            const double jy = std::fmod(0.5 + s * 0.5698402910 + random01(x, y, 0, 1), 1.0);
            const double sx = (2 * (x + jx) / o.width - 1) * camera.tan_half_height * camera.aspect;
            const double sy = (1 - 2 * (y + jy) / o.height) * camera.tan_half_height;
            const Vec3d direction = normalized(camera.forward + camera.right * sx + camera.up * sy);
            const Hit hit = tracer.trace(camera.eye, direction);
            if (!hit.found || info[hit.geometry].style == MeshStyle::hidden) continue;
            const GeometryInfo& g = info[hit.geometry];
            const Vec3d n = hit.normal;
            if (g.curve && ribbons) {
              sum = sum + g.albedo;
              coverage += 1;
              continue;
            }
            if (g.style == MeshStyle::faint) {
              // A light grey let through by the background behind it: lit, without
              // shadows, so the shape shows without competing with the curves.
              constexpr double opacity = 0.5;
              const double light = 0.5 + 0.25 * std::max(0.0, dot(n, key)) + 0.1 * dot(n, camera.up);
              sum = sum + Vec3d{light, light, light} * opacity;
              coverage += opacity;
              continue;
            }
            // Cosine-weighted directions around n for ambient occlusion.
            const Vec3d a = std::abs(n.x) > 0.5 ? Vec3d{0, 1, 0} : Vec3d{1, 0, 0};
            const Vec3d b1 = normalized(cross(n, a)), b2 = cross(n, b1);
            const Vec3d start = hit.position + n * offset;
            int open = 0;
            for (int r = 0; r < ao_rays; ++r) {
              const double u1 = random01(x, y, s, 2 + 2 * r), u2 = random01(x, y, s, 3 + 2 * r);
              const double radial = std::sqrt(u1), phi = 2 * pi * u2;
              const Vec3d d = b1 * (radial * std::cos(phi)) + b2 * (radial * std::sin(phi)) + n * std::sqrt(1 - u1);
              open += !tracer.occluded(start, d, float(ao_distance));
            }
            const double ao = double(open) / ao_rays;
            const double diffuse = std::max(0.0, dot(n, key));
            const double sky = 0.55 + 0.45 * dot(n, camera.up);
            Vec3d colour = hit.albedo * (0.72 * diffuse + 0.38 * sky * ao);
            if (g.curve) {
              const Vec3d half = normalized(key - direction);
              const double specular = 0.25 * std::pow(std::max(0.0, dot(n, half)), 40);
              colour = colour + Vec3d{specular, specular, specular};
            }
            sum = sum + colour;
            coverage += 1;
          }
          uint8_t* out = &image.rgba[(size_t(y) * o.width + x) * 4];
          if (o.background.transparent) {
            // Straight (not premultiplied) alpha, as PNG stores it.
            const Vec3d c = coverage > 0 ? sum * (1 / coverage) : Vec3d{};
            out[0] = to_byte(c.x), out[1] = to_byte(c.y), out[2] = to_byte(c.z);
            out[3] = uint8_t(std::lround(255 * coverage / o.samples));
          } else {
            const Vec3d c = (sum + background * (o.samples - coverage)) * (1.0 / o.samples);
            out[0] = to_byte(c.x), out[1] = to_byte(c.y), out[2] = to_byte(c.z), out[3] = 255;
          }
        }
    }
  });
  return image;
}

std::filesystem::path turntable_frame_path(const std::filesystem::path& path, int32_t frame, int32_t frames) {
  std::string number = std::to_string(frame);
  const size_t digits = std::max<size_t>(3, std::to_string(std::max(frames - 1, 0)).size());
  number.insert(0, digits - std::min(digits, number.size()), '0');
  std::filesystem::path out = path;
  out.replace_filename(path.stem().string() + "_" + number + path.extension().string());
  return out;
}

std::vector<std::filesystem::path> write_turntable(const Scene& scene, const RenderOptions& options, int32_t frames,
                                                   const std::filesystem::path& path) {
  constexpr int32_t max_frames = 100000;
  if (frames < 1 || frames > max_frames)
    throw UsageError("turntable of " + std::to_string(frames) + " frames: expected 1.." + std::to_string(max_frames));
  require_png_path(path);
  std::vector<std::filesystem::path> written;
  for (int32_t k = 0; k < frames; ++k) {
    RenderOptions frame = options;
    frame.framing = Framing::sphere;
    // Frame 0 keeps the view's azimuth as given: it is the still picture from that view.
    frame.view.azimuth = options.view.azimuth + 360.0 * k / frames;
    written.push_back(turntable_frame_path(path, k, frames));
    write_png(render(scene, frame), written.back());
  }
  return written;
}

} // namespace meander
