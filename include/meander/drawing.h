// Plotter drawings (`meander draw`, docs/drawing.md): curves seen from a view as the
// pictures see them, the parts a surface hides removed, laid out in millimetres on a sheet
// of paper as the paths a pen draws, in an order that keeps the pen's travel short.
#pragma once

#include "meander/mesh.h"
#include "meander/render.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace meander {

// A sheet of paper and the margin left blank on each side, in millimetres.
struct Paper {
  double width = 210, height = 297, margin = 10;
};

// "A4", "A3", "A5", "letter", "legal" or "WxH" in millimetres ("300x200mm", "300x200"),
// portrait; `landscape` turns it. Throws UsageError naming the text.
Paper parse_paper(std::string_view text, bool landscape = false);

struct DrawingOptions {
  // Where the drawing is seen from, as the pictures' (render.h): the view and framing,
  // or a camera. The sheet's drawable area gives the picture's proportions.
  View view;
  Framing framing = Framing::bounds;
  std::optional<CameraPose> camera;
  Paper paper;
  // The pen's width in millimetres: the drawing keeps no more points than it shows (a
  // point within a twentieth of it of the line through its neighbours is dropped).
  double pen = 0.3;
  // Set: millimetres on paper a unit of the curves, at the depth of the centre of their
  // bounding box (a model sized in millimetres drawn at true size there), and the sheet is
  // the drawing's size and the margins round it, in place of fitting the drawing to `paper`.
  std::optional<double> scale;
};

struct Point2 {
  double x = 0, y = 0;
};

// A rectangle on the sheet, in millimetres from its top-left corner.
struct Rect {
  double x = 0, y = 0, width = 0, height = 0;
};

// Paths on the paper in millimetres from its top-left corner, x to the right and y down
// (as SVG): path k is points[start[k] .. start[k+1]), closed back to its first point when
// closed[k] is set, drawn from the curve layer[k]; in drawing order, layer by layer.
struct Drawing {
  Paper paper;
  std::vector<Point2> points;
  std::vector<int32_t> start{0};
  std::vector<uint8_t> closed;
  std::vector<int32_t> layer;
  int32_t layers = 0; // the curves drawn from, one layer each (some may have no path)
  // Millimetres with the pen down, and with it up from one path's end to the next path's start.
  double drawn_length = 0, travel = 0;

  int32_t size() const { return int32_t(start.size()) - 1; }
};

// The curves as seen from options' view, their parts hidden by `occluder` (may be
// empty) left out: a point is hidden when the surface lies in front of it by more than
// half the surface's mean edge (a curve on the surface strays from it by less: smoothed,
// it cuts a little inside across the faces), and each change from seen to hidden is placed
// on its segment to within 1/256 of the segment. The seen parts are fitted to the sheet
// inside its margins (uniformly scaled, centred; or drawn at options.scale), runs of a closed curve across its
// first point joined, points the pen cannot show dropped (and paths shorter than its
// width, which would be dots), and the paths of each curve
// ordered nearest first (from the sheet's top-left corner, then each path's end), open
// ones drawn either way. Throws UsageError for a sheet no larger than its margins or a
// pen not a positive number. Parallel (oneTBB); deterministic.
Drawing draw_curves(const Polylines& curves, const PolygonMesh& occluder, const DrawingOptions& options);

// Curves already on the sheet (x, y in millimetres from its top-left corner, y down; z
// is not used) as a drawing, each a layer: the points the pen cannot show dropped, paths
// shorter than its width left out, in draw_curves' order. O(points).
Drawing sheet_drawing(const Polylines& curves, const Paper& paper, double pen);

// The drawing as SVG for plotters and Inkscape: the sheet's size in millimetres (one user
// unit a millimetre), one Inkscape layer per curve, each path one <path> of straight
// segments in drawing order, stroked with the pen's width.
std::string drawing_svg(const Drawing& drawing, double pen);

// The two regions a drawing of closed paths bounds inside `area` as SVG: `inside` where an
// odd number of them surround a point (one simple closed curve: what it encloses), the
// rest of the area `outside`, no stroke (the duotone of a line picture).
std::string duotone_svg(const Drawing& drawing, const Rect& area, Rgb inside, Rgb outside);

// The drawing as the paper shows it: the largest picture of the sheet's proportions
// inside `width` x `height` pixels, the pen's strokes black and antialiased on white.
// Throws UsageError for a side outside 1..16384. O(pixels + points * pen width).
Image drawing_image(const Drawing& drawing, double pen, int32_t width, int32_t height);

// Writes drawing_svg atomically (io.h, write_bytes).
void write_drawing(const Drawing& drawing, double pen, const std::filesystem::path& path);

} // namespace meander
