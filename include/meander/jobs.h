// The wire and duotone jobs, as the CLI's `wire` and `duotone`, the studio and scripts
// run them, so that every client makes the same thing from the same parameters
// (parameters.h describes them). A wire is make_curve (pipeline.h) with wire_curve_job,
// then make_wire; a duotone is make_duotone (duotone.h), then paint_duotone: two steps,
// so that a client can refuse between them a result too large for its memory. Pictures
// of a result: the *_scene functions.
#pragma once

#include "meander/bridges.h"
#include "meander/drawing.h"
#include "meander/duotone.h"
#include "meander/io.h"
#include "meander/pipeline.h"
#include "meander/printability.h"
#include "meander/render.h"
#include "meander/shell.h"
#include "meander/tone_mesh.h"
#include "meander/wire.h"

#include <optional>
#include <string>
#include <vector>

namespace meander {

enum class WireMethod {
  constant, // a polygon or line swept along the smooth curve (constant_wire)
  variable, // trapezoids inside the cycle's triangles, smoothed by Catmull-Clark (variable_wire)
};

// Parses "constant" | "variable"; throws UsageError otherwise.
WireMethod parse_wire_method(std::string_view name);

struct WireJob {
  CurveJob curve;
  WireMethod method = WireMethod::constant;
  WireShape shape = WireShape::wire;
  std::optional<double> radius; // constant: > 0, or none for the largest clear one
  int sides = 8;                // constant wire
  // Wire (not ribbon): bridges (bridges.h) so that no stretch longer than this goes without one.
  std::optional<double> bridges;
  double s = 0.6, t = 0.6, thickness = 0;
  int levels = 2;
  // Variable: the mesh is first made ready for slabs (SlabMeshOptions: stars, caps over
  // cap_angle flipped, needles collapsed) unless keep_faces.
  double cap_angle = 120;
  bool keep_faces = false;
  // Variable: VariableWireOptions::clear and rungs.
  bool clear = true;
  int rungs = 2;
  // The printability report: none (a preview), or with the thickness of a wire measured
  // (a ribbon has none) when measure_thickness, and judged against min_thickness.
  bool report = true;
  bool measure_thickness = true;
  double min_thickness = 0;
  // The nozzle width in millimetres: with curve.model_size, min_thickness defaults to 2
  // nozzles and parts of the wire must keep a nozzle apart; the report also gives the
  // smallest size the wire prints at (PrintabilityOptions::nozzle).
  double nozzle = 0.4;
};

// The curve job a wire is made on: job.curve, with the slab mesh of the variable method.
CurveJob wire_curve_job(const WireJob& job);

// How many triangles make_wire would make on a curve of this many cycle triangles.
int64_t wire_triangles(int64_t cycle_triangles, const WireJob& job);

struct WireResult {
  PolygonMesh mesh;
  double radius = 0; // constant: the radius used
  // With WireJob::bridges: where they are (ends into the curve's points), the longest
  // stretch without one, whether they join every curve.
  BridgePlan bridges;
  std::vector<uint8_t> bridge_faces; // with bridges fused in: per face of mesh, 1 on a strut
  PrintabilityReport report;
  // Of a self-intersecting wire: the cycle's triangles that cross others
  // (crossing_cycle_triangles), where no wire that follows the surface can be clear.
  std::vector<int32_t> surface_crossings;
};

// The wire on a curve made with wire_curve_job(job), then its report. Throws
// TopologyError when no radius avoids a self-intersection, ParameterError for values out
// of range, and what constant_wire, variable_wire and check_printability throw. Appends
// to `times` if given, and tells `progress` (which may cancel it: Cancelled) if given.
WireResult make_wire(const CurveResult& curve, const WireJob& job, StageTimes* times = nullptr,
                     Progress* progress = nullptr);

// The printability report as JSON (printability_json), with WireJob::bridges a
// "bridges" object too: count, longest_stretch, every_pass_tied, one_piece.
std::string wire_report_json(const WireResult& wire, const WireJob& job);

// What the slab mesh changed, as sentences ("flipped 3 edges facing an angle over 120
// degrees"), none when nothing; for the user to read beside the result.
std::vector<std::string> slab_mesh_notes(const CurveResult& curve, const WireJob& job);

struct DuotoneJob {
  std::optional<double> model_size; // as CurveJob::model_size
  // Set: the duotone is made on the surface remeshed evenly so that the separating
  // curve's neighbouring passes lie about this far apart (remesh_to_spacing).
  std::optional<double> spacing;
  int64_t max_faces = 0; // with spacing: as CurveJob::max_faces
  DuotoneOptions duotone;
  TileOptions tiles;
  int subdivide = 0; // Catmull-Clark levels of the painted surface
  // Set: a two-colour print, the surface thickened by this wall and cut along the curve
  // (make_shell), judged against min_thickness (with a model size 0.8 mm unless set).
  std::optional<double> shell;
  double min_thickness = 0;
  double clearance = 0; // > 0 with shell: the two solids that far apart (ShellOptions::clearance)
};

// make_duotone(mesh, connectivity, job.duotone), on the remeshed surface with job.spacing
// (its vertices on the input surface). Throws what remesh_to_spacing and make_duotone
// throw, and Cancelled by `progress`, if given, between its stages.
Duotone make_duotone(const PolygonMesh& mesh, const Connectivity& connectivity, const DuotoneJob& job,
                     Progress* progress = nullptr);

// Those of a duotone job with DuotoneJob::spacing set (pipeline.h).
EvenSurfaceOptions even_surface_options(const DuotoneJob& job);

// The same on an even surface made for this job (throws UsageError unless
// even.options == even_surface_options(job)), without the remesh's time.
Duotone make_duotone(const EvenSurface& even, const DuotoneJob& job, Progress* progress = nullptr);

// The duotone make_duotone(mesh, connectivity, job) made, painted with
// job.tiles and subdivided job.subdivide levels. `atlas`, if not empty, is
// duotone_atlas(job.tiles) already made. Throws ParameterError for values out of range,
// and what duotone_surface and subdivide throw. Appends to `times` if given; `progress`
// as make_wire's.
TexturedMesh paint_duotone(const Duotone& duotone, const DuotoneJob& job, const Texture& atlas = {},
                           StageTimes* times = nullptr, Progress* progress = nullptr);

// The two-colour print of a duotone make_duotone(mesh, connectivity, job) made, with
// job.shell set: duotone_shell (shell.h) with the job's tiles. Throws UsageError without
// job.shell, and what duotone_shell throws.
SplitShell make_shell(const Duotone& duotone, const DuotoneJob& job);

// One paragraph for people (no trailing newline): the solids' triangles and volumes, the
// wall, and where it is thinner than asked or than the floor.
std::string shell_summary(const SplitShell& shell, const DuotoneJob& job);

// Two solids as the parts of a print (write_3mf_parts, io.h) in these colours, named
// "colour 1 (#rrggbb)" and "colour 2 (...)".
std::array<ColoredPart, 2> colored_parts(const PolygonMesh& first, const PolygonMesh& second,
                                         const std::array<Color8, 2>& colors);

// The one SVG of curves, what `meander curve -o OUT.svg`, `duotone --curve OUT.svg`, the
// studio's curve.svg and meander.write_curves write: the plotter drawing (drawing.h)
// seen from the front (along -z: x to the right, y up), the parts `surface` hides
// removed (none where it is empty), with a 0.3 mm pen; with `millimetres` (a model size)
// at true size on a sheet 2 mm larger than the drawing on each side, else fitted to an
// A4 sheet inside 10 mm margins.
std::string curve_svg(const Polylines& curves, const PolygonMesh& surface, bool millimetres);

// The same of a curve make_curve made, hidden by the surface it lies on.
std::string curve_svg(const CurveResult& curve, bool millimetres);

// The drawing of a curve make_curve made, hidden by the surface it lies on (what `meander
// draw` draws of a mesh).
Drawing draw_curve(const CurveResult& curve, const DrawingOptions& options);

// `meander image`: a picture drawn with one closed line on a sheet (docs/drawing.md).
struct ImageJob {
  ToneOptions tone;
  // The sheet and its margin, turned to the picture's orientation; the picture fills what
  // is inside the margins as far as its proportions let it, centred.
  Paper paper;
  // Set: the picture is this wide in millimetres, and the sheet is the picture and the
  // margins round it (`paper`'s size is not used).
  std::optional<double> width;
  double pen = 0.3; // millimetres
  CycleOptions cycle;
  CurveOptions curve;
  int64_t max_pixels = 50'000'000; // a larger picture is refused (read_texture)
  // The duotone's regions: inside the curve, and between it and the picture's edges.
  std::array<Color8, 2> colors = TileOptions{}.colors;
};

struct LinePicture {
  Rect area;       // where the picture lies on the sheet
  Polylines curve; // the closed curve on the sheet: millimetres, y down, z = 0
  Drawing drawing;
  int32_t cells = 0; // the quadtree's
  int64_t leaves = -1; // the tree's, with job.cycle.count_leaves
};

// tone_mesh of the picture on the sheet, its Hamiltonian cycle (one: the cells are a
// disk) and the smooth curve, laid out as a drawing. Throws ParameterError for values out
// of range, UsageError for a sheet with no room inside its margins, and Cancelled by
// `progress` between stages. Appends to `times` if given.
LinePicture make_line_picture(const Texture& picture, const ImageJob& job, StageTimes* times = nullptr,
                              Progress* progress = nullptr);

// The line picture's duotone (duotone_svg): inside the curve in the first colour.
std::string line_picture_duotone_svg(const LinePicture& picture, const ImageJob& job);

// The line as a curve file holds it (`meander image -o OUT.obj`): millimetres with y up,
// as 3D programs show it.
Polylines line_picture_curve(const LinePicture& picture);

// The colours of the pictures: a copper wire on a light grey surface, its bridges blue.
inline constexpr Rgb wire_color{0.72f, 0.45f, 0.2f};
inline constexpr Rgb bridge_color{0.2f, 0.42f, 0.62f};
inline constexpr Rgb surface_color{0.82f, 0.82f, 0.82f};

// The pictures, as in the paper's figures: the curve with the surface (the cycle's
// triangles) hiding its back parts; a wire (of `job`'s shape and method) half sunk in
// the surface it follows, drawn `occluder`; a ribbon, which lies in the surface, alone;
// a duotone as painted. The faces `bridge_faces` flags (WireResult::bridge_faces; none
// if empty) are drawn in the bridges' colour.
Scene curve_scene(const CurveResult& curve, MeshStyle occluder = MeshStyle::hidden);
Scene wire_scene(PolygonMesh wire, const CurveResult& curve, const WireJob& job, MeshStyle occluder = MeshStyle::hidden,
                 std::span<const uint8_t> bridge_faces = {});
Scene duotone_scene(const TexturedMesh& surface);

} // namespace meander
