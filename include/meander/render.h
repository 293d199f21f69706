// Headless pictures of meshes and curves: ray tracing on the CPU with Embree, written
// as PNG. Meshes are drawn smooth-shaded (vertex normals, area-weighted) or serve as
// occluders (hidden, or drawn faintly), curves as round tubes or flat ribbons of constant
// screen width; a key light plus ambient occlusion; several jittered samples per pixel.
// Rendering is deterministic: the same scene and options give the same bytes, whatever
// the number of threads. Tiles are rendered in parallel (oneTBB).
#pragma once

#include "meander/image.h"
#include "meander/mesh.h"
#include "meander/textured_mesh.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

namespace meander {

// A colour with components in 0..1 as written in files (sRGB).
struct Rgb {
  float r = 0, g = 0, b = 0;
};

// How a mesh shows. The two occluder styles draw curves the way the paper's figures do:
// the parts behind the surface are not drawn ("back-face parts are not drawn for
// cleaner images"), and neither is the surface's own shading or shadow on the curves.
enum class MeshStyle {
  shaded, // smooth-shaded in its colour, with ambient occlusion
  hidden, // an occluder that is not drawn: its pixels show the background
  faint,  // an occluder drawn as a very light translucent grey that shows the shape
};

struct SceneMesh {
  PolygonMesh mesh; // polygons are fanned from their first vertex
  Rgb color{0.8f, 0.8f, 0.8f};
  MeshStyle style = MeshStyle::shaded;
  // With materials (textured_mesh.h), they colour the faces instead of `color`: the base
  // colour times the texture, sampled bilinearly in linear light at the texture
  // coordinate interpolated across the triangle. Must fit the mesh (check_appearance).
  Appearance appearance;
};

struct SceneCurves {
  Polylines curves; // closed loops and open polylines
  Rgb color{0.75f, 0.12f, 0.08f};
};

struct Scene {
  std::vector<SceneMesh> meshes;
  std::vector<SceneCurves> curves;
};

// Where the camera looks from, in degrees: azimuth around the vertical +y axis (0 looks
// from +z, 90 from +x), elevation above the horizontal plane (90 looks down from +y).
struct View {
  double azimuth = 45, elevation = 30;
};

struct Background {
  Rgb color{1, 1, 1};
  bool transparent = false; // transparent: an RGBA image whose alpha is the coverage
};

// Either way, curves are drawn over the surfaces they lie on: a surface hides a curve
// only where it is more than a few curve widths in front of it (two for tubes, four for
// ribbons), so the parts of a curve sunk into its surface still show and those on the
// far side of a solid do not.
enum class CurveStyle {
  tube,   // round tubes of one diameter in the scene: nearer parts look thicker
  ribbon, // flat ribbons facing the camera, flat-shaded, as wide in pixels at any depth
};

// Where the camera stands, always looking along `view`.
enum class Framing {
  // Looks at the centre of the points' extent across the view, from far enough that
  // every point is inside the picture with a 6% margin on each side.
  bounds,
  // Frames the projected points tightly: the eye is placed where the picture's four edge
  // planes, moved 3% inwards, touch the points (the nearer pair of edges touches, the
  // other pair is centred), so the object fills the picture.
  silhouette,
  // Looks at the centre of the bounding box from far enough that its bounding sphere is
  // inside the picture with a 6% margin, whatever the view: the same distance from
  // every direction (turntables).
  sphere,
};

// A camera placed by the caller (the studio's view as it is on screen), in place of the
// view and the framing: where the eye is, the point it looks at, which way is up, and
// the vertical field of view in degrees.
struct CameraPose {
  Vec3d eye, target, up{0, 1, 0};
  double fov_degrees = 25;
};

struct RenderOptions {
  int32_t width = 1600, height = 1200; // pixels, each 1..16384
  View view;
  Background background;
  int32_t samples = 4; // rays per pixel, 1..1024
  // Curve diameter in pixels: for tubes at the scene's centre, for ribbons everywhere.
  // 0: from the curve spacing on the meshes (a quarter of the mean distance between
  // neighbouring passes), at least 1.5 px.
  double curve_width = 0;
  CurveStyle curve_style = CurveStyle::tube;
  Framing framing = Framing::bounds;
  std::optional<CameraPose> camera; // set: used in place of view and framing
};

// The camera render() looks through for `scene` with `options` (their view and framing,
// or their camera): what a drawing of the same scene is seen with (drawing.h). Throws
// UsageError for a camera no picture can be taken with, as render() does.
CameraPose picture_camera(const Scene& scene, const RenderOptions& options);

// "front", "back", "left", "right", "top", "iso" or "AZ,EL" in degrees ("30,20").
// Throws UsageError("view 'x': expected front, back, left, right, top, iso or AZ,EL in degrees").
View parse_view(std::string_view text);

// "white", "transparent" or "#rrggbb". Throws UsageError naming the text.
Background parse_background(std::string_view text);

// "1600x1200" into width and height, each 1..16384. Throws UsageError naming the text.
void parse_size(std::string_view text, int32_t& width, int32_t& height);

// Renders the scene with a perspective camera (25 degrees vertical field of view) looking
// from `view`, placed as `framing` says. Throws UsageError for a size or sample count out
// of range. Time: building the BVH is about linear in the triangles and curve segments;
// then width * height * samples rays and a few ambient-occlusion rays each.
Image render(const Scene& scene, const RenderOptions& options);

// The file of frame `frame` (0-based) of a turntable of `frames`: "spin.png" becomes
// "spin_007.png", the number zero-padded to at least 3 digits (4 from 1001 frames on).
std::filesystem::path turntable_frame_path(const std::filesystem::path& path, int32_t frame, int32_t frames);

// Renders `frames` pictures turning around the vertical axis through the centre of the
// scene's bounds: frame k looks from azimuth view.azimuth + 360 * k / frames at the
// view's elevation, framed on the bounding sphere (options.framing is not used), so the
// camera keeps its distance and nothing leaves the picture. Frame 0 is render() with
// Framing::sphere. Writes each frame with write_png to turntable_frame_path(path, k,
// frames) and returns the paths. Throws UsageError for frames outside 1..100000 or a
// path that is not .png, before any work; frames already written stay if a later one
// fails. Time: `frames` renders.
std::vector<std::filesystem::path> write_turntable(const Scene& scene, const RenderOptions& options, int32_t frames,
                                                   const std::filesystem::path& path);

} // namespace meander
