#include "meander/drawing.h"

#include "embree/embree_scene.h"
#include "meander/error.h"
#include "meander/io.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace meander {

Paper parse_paper(std::string_view text, bool landscape) {
  std::string name(text);
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  constexpr std::pair<std::string_view, std::array<double, 2>> named[] = {
      {"a3", {297, 420}}, {"a4", {210, 297}}, {"a5", {148, 210}}, {"letter", {215.9, 279.4}}, {"legal", {215.9, 355.6}}};
  Paper paper;
  bool found = false;
  for (const auto& [key, size] : named)
    if (name == key) paper.width = size[0], paper.height = size[1], found = true;
  if (!found) {
    std::string_view rest = name;
    if (rest.ends_with("mm")) rest.remove_suffix(2);
    const size_t x = rest.find('x');
    double w = 0, h = 0;
    const auto number = [](std::string_view digits, double& value) {
      const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
      return error == std::errc() && end == digits.data() + digits.size() && std::isfinite(value) && value > 0;
    };
    if (x == std::string_view::npos || !number(rest.substr(0, x), w) || !number(rest.substr(x + 1), h))
      throw UsageError("paper '" + std::string(text) +
                       "': expected A3, A4, A5, letter, legal or WIDTHxHEIGHT in millimetres (300x200mm)");
    paper.width = w, paper.height = h;
  }
  if (landscape != (paper.width > paper.height)) std::swap(paper.width, paper.height);
  return paper;
}

namespace {

// The occluding surface as Embree triangles (polygons fanned from their first corner).
class Occluder {
public:
  // Robust: a ray through an edge or a vertex of the surface must not slip between its
  // faces (the rays of a circle on a sphere meet its meridians' edges).
  explicit Occluder(const PolygonMesh& mesh) : rtc_("draw", RTC_SCENE_FLAG_ROBUST, RTC_BUILD_QUALITY_MEDIUM) {
    std::vector<uint32_t> triangles;
    for (int32_t f = 0; f < mesh.num_faces(); ++f) {
      const auto face = mesh.face(f);
      for (size_t i = 1; i + 1 < face.size(); ++i)
        triangles.insert(triangles.end(), {uint32_t(face[0]), uint32_t(face[i]), uint32_t(face[i + 1])});
    }
    if (!triangles.empty()) {
      RTCGeometry geometry = rtcNewGeometry(rtc_.device(), RTC_GEOMETRY_TYPE_TRIANGLE);
      set_vertices(geometry, mesh.positions);
      auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                     3 * sizeof(uint32_t), triangles.size() / 3));
      std::copy(triangles.begin(), triangles.end(), indices);
      rtc_.attach(geometry);
      empty_ = false;
    }
    rtc_.commit();
  }

  // Whether the surface crosses the line from `eye` to `p` more than `slack` before p.
  bool hides(Vec3d eye, Vec3d p, double slack) const {
    if (empty_) return false;
    const Vec3d d = p - eye;
    const double length = norm(d);
    if (length <= slack) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = float(eye.x), ray.org_y = float(eye.y), ray.org_z = float(eye.z);
    ray.dir_x = float(d.x), ray.dir_y = float(d.y), ray.dir_z = float(d.z);
    ray.tnear = 0;
    ray.tfar = float(1 - slack / length);
    ray.mask = 0xFFFFFFFF;
    rtcOccluded1(rtc_.scene(), &context, &ray);
    return ray.tfar < 0;
  }

private:
  EmbreeScene rtc_;
  bool empty_ = true;
};

// The mean length of the surface's edges (each counted once per face it bounds).
double mean_edge(const PolygonMesh& m) {
  double length = 0;
  for (int32_t f = 0; f < m.num_faces(); ++f) {
    const auto face = m.face(f);
    for (size_t i = 0; i < face.size(); ++i)
      length += norm(to_double(m.positions[size_t(face[(i + 1) % face.size()])]) - to_double(m.positions[size_t(face[i])]));
  }
  return m.num_corners() > 0 ? length / m.num_corners() : 0;
}

// Squared, and not through std::hypot, whose care for overflow took a fifth of a line
// picture's time: millimetres on a sheet do not overflow.
double distance2(Point2 a, Point2 b) { return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y); }
double distance(Point2 a, Point2 b) { return std::sqrt(distance2(a, b)); }

