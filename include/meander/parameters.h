// Every parameter of the curve, wire and duotone jobs, described once (name, range,
// choices, help; the default is the job struct's): the CLI's options, the studio's
// request keys and its help (GET /api/parameters), and the jobs' own checks are all
// made from these descriptions, so a parameter is added in one place. A name is
// snake_case, as the studio and scripts spell it ("texture_size"); the CLI spells it
// --texture-size.
#pragma once

#include "meander/jobs.h"

#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

namespace meander {

struct Parameter {
  std::string_view name;
  std::string_view help;
  // Numbers: the range, both ends allowed.
  double min = -INFINITY, max = INFINITY;
  // Names: the accepted ones (radius, a positive number or a name, lists its name).
  std::span<const std::string_view> choices;
  // A length: its value may carry a unit (mm, cm, m, in), and is then in millimetres,
  // which only a model size allows (has_unit), unless the length is always in millimetres.
  bool length = false;
  bool millimetres = false;
};

// The value of parameter p from text, as the CLI gets it and the studio gets names:
// throws ParameterError naming p ("samples: expected an integer in [1, 1000], got 0").
// T is int, uint64_t, double, bool, one of the jobs' enums, std::optional<double> (a
// number in p's range where it has one, else a positive number, or p's one choice for
// none: radius "auto", spacing "none"), std::array<Color8, 2> (colors) or Paper
// (parse_paper's names and sizes; the margin is a parameter of its own).
template <class T> void set_parameter(const Parameter& p, std::string_view text, T& value);

// A value of parameter p as set_parameter reads it: the default shown in help texts.
template <class T> std::string parameter_text(const Parameter& p, const T& value);

// Whether `text`, a value of a length parameter, carries a unit ("3mm", "4.7in"). A length
// with a unit is read in millimetres; check_unit refuses one without a model size.
bool has_unit(std::string_view text);

// Throws ParameterError when `text`, a value of parameter p, carries a unit while the job
// has no model size (`sized`): lengths are then in the model's own units. The model size
// and the lengths always in millimetres (the nozzle, a sheet's) may carry one. `model_size` is the model size's
// name as the client spells it ("--model-size", "model_size").
void check_unit(const Parameter& p, std::string_view text, bool sized, std::string_view model_size);

// A length that is not a job's (a sheet's margin, a pen): a non-negative number of
// millimetres, or a number with its unit ("10mm", "1cm", "0.5in"). Throws ParameterError
// naming `name`.
double millimetres(std::string_view name, std::string_view text);

// Throws ParameterError unless `value` is a number in p's range (an integer where `integer`).
void check_parameter(const Parameter& p, double value, bool integer);

// Calls visit(parameter, field) for each parameter of a CurveJob, WireJob, DuotoneJob or
// ImageJob (const or not), in the order the help lists them; `field` is a reference into the job.
template <class Job, class Visit> void visit_parameters(Job& job, Visit&& visit);

// Throws ParameterError for the first value of the job out of its parameter's range.
void check_parameters(const CurveJob& job);
void check_parameters(const WireJob& job);
void check_parameters(const DuotoneJob& job);
void check_parameters(const ImageJob& job);

// The descriptions.
namespace parameters {

inline constexpr std::string_view quad_choices[] = {"dual-simplest", "catmull-clark", "none"};
inline constexpr std::string_view tree_choices[] = {"random", "uniform", "bfs", "dfs", "shaped"};
inline constexpr std::string_view smooth_choices[] = {"bspline", "catmull-rom", "none"};
inline constexpr std::string_view method_choices[] = {"constant", "variable"};
inline constexpr std::string_view shape_choices[] = {"wire", "ribbon"};
inline constexpr std::string_view radius_choices[] = {"auto"};
inline constexpr std::string_view spacing_choices[] = {"none"};
inline constexpr std::string_view bridges_choices[] = {"none"};
inline constexpr std::string_view model_size_choices[] = {"none"};
inline constexpr std::string_view branches_choices[] = {"none"};
inline constexpr std::string_view duotone_quad_choices[] = {"catmull-clark", "dual-simplest", "none"};
inline constexpr std::string_view rule_choices[] = {"tree", "flip"};
inline constexpr std::string_view tiles_choices[] = {"truchet", "outline", "triangles", "stripes", "dots"};
inline constexpr std::string_view shell_choices[] = {"none"};

inline constexpr Parameter quad{.name = "quad", .help = "quadrangulation", .choices = quad_choices};
inline constexpr Parameter tree{.name = "tree",
                                .help = "spanning tree strategy: the style of the meander (shaped: random, preferring "
                                        "well-shaped triangles)",
                                .choices = tree_choices};
inline constexpr Parameter branches{.name = "branches",
                                    .help = "the waviness of the curve, continuously from long snakes (0) to many "
                                            "short branches (1): the random tree grown by that rule (none: --tree's "
                                            "own; -v prints the tree's leaves, the branches' tips)",
                                    .min = 0,
                                    .max = 1,
                                    .choices = branches_choices};
inline constexpr Parameter seed{.name = "seed", .help = "random seed (same seed, same output)"};
inline constexpr Parameter smooth{.name = "smooth", .help = "smoothing of the control polygon", .choices = smooth_choices};
inline constexpr Parameter samples{.name = "samples", .help = "points per control polygon segment", .min = 1, .max = 1000};
inline constexpr Parameter model_size{.name = "model_size",
                                      .help = "scale the model so that its largest bounding-box side is this long "
                                              "(120mm, 12cm, 4.7in; a bare number is millimetres): every file is then "
                                              "in millimetres (glTF in metres), and lengths may carry units (none: the "
                                              "model's own units)",
                                      .choices = model_size_choices,
                                      .length = true,
                                      .millimetres = true};
inline constexpr Parameter spacing{.name = "spacing",
                                   .help = "the distance between neighbouring passes of the curve, in mesh units "
                                           "(millimetres with a model size): the surface is first remeshed evenly to "
                                           "it (none: the mesh's own edges)",
                                   .choices = spacing_choices,
                                   .length = true};
inline constexpr Parameter relax{.name = "relax",
                                 .help = "with --spacing: rounds of evening the gaps between the curve's passes on the "
                                         "surface (0: the curve as made on the even mesh)",
                                 .min = 0,
                                 .max = 200};

inline constexpr Parameter method{.name = "method",
                                  .help = "constant: a polygon or line swept along the smooth curve; variable: trapezoids "
                                          "inside the cycle's triangles, smoothed by Catmull-Clark",
                                  .choices = method_choices};
inline constexpr Parameter shape{.name = "shape", .help = "wire (closed tube) or ribbon (band on the surface)", .choices = shape_choices};
inline constexpr Parameter radius{.name = "radius",
                                  .help = "constant: tube radius or half the ribbon width in mesh units (millimetres "
                                          "with a model size), or auto: the largest that does not self-intersect (with "
                                          "--spacing: a fifth of the spacing, or less where the curve comes nearer)",
                                  .choices = radius_choices,
                                  .length = true};
inline constexpr Parameter bridges{.name = "bridges",
                                   .help = "wire (constant or variable): fuse neighbouring passes with struts where they come closest, "
                                           "so that no stretch of the wire longer than this goes without one and the "
                                           "print is one rigid piece, in mesh units (millimetres with a model size; "
                                           "about 4 spacings; none: a free loop)",
                                   .choices = bridges_choices,
                                   .length = true};
inline constexpr Parameter sides{.name = "sides", .help = "constant wire: sides of the swept polygon (and of the bridges' struts)", .min = 3, .max = 64};
inline constexpr Parameter s{.name = "s", .help = "variable: trapezoid size across the curve (1 covers the surface)", .min = 0, .max = 1};
inline constexpr Parameter t{.name = "t", .help = "variable: trapezoid size along the curve", .min = 0, .max = 1};
inline constexpr Parameter thickness{.name = "thickness",
                                     .help = "variable wire: slab thickness in mesh units (millimetres with a model "
                                             "size; 0: half the local ribbon width)",
                                     .min = 0,
                                     .length = true};
inline constexpr Parameter cap_angle{.name = "cap_angle",
                                     .help = "variable: first flip the long edge of flat triangles whose largest angle "
                                             "exceeds this many degrees (180: flip none)",
                                     .min = 90,
                                     .max = 180};
inline constexpr Parameter keep_faces{.name = "keep_faces",
                                      .help = "variable: build on the mesh's faces as they are, without splitting polygons "
                                              "of 5 or more sides into triangles, flipping flat triangles or collapsing "
                                              "the short edges of needles and of triangles folded over"};
inline constexpr Parameter levels{.name = "levels", .help = "variable: Catmull-Clark subdivision levels", .min = 0, .max = 6};
inline constexpr Parameter min_thickness{.name = "min_thickness",
                                         .help = "wire: the thinnest wall the printer makes, in mesh units "
                                                 "(millimetres with a model size; about twice the nozzle width); "
                                                 "thinner is reported as not printable",
                                         .min = 0,
                                         .length = true};
inline constexpr Parameter nozzle{.name = "nozzle",
                                  .help = "wire: the printer's nozzle width in millimetres: with a model size a wire is "
                                          "printable only if at least 2 nozzles thick (unless --min-thickness says "
                                          "otherwise) with its parts a nozzle apart; without one, the report says the "
                                          "smallest size it prints at",
                                  .min = 0.01,
                                  .max = 10,
                                  .length = true,
                                  .millimetres = true};

inline constexpr Parameter duotone_quad{.name = "quad",
                                        .help = "2-colourable quads: catmull-clark (dual-simplest on a mesh with "
                                                "boundary), dual-simplest (larger tiles), none (an all-quad closed input "
                                                "whose vertices are 2-colourable)",
                                        .choices = duotone_quad_choices};
inline constexpr Parameter rule{.name = "rule",
                                .help = "tree: a spanning tree of the yellow diagonals (the reviewer's rule); flip: random "
                                        "diagonals flipped until one curve (the paper's)",
                                .choices = rule_choices};
inline constexpr Parameter duotone_tree{.name = "tree", .help = "which spanning tree: the look", .choices = {tree_choices, 4}};
inline constexpr Parameter colors{.name = "colors",
                                  .help = "the two colours C1,C2: names (yellow, gold, blue, navy, red, ...) or #rrggbb"};
inline constexpr Parameter tiles{.name = "tiles", .help = "tile style", .choices = tiles_choices};
inline constexpr Parameter texture_size{.name = "texture_size", .help = "texture atlas width in pixels (even)", .min = 64, .max = 8192};
inline constexpr Parameter subdivide{.name = "subdivide",
                                     .help = "Catmull-Clark subdivision levels of the textured surface (OpenSubdiv, "
                                             "texture coordinates carried along)",
                                     .min = 0,
                                     .max = 5};
inline constexpr Parameter shell{.name = "shell",
                                 .help = "a two-colour print: the surface thickened inward by this wall (in mesh units; "
                                         "millimetres with a model size) and cut along the curve into two solids, one "
                                         "per colour (-o OUT.3mf, --parts A.stl,B.stl; none: the painted surface)",
                                 .choices = shell_choices,
                                 .length = true};
inline constexpr Parameter shell_min_thickness{.name = "min_thickness",
                                               .help = "with --shell: the thinnest wall the printer makes, in mesh "
                                                       "units (millimetres with a model size, where it is 0.8 unless "
                                                       "given); where the model is too thin for it the report says so",
                                               .min = 0,
                                               .length = true};
inline constexpr Parameter clearance{.name = "clearance",
                                     .help = "with --shell: draw the two pieces this far apart at the cut, to be printed "
                                             "apart and put together, in mesh units (millimetres with a model size; 0: "
                                             "they meet, one print)",
                                     .min = 0,
                                     .length = true};

// `meander image`: every length in millimetres on the sheet.
inline constexpr std::string_view width_choices[] = {"none"};
inline constexpr Parameter image_spacing{.name = "spacing",
                                         .help = "the gap between neighbouring passes of the line where the picture is "
                                                 "black (mm, or with a unit)",
                                         .min = 0.05,
                                         .max = 100,
                                         .length = true,
                                         .millimetres = true};
inline constexpr Parameter max_spacing{.name = "max_spacing",
                                       .help = "the gap where the picture is white (mm, or with a unit; at least the spacing)",
                                       .min = 0.05,
                                       .max = 1000,
                                       .length = true,
                                       .millimetres = true};
inline constexpr Parameter gamma{.name = "gamma",
                                 .help = "brightness is the picture's to the power 1/gamma: more than 1 lightens the "
                                         "middle tones, less darkens them",
                                 .min = 0.1,
                                 .max = 10};
inline constexpr Parameter invert{.name = "invert", .help = "draw the light parts instead of the dark (a light pen on dark paper)"};
inline constexpr Parameter paper{.name = "paper", .help = "the sheet: A3, A4, A5, letter, legal or WIDTHxHEIGHT in mm, "
                                                          "turned to the picture's orientation"};
inline constexpr Parameter margin{.name = "margin",
                                  .help = "blank margin on each side of the sheet (mm, or with a unit)",
                                  .min = 0,
                                  .length = true,
                                  .millimetres = true};
inline constexpr Parameter width{.name = "width",
                                 .help = "the picture's width on the sheet (mm, or with a unit), the sheet then the "
                                         "picture and its margins (none: as large as the paper allows)",
                                 .choices = width_choices,
                                 .length = true,
                                 .millimetres = true};
inline constexpr Parameter pen{.name = "pen",
                               .help = "the pen's width (mm, or with a unit): the stroke, and the detail kept",
                               .min = 0.01,
                               .max = 20,
                               .length = true,
                               .millimetres = true};
inline constexpr Parameter max_pixels{.name = "max_pixels", .help = "refuse a larger picture", .min = 1};
inline constexpr Parameter duotone_colors{.name = "colors",
                                          .help = "the duotone's colours C1,C2 (inside the line, outside): names (yellow, "
                                                  "gold, blue, navy, red, ...) or #rrggbb"};

} // namespace parameters

template <class Job, class Visit> void visit_parameters(Job& job, Visit&& visit) {
  using Plain = std::remove_const_t<Job>;
  static_assert(std::is_same_v<Plain, CurveJob> || std::is_same_v<Plain, WireJob> || std::is_same_v<Plain, DuotoneJob> ||
                std::is_same_v<Plain, ImageJob>);
  if constexpr (std::is_same_v<Plain, CurveJob>) {
    visit(parameters::model_size, job.model_size);
    visit(parameters::spacing, job.spacing);
    visit(parameters::relax, job.relax);
    visit(parameters::quad, job.quadrangulation);
    visit(parameters::tree, job.cycle.tree);
    visit(parameters::branches, job.cycle.branches);
    visit(parameters::seed, job.cycle.seed);
    visit(parameters::smooth, job.curve.smoothing);
    visit(parameters::samples, job.curve.samples);
  } else if constexpr (std::is_same_v<Plain, WireJob>) {
    visit(parameters::method, job.method);
    visit(parameters::shape, job.shape);
    visit_parameters(job.curve, visit);
    visit(parameters::radius, job.radius);
    visit(parameters::sides, job.sides);
    visit(parameters::bridges, job.bridges);
    visit(parameters::s, job.s);
    visit(parameters::t, job.t);
    visit(parameters::thickness, job.thickness);
    visit(parameters::cap_angle, job.cap_angle);
    visit(parameters::keep_faces, job.keep_faces);
    visit(parameters::levels, job.levels);
    visit(parameters::min_thickness, job.min_thickness);
    visit(parameters::nozzle, job.nozzle);
  } else if constexpr (std::is_same_v<Plain, ImageJob>) {
    visit(parameters::paper, job.paper);
    visit(parameters::margin, job.paper.margin);
    visit(parameters::width, job.width);
    visit(parameters::pen, job.pen);
    visit(parameters::image_spacing, job.tone.spacing);
    visit(parameters::max_spacing, job.tone.max_spacing);
    visit(parameters::gamma, job.tone.gamma);
    visit(parameters::invert, job.tone.invert);
    visit(parameters::tree, job.cycle.tree);
    visit(parameters::branches, job.cycle.branches);
    visit(parameters::seed, job.cycle.seed);
    visit(parameters::smooth, job.curve.smoothing);
    visit(parameters::samples, job.curve.samples);
    visit(parameters::max_pixels, job.max_pixels);
    visit(parameters::duotone_colors, job.colors);
  } else {
    visit(parameters::model_size, job.model_size);
    visit(parameters::spacing, job.spacing);
    visit(parameters::duotone_quad, job.duotone.quadrangulation);
    visit(parameters::rule, job.duotone.rule);
    visit(parameters::duotone_tree, job.duotone.tree);
    visit(parameters::seed, job.duotone.seed);
    visit(parameters::colors, job.tiles.colors);
    visit(parameters::tiles, job.tiles.style);
    visit(parameters::texture_size, job.tiles.texture_size);
    visit(parameters::subdivide, job.subdivide);
    visit(parameters::shell, job.shell);
    visit(parameters::shell_min_thickness, job.min_thickness);
    visit(parameters::clearance, job.clearance);
  }
}

} // namespace meander
