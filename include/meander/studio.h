// The studio's work, apart from HTTP (studio_server.h serves it): what a page or a script
// asks for, checked; sessions holding an uploaded surface and its latest result; and
// the result made by the same library calls as the CLI's `curve` and `wire` and turned
// into the files the page shows and downloads. The JSON API is documented in
// docs/studio.md.
#pragma once

#include "meander/check.h"
#include "meander/curve.h"
#include "meander/duotone.h"
#include "meander/evenness.h"
#include "meander/jobs.h"
#include "meander/pipeline.h"
#include "meander/printability.h"
#include "meander/progress.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace meander {

// What the studio makes, as the page's mode menu lists them. The wire modes are
// `meander wire --method constant|variable --shape wire|ribbon`, duotone is `meander
// duotone` (duotone.h), picture is `meander image` of an uploaded picture (the only mode
// of a picture, which no other mode takes).
enum class StudioMode { curve, constant_wire, constant_ribbon, variable_wire, variable_ribbon, duotone, picture };

// Parses "curve" | "constant-wire" | "constant-ribbon" | "variable-wire" |
// "variable-ribbon" | "duotone" | "picture"; throws UsageError otherwise.
StudioMode parse_studio_mode(std::string_view name);

// A preview holds at most about this many elements (triangles, or a curve's segments)
// when fewer curve samples, or a wire drawn as its ribbon, can make it so: the page takes
// a preview of half a million triangles in about 0.2 s here (docs/studio.md, Speed).
constexpr int64_t studio_preview_budget = 500'000;

// A preview relaxes a spacing's curve (2 rounds) only on a remeshed surface of at most
// this many faces: the rounds cost about 0.1 s there, growing with the faces.
constexpr int64_t studio_preview_relax_faces = 10'000;

// What to make: the mode and the parameters of every mode's job (parameters.h), as the
// page keeps them all. Curve mode runs wire.curve (make_curve), the wire modes `wire`
// (its method and shape are the mode's), duotone `duotone`, picture `image`
// (make_line_picture).
struct StudioParams {
  StudioMode mode = StudioMode::curve;
  WireJob wire;
  DuotoneJob duotone;
  ImageJob image;
  // The quick version the page shows first after each change (and alone while a slider
  // is dragged): at most 2 curve samples per segment (1 where 2 would make the result
  // larger than studio_preview_budget, studio_result_size), a wire still over it drawn as
  // its ribbon, a variable ribbon still over it with one rung a triangle
  // (VariableWireOptions::rungs), levels and subdivide 0, at most 2 rounds of relaxation
  // with a spacing (none over studio_preview_relax_faces remeshed faces), `radius
  // auto` unchecked (see make_studio_result), a variable wire's self-intersections not
  // cleared (WireJob::clear), and no printability report. The full result follows it.
  // A picture's preview is its line with at most 2 curve samples per segment.
  bool preview = false;
};

struct MakeRequest {
  std::string session;
  StudioParams params;
  // For tests of clients: the job waits, once started, until it is cancelled
  // (Progress::hold), so that a test holds it in flight without making it slow. A
  // server takes it only when started for tests.
  bool hold = false;
};

// Parses the body of POST /api/make: a JSON object with "session" (required), "mode",
// "preview" and "hold" (booleans) and any parameter of any mode's job (parameters.h: numbers as JSON
// numbers, names as strings, "radius" a number or "auto", "colors" "C1,C2"), of which
// those of the mode's job are set and the others left alone; absent keys keep their
// defaults. Throws UsageError naming the key and what it expects ("s: expected a number
// in [0, 1], got 1.5", "colour: unknown parameter") for anything else: malformed JSON, a
// value of the wrong type or out of its parameter's range, an unknown key. Never throws
// anything else on any bytes (the fuzz target for the API's parameters).
MakeRequest parse_make_request(std::string_view body);

// Every mode's parameters for GET /api/parameters, so that the page's help is the CLI's:
// {"curve": [P, ...], "wire": [...], "duotone": [...], "picture": [...]}, each P {"name", "help",
// "default", and "min", "max", "choices" where it has them}.
std::string studio_parameters_json();

// What a session holds: a surface ready for the pipeline (read, repaired, its
// connectivity kept), or a picture for picture mode (the surface then empty).
struct StudioSurface {
  std::string name; // the file name messages use
  RepairResult repaired;
  int32_t input_vertices = 0, input_faces = 0; // as read, before repair
  Texture picture; // an uploaded picture
};

// The extensions of the pictures the studio takes (.png .jpg .jpeg .bmp .tga .gif), and
// whether a file name has one (case aside).
extern const std::array<std::string_view, 6> studio_picture_extensions;
bool is_studio_picture(std::string_view filename);