// From p to the segment a-b, squared.
double to_segment2(Point2 p, Point2 a, Point2 b) {
  const double dx = b.x - a.x, dy = b.y - a.y, length2 = dx * dx + dy * dy;
  const double t = length2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / length2, 0.0, 1.0) : 0.0;
  return distance2(p, {a.x + t * dx, a.y + t * dy});
}

// Douglas-Peucker: of the n points at(0) .. at(n - 1), those that keep the path within
// `tolerance` (its ends kept; a closed path is simplified as the open one back to its
// first point). Through `at`, so that a curve's points are read where they are.
template <class At> std::vector<Point2> simplified(size_t n, bool closed, double tolerance, At&& at) {
  const size_t m = closed && n > 0 ? n + 1 : n; // point n of a closed path is its first
  const auto point = [&](size_t i) { return at(i == n ? 0 : i); };
  std::vector<Point2> out;
  if (m < 3) {
    for (size_t i = 0; i < n; ++i) out.push_back(at(i));
    return out;
  }
  std::vector<uint8_t> keep(m, 0);
  keep[0] = keep[m - 1] = 1;
  std::vector<std::pair<size_t, size_t>> stack{{0, m - 1}};
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    double farthest = -1;
    size_t far = a;
    const Point2 pa = point(a), pb = point(b);
    for (size_t i = a + 1; i < b; ++i)
      if (const double d = to_segment2(point(i), pa, pb); d > farthest) farthest = d, far = i;
    if (farthest > tolerance * tolerance) {
      keep[far] = 1;
      stack.emplace_back(a, far);
      stack.emplace_back(far, b);
    }
  }
  for (size_t i = 0; i < n; ++i)
    if (keep[i]) out.push_back(at(i));
  return out;
}

struct Path {
  std::vector<Point2> points;
  bool closed = false;
  int32_t layer = 0;
};

// Each layer's paths, nearest first: from the pen's place, the path with the nearest
// start (or, open, either end: it is then drawn backwards); O(P^2) over a layer's P paths,
// which the few dozen cuts per curve keep small.
std::vector<Path> ordered(std::vector<Path> paths, int32_t layers) {
  std::vector<Path> out;
  out.reserve(paths.size());
  Point2 pen{0, 0};
  for (int32_t layer = 0; layer < layers; ++layer) {
    std::vector<size_t> left;
    for (size_t i = 0; i < paths.size(); ++i)
      if (paths[i].layer == layer) left.push_back(i);
    while (!left.empty()) {
      double best = INFINITY;
      size_t pick = 0;
      bool reversed = false;
      for (size_t j = 0; j < left.size(); ++j) {
        const Path& p = paths[left[j]];
        if (const double d = distance(pen, p.points.front()); d < best) best = d, pick = j, reversed = false;
        if (!p.closed)
          if (const double d = distance(pen, p.points.back()); d < best) best = d, pick = j, reversed = true;
      }
      Path& p = paths[left[pick]];
      if (reversed) std::reverse(p.points.begin(), p.points.end());
      pen = p.closed ? p.points.front() : p.points.back();
      out.push_back(std::move(p));
      left.erase(left.begin() + std::ptrdiff_t(pick));
    }
  }
  return out;
}

void check_sheet(const Paper& paper, double pen) {
  const double area_width = paper.width - 2 * paper.margin, area_height = paper.height - 2 * paper.margin;
  if (!(paper.margin >= 0 && area_width > 0 && area_height > 0 && std::isfinite(area_width + area_height)))
    throw UsageError("paper of " + std::to_string(paper.width) + " x " + std::to_string(paper.height) +
                     " mm: no room inside margins of " + std::to_string(paper.margin) + " mm");
  if (!(pen > 0 && std::isfinite(pen))) throw UsageError("pen: expected a positive width in millimetres");
}

// The points of a path the pen shows: those more than a twentieth of its width off the
// line through the points kept round them.
double pen_tolerance(double pen) { return pen / 20; }

// Paths on the sheet, simplified for the pen, as the drawing: no dots, in order.
Drawing laid_out(std::vector<Path> paths, const Paper& paper, double pen, int32_t layers) {
  // A path shorter than the pen is wide would be a dot: a glimpse of the curve at a
  // silhouette.
  std::erase_if(paths, [&](const Path& p) {
    double length = 0;
    for (size_t i = 1; i < p.points.size(); ++i) length += distance(p.points[i - 1], p.points[i]);
    return p.points.size() < 2 || length < pen;
  });

  Drawing drawing{.paper = paper, .layers = layers};
  Point2 at{0, 0};
  for (Path& p : ordered(std::move(paths), layers)) {
    drawing.travel += distance(at, p.points.front());
    for (size_t i = 1; i < p.points.size(); ++i) drawing.drawn_length += distance(p.points[i - 1], p.points[i]);
    if (p.closed) drawing.drawn_length += distance(p.points.back(), p.points.front());
    at = p.closed ? p.points.front() : p.points.back();
    drawing.points.insert(drawing.points.end(), p.points.begin(), p.points.end());
    drawing.start.push_back(int32_t(drawing.points.size()));
    drawing.closed.push_back(p.closed);
    drawing.layer.push_back(p.layer);
  }
  return drawing;
}

} // namespace

Drawing draw_curves(const Polylines& curves, const PolygonMesh& occluder, const DrawingOptions& options) {
  Paper paper = options.paper;
  check_sheet(paper, options.pen);
  if (options.scale && !(*options.scale > 0 && std::isfinite(*options.scale)))
    throw UsageError("drawing scale: expected a positive number of millimetres a unit");
  const double area_width = paper.width - 2 * paper.margin, area_height = paper.height - 2 * paper.margin;

  // The pictures' camera for this scene, in the drawable area's proportions.
  Scene scene;
  scene.meshes.push_back({.mesh = occluder, .style = MeshStyle::hidden});
  scene.curves.push_back({.curves = curves});
  RenderOptions picture{.width = int32_t(std::clamp(std::lround(1000 * area_width / area_height), 1L, 16384L)),
                        .height = 1000,
                        .view = options.view,
                        .framing = options.framing,
                        .camera = options.camera};
  const CameraPose pose = picture_camera(scene, picture);
  scene = {};
  const Vec3d eye = pose.eye;
  const Vec3d forward = (pose.target - pose.eye) * (1 / norm(pose.target - pose.eye));
  const Vec3d right = cross(forward, pose.up) * (1 / norm(cross(forward, pose.up)));
  const Vec3d up = cross(right, forward);

  // A point is hidden behind more than half the surface's mean edge: a curve on the
  // surface strays from it by less (smoothed, it cuts inside across the faces).
  const Occluder surface(occluder);
  const double slack = 0.5 * mean_edge(occluder);
  const auto seen = [&](Vec3d p) { return dot(p - eye, forward) > 0 && !surface.hides(eye, p, slack); };
  std::vector<uint8_t> visible(curves.points.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, visible.size(), 1024), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) visible[i] = seen(to_double(curves.points[i]));
  });
  // Where the curve goes from seen (a) to hidden (b): the last seen point of the segment,
  // to 1/256 of it.
  const auto edge = [&](Vec3d a, Vec3d b) {
    for (int step = 0; step < 8; ++step) {
      const Vec3d middle = (a + b) * 0.5;
      (seen(middle) ? a : b) = middle;
    }
    return a;
  };
  const auto project = [&](Vec3d p) {
    const Vec3d d = p - eye;
    const double depth = dot(d, forward);
    return Point2{dot(d, right) / depth, -dot(d, up) / depth};
  };

  std::vector<Path> paths;
  for (int32_t k = 0; k < curves.size(); ++k) {
    const int32_t first = curves.start[size_t(k)], n = curves.start[size_t(k) + 1] - first;
    const bool closed = curves.closed(k);
    const auto at = [&](int32_t i) { return to_double(curves.points[size_t(first + (i % n + n) % n)]); };
    const auto shown = [&](int32_t i) { return visible[size_t(first + (i % n + n) % n)] != 0; };
    if (n == 0) continue;
    int32_t hidden_at = -1;
    for (int32_t i = 0; i < n && hidden_at < 0; ++i)
      if (!shown(i)) hidden_at = i;
    if (hidden_at < 0) {
      Path whole{.closed = closed, .layer = k};
      for (int32_t i = 0; i < n; ++i) whole.points.push_back(project(at(i)));
      paths.push_back(std::move(whole));
      continue;
    }
    // Runs of seen points; on a closed curve from its first hidden point round, so that a
    // run across the first point is one path.
    const int32_t begin = closed ? hidden_at : 0, end = closed ? hidden_at + n : n;
    Path run{.layer = k};
    for (int32_t i = begin; i <= end; ++i) {
      const bool inside = i < end && shown(i);
      if (inside && run.points.empty() && (closed || i > 0)) run.points.push_back(project(edge(at(i), at(i - 1))));
      if (inside) run.points.push_back(project(at(i)));
      if (!inside && !run.points.empty()) {
        if (i < end || closed) run.points.push_back(project(edge(at(i - 1), at(i))));
        paths.push_back(std::move(run));
        run = {.layer = k};
      }
    }
  }

  // Fitted to the drawable area, centred; then only the points the pen shows.
  double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
  for (const Path& p : paths)
    for (const Point2& q : p.points)
      lo_x = std::min(lo_x, q.x), hi_x = std::max(hi_x, q.x), lo_y = std::min(lo_y, q.y), hi_y = std::max(hi_y, q.y);
  const double extent_x = paths.empty() ? 0 : hi_x - lo_x, extent_y = paths.empty() ? 0 : hi_y - lo_y;
  double fit = 1;
  if (options.scale) { // true size at the depth of the curves' centre, on a sheet the drawing's size
    const Box3 box = bounding_box(curves.points);
    fit = *options.scale * dot(to_double(box.min + box.max) * 0.5 - eye, forward);
    paper.width = extent_x * fit + 2 * paper.margin, paper.height = extent_y * fit + 2 * paper.margin;
  } else if (const double scale = std::min(extent_x > 0 ? area_width / extent_x : INFINITY,
                                           extent_y > 0 ? area_height / extent_y : INFINITY);
             std::isfinite(scale)) {
    fit = scale;
  }
  const double offset_x = (paper.width - extent_x * fit) / 2 - (paths.empty() ? 0 : lo_x) * fit;
  const double offset_y = (paper.height - extent_y * fit) / 2 - (paths.empty() ? 0 : lo_y) * fit;
  tbb::parallel_for(size_t(0), paths.size(), [&](size_t i) {
    const std::vector<Point2>& p = paths[i].points;
    paths[i].points = simplified(p.size(), paths[i].closed, pen_tolerance(options.pen), [&](size_t k) {
      return Point2{offset_x + p[k].x * fit, offset_y + p[k].y * fit};
    });
  });
  return laid_out(std::move(paths), paper, options.pen, curves.size());
}