// Reads an uploaded file from memory, its format from the extension of `filename`
// (only the last path component is used, as the name in messages; nothing is read from
// or written to disk), and repairs it as `meander curve` does. OBJ, PLY, STL, OFF, GLB
// and glTF with embedded data; a glTF that refers to files outside itself is refused.
// A picture (is_studio_picture) is decoded as `meander image` reads it, and refused
// beyond `max_pixels` (0: no limit).
// Throws what read_mesh, repair and read_texture throw (the CLI's messages), UsageError
// for another extension, InputError for more faces than `max_faces` (0: no limit).
StudioSurface load_studio_surface(std::string_view filename, std::string_view bytes, int64_t max_faces = 0,
                                  int64_t max_pixels = 0);

// The bundled demo model: `meander generate pretzel --faces 1600`, light enough that
// every mode updates within about a second at the CLI's defaults.
StudioSurface demo_surface();

struct StudioResult {
  StudioParams params;
  // Quads, cycle and smooth curve; in duotone mode the duotone's quads and diagonals
  // and its separating curves.
  CurveResult curve;
  double curve_length = 0;
  // With a spacing (not in a preview or a duotone): how evenly the curve covers the input.
  std::optional<EvennessReport> evenness;
  PolygonMesh mesh;        // the wire, ribbon or duotone surface; empty in curve mode
  Appearance appearance;   // duotone: the tile atlas and texture coordinates of `mesh`
  double radius = 0;     // constant modes: the radius used (auto resolved)
  BridgePlan bridges;    // constant wire with bridges (not in a preview): where they are
  std::vector<uint8_t> bridge_faces; // and which faces of `mesh` are on them
  // Duotone with a shell (not in a preview): the two-colour print, or why it could not
  // be made (make_shell's TopologyError or ParameterError: a wall or gap too wide).
  std::optional<SplitShell> shell;
  std::string shell_refusal;
  PrintabilityReport report; // of a wire or ribbon (self-intersections, no thickness)
  // Of a self-intersecting wire or ribbon: how many of the cycle's triangles cross others
  // (crossing_cycle_triangles), so that the page can say when no settings will clear it.
  int32_t surface_crossings = 0;
  int64_t triangles = 0; // of the cycle (curve mode) or the mesh, after fanning
  LinePicture picture;   // picture mode's line and drawing (curve.curves is its line too)
  double seconds = 0;    // making it, report included
  // With a spacing: the even surface it was made on, which the next result of the same
  // spacing takes instead of remeshing again (shared, never changed).
  std::shared_ptr<const EvenSurface> even;
};

// How many elements make_studio_result(surface, params) would hold at its largest: curve
// points, triangles of the wire, ribbon or duotone surface, and texture pixels, counted
// from the surface's faces, corners and edges before any work (exact for the dual of
// Simplest and no quadrangulation, an upper bound for duotone), so that a server can
// refuse a request whose samples, sides, levels or subdivision would exhaust memory.
int64_t studio_result_size(const StudioSurface& surface, const StudioParams& params);

// Runs the mode's job on the surface as the CLI does (make_curve; wire_curve_job,
// make_curve and make_wire, its report without the thickness rays (the live view's stats;
// none for a preview); make_duotone, paint_duotone and separating_curves;
// make_line_picture). Throws what those throw, TopologyError messages naming the
// surface, UsageError for picture mode on a surface or another mode on a picture.
// `previous`, the session's last result if any, lends its duotone atlas when the tile
// options are the same (the atlas depends on them alone), its even surface when the
// spacing, model size and quadrangulation are the same, and to a constant preview with
// `radius auto` the radius it found, when it is a full result on the same curve.
// `progress`, if given, shows the stage under way and may cancel the work (Cancelled).
StudioResult make_studio_result(const StudioSurface& surface, const StudioParams& params,
                                const StudioResult* previous = nullptr, Progress* progress = nullptr);

// The stats beside the view as JSON: mode, preview, triangles, curves, curve_length, seconds,
// millimetres (not for a picture: true when made to a model size, its lengths in mm),
// leaves (of the curve's tree), gap_median and gap_cv (with a spacing, of a full result),
// for wires and ribbons vertices, faces, radius, preview_as_ribbon (true: a wire's preview
// drawn as its ribbon) and (not for a preview, which has no report) watertight,
// self_intersecting, volume, printable, bridges {count, longest_stretch, every_pass_tied}
// (with bridges), for duotone quads, faces, notes, shell {volumes, below_floor_corners,
// summary, apart (with a clearance)} or {refused} (with a shell), and for a
// picture cells (of its quadtree), paper [width, height] in millimetres, pen_up_travel;
// a picture's curve_length is its line's length on the sheet, in millimetres.
std::string studio_stats_json(const StudioResult& result);

// The files a result can be fetched as (GET /api/result/SESSION/NAME). The names are a
// fixed table: nothing a client sends is ever used as a path.
enum class StudioFile {
  surface, // the surface as the view draws it (binary, see studio_view_bytes)
  view,    // the result as the view draws it
  texture, // duotone: the tile atlas as PNG
  stl, threemf, glb, obj_zip, svg, png,
  duotone_svg, // picture: the two regions its line bounds
  print,       // duotone with a shell: the two-colour print (3MF)
};