Drawing sheet_drawing(const Polylines& curves, const Paper& paper, double pen) {
  check_sheet(paper, pen);
  std::vector<Path> paths(size_t(curves.size()));
  tbb::parallel_for(int32_t(0), curves.size(), [&](int32_t k) {
    const auto p = curves.polyline(k);
    paths[size_t(k)] = {.points = simplified(p.size(), curves.closed(k), pen_tolerance(pen), [&](size_t i) { return Point2{p[i].x, p[i].y}; }),
                        .closed = curves.closed(k),
                        .layer = k};
  });
  return laid_out(std::move(paths), paper, pen, curves.size());
}

namespace {

// Millimetres to 1/1000, without the trailing zeros that say nothing ("12.5", "3").
void put(std::string& out, double value) {
  char number[64];
  const auto [end, error] = std::to_chars(number, number + sizeof number, value, std::chars_format::fixed, 3);
  std::string_view text(number, error == std::errc() ? size_t(end - number) : 0);
  while (text.find('.') != std::string_view::npos && (text.back() == '0' || text.back() == '.')) {
    const bool dot = text.back() == '.';
    text.remove_suffix(1);
    if (dot) break;
  }
  out += text == "-0" ? "0" : text;
}

void put_header(std::string& out, const Paper& paper) {
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
         "xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" width=\"";
  put(out, paper.width);
  out += "mm\" height=\"";
  put(out, paper.height);
  out += "mm\" viewBox=\"0 0 ";
  put(out, paper.width);
  out += ' ';
  put(out, paper.height);
  out += "\">\n";
}

// Path k's d attribute: "M x y L x y ... Z".
void put_path(std::string& out, const Drawing& d, int32_t k) {
  for (int32_t i = d.start[size_t(k)]; i < d.start[size_t(k) + 1]; ++i) {
    out += i == d.start[size_t(k)] ? "M" : " L";
    put(out, d.points[size_t(i)].x);
    out += ' ';
    put(out, d.points[size_t(i)].y);
  }
  if (d.closed[size_t(k)]) out += " Z";
}

std::string hex(Rgb c) {
  char text[8];
  const auto byte = [](float v) { return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255)); };
  std::snprintf(text, sizeof text, "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
  return text;
}

} // namespace

std::string drawing_svg(const Drawing& d, double pen) {
  std::string out;
  out.reserve(d.points.size() * 18 + 1024); // " L123.456 78.901"
  put_header(out, d.paper);
  for (int32_t k = 0, path = 0; k < d.layers; ++k) {
    if (path == d.size() || d.layer[size_t(path)] != k) continue;
    out += "<g inkscape:groupmode=\"layer\" inkscape:label=\"" + std::to_string(k + 1) + " curve " + std::to_string(k + 1) +
           "\" id=\"layer" + std::to_string(k + 1) + "\" fill=\"none\" stroke=\"black\" stroke-width=\"";
    put(out, pen);
    out += "\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
    for (; path < d.size() && d.layer[size_t(path)] == k; ++path) {
      out += "<path d=\"";
      put_path(out, d, path);
      out += "\"/>\n";
    }
    out += "</g>\n";
  }
  out += "</svg>\n";
  return out;
}

std::string duotone_svg(const Drawing& d, const Rect& area, Rgb inside, Rgb outside) {
  std::string out;
  put_header(out, d.paper);
  out += "<rect x=\"";
  put(out, area.x);
  out += "\" y=\"";
  put(out, area.y);
  out += "\" width=\"";
  put(out, area.width);
  out += "\" height=\"";
  put(out, area.height);
  out += "\" fill=\"" + hex(outside) + "\"/>\n<path fill=\"" + hex(inside) + "\" fill-rule=\"evenodd\" d=\"";
  for (int32_t k = 0; k < d.size(); ++k)
    if (d.closed[size_t(k)]) {
      if (out.back() != '"') out += ' ';
      put_path(out, d, k);
    }
  out += "\"/>\n</svg>\n";
  return out;
}

Image drawing_image(const Drawing& d, double pen, int32_t width, int32_t height) {
  if (width < 1 || width > 16384 || height < 1 || height > 16384)
    throw UsageError("picture of " + std::to_string(width) + " x " + std::to_string(height) +
                     " pixels: each side must be 1 to 16384");
  const int32_t w = std::max<int32_t>(1, int32_t(std::min<double>(width, std::floor(height * d.paper.width / d.paper.height))));
  const int32_t h = std::max<int32_t>(1, int32_t(std::round(w * d.paper.height / d.paper.width)));
  const double scale = w / d.paper.width; // pixels a millimetre
  const double radius = std::max(0.5, pen * scale / 2);
  // Each pixel's ink, the most any stroke gives it: a stroke's coverage falls from 1 to
  // 0 across the pixel at its edge.
  std::vector<float> ink(size_t(w) * size_t(h));
  const auto stroke = [&](Point2 a, Point2 b) {
    a = {a.x * scale - 0.5, a.y * scale - 0.5}, b = {b.x * scale - 0.5, b.y * scale - 0.5}; // pixel centres at integers
    const int32_t x0 = std::max(0, int32_t(std::floor(std::min(a.x, b.x) - radius - 1)));
    const int32_t x1 = std::min(w - 1, int32_t(std::ceil(std::max(a.x, b.x) + radius + 1)));
    const int32_t y0 = std::max(0, int32_t(std::floor(std::min(a.y, b.y) - radius - 1)));
    const int32_t y1 = std::min(h - 1, int32_t(std::ceil(std::max(a.y, b.y) + radius + 1)));
    for (int32_t y = y0; y <= y1; ++y)
      for (int32_t x = x0; x <= x1; ++x) {
        const float cover = float(std::clamp(radius + 0.5 - std::sqrt(to_segment2({double(x), double(y)}, a, b)), 0.0, 1.0));
        float& pixel = ink[size_t(y) * size_t(w) + size_t(x)];
        pixel = std::max(pixel, cover);
      }
  };
  for (int32_t k = 0; k < d.size(); ++k) {
    const int32_t first = d.start[size_t(k)], last = d.start[size_t(k) + 1] - 1;
    for (int32_t i = first; i < last; ++i) stroke(d.points[size_t(i)], d.points[size_t(i) + 1]);
    if (d.closed[size_t(k)] && last > first) stroke(d.points[size_t(last)], d.points[size_t(first)]);
  }
  Image image{.width = w, .height = h};
  image.rgba.resize(ink.size() * 4);
  for (size_t i = 0; i < ink.size(); ++i) {
    const auto grey = uint8_t(std::lround(255 * (1 - ink[i])));
    image.rgba[4 * i] = image.rgba[4 * i + 1] = image.rgba[4 * i + 2] = grey;
    image.rgba[4 * i + 3] = 255;
  }
  return image;
}

void write_drawing(const Drawing& drawing, double pen, const std::filesystem::path& path) {
  write_bytes(path, drawing_svg(drawing, pen));
}

} // namespace meander