// "surface.bin", "view.bin", "texture.png", "result.stl", "result.3mf", "result.glb",
// "result.zip", "curve.svg", "render.png", "duotone.svg", "print.3mf"; throws UsageError
// for any other name.
StudioFile parse_studio_file(std::string_view name);

// Geometry for the page's three.js view (docs/studio.md, "view.bin"): "MND3", the counts,
// flags and bounding box, then each array compressed by meshoptimizer's codecs: 16-bit
// quantized positions, int8 normals (when there are faces), 16-bit texture coordinates
// (with an appearance that has them), triangles (polygons fanned), line segments (the
// curves). The vertices are numbered as the triangles first use them, the curves' points
// after them; with texture coordinates each distinct (vertex, texture coordinate) pair of
// the corners is a vertex. The page decodes the arrays where the geometry uses them, with
// no loop over the vertices.
std::string studio_view_bytes(const PolygonMesh& mesh, const Polylines& curves, const Appearance& appearance = {});

struct StudioDownload {
  std::string bytes;
  std::string content_type;
  std::string filename; // offered to the browser (Content-Disposition): NAME_MODE[_preview].EXT
};

// How render.png is drawn: its size, and the camera of the page's view (none: framed as
// `meander curve --png` frames it); curve.svg with a camera is the plotter drawing of that
// view on an A4 sheet, landscape when the size is (none: curve_svg's, from the front).
// A picture's drawing has no camera: its PNG is the sheet at the largest size inside
// the size.
struct StudioPicture {
  int32_t width = 1200, height = 900;
  std::optional<CameraPose> camera;
};

// The picture a query asks for (GET .../render.png or curve.svg?size=WxH&eye=X,Y,Z&target=X,Y,Z&up=X,Y,Z&fov=DEGREES,
// each optional, eye and target together). Throws UsageError naming the key for anything
// else (and what render() refuses: a size over 16384 or a degenerate camera).
StudioPicture parse_studio_picture(const std::multimap<std::string, std::string>& query);

// One file of the result, made in memory. The zip holds OBJ + MTL (+ the PNG texture of
// a duotone), or the curve as OBJ (a picture's line in millimetres, as `meander image -o
// .obj` writes it). A picture's curve.svg, render.png and duotone.svg are what `meander
// image` writes as OUT.svg, OUT.png and --duotone. Throws UsageError for a mesh file in
// curve or picture mode, texture.png without a duotone, duotone.svg without a picture,
// surface.bin of a picture, print.3mf (the two solids of a shell as parts on two
// extruders, as `meander duotone --shell -o OUT.3mf` writes) without a shell.
StudioDownload studio_download(const StudioSurface& surface, const StudioResult& result, StudioFile file,
                               const StudioPicture& picture = {});

// Sessions: each holds a surface and its latest result, under a random 128-bit id
// (32 hex digits). Safe to call from many threads; work on one session is serialised
// by its own lock, different sessions run in parallel. The oldest sessions are dropped
// beyond `capacity`.
class StudioSessions {
public:
  struct Session {
    std::mutex lock; // held while making or reading `result`
    std::shared_ptr<const StudioSurface> surface;
    std::shared_ptr<const StudioResult> result; // null until the first make

    // The job of a new request: the one in flight, if any, is cancelled (it throws
    // Cancelled at its next check and lets go of `lock`), since nobody wants its result
    // any more. `abandoned` as Progress's.
    std::shared_ptr<Progress> start_job(std::function<bool()> abandoned = {});
    // The job is over (made, failed or cancelled).
    void end_job(const std::shared_ptr<Progress>& job);
    // Cancels the job in flight; false if there is none.
    bool cancel_job();
    // The job in flight's stage and fraction; nullopt when there is none.
    std::optional<Progress::State> job_state() const;

  private:
    mutable std::mutex job_lock_;
    std::shared_ptr<Progress> job_;
  };

  explicit StudioSessions(size_t capacity = 32) : capacity_(capacity) {}
  struct Added {
    std::string id;
    std::shared_ptr<Session> session;
  };
  // Stores the surface in a new session; returns its id and the session itself, which
  // the caller holds even when other threads' adds drop it from the table at once (a
  // find by the id could then come back empty).
  Added add(StudioSurface surface);
  // The session, or null for an unknown or dropped id (any string is safe to pass).
  std::shared_ptr<Session> find(std::string_view id) const;

private:
  mutable std::mutex lock_;
  size_t capacity_;
  uint64_t clock_ = 0;
  struct Entry {
    std::shared_ptr<Session> session;
    uint64_t created;
  };
  std::unordered_map<std::string, Entry> sessions_;
};

} // namespace meander
