// Headless pictures of meshes and curves: ray tracing on the CPU with Embree, written
// as PNG. Meshes are drawn smooth-shaded (vertex normals, area-weighted), curves as
// round tubes; a key light plus ambient occlusion; several jittered samples per pixel.
// Rendering is deterministic: the same scene and options give the same bytes, whatever
// the number of threads. Tiles are rendered in parallel (oneTBB).
#pragma once

#include "meander/mesh.h"

#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

namespace meander {

// A colour with components in 0..1 as written in files (sRGB).
struct Rgb {
  float r = 0, g = 0, b = 0;
};

struct SceneMesh {
  PolygonMesh mesh; // polygons are fanned from their first vertex
  Rgb color{0.8f, 0.8f, 0.8f};
  // Occluder only: hides what is behind it but is not drawn (its pixels show the
  // background), as the paper draws curves with their back parts hidden.
  bool occluder_only = false;
};

struct SceneCurves {
  Polylines curves; // each polyline is a closed loop
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

struct RenderOptions {
  int32_t width = 1600, height = 1200; // pixels, each 1..16384
  View view;
  Background background;
  int32_t samples = 4; // rays per pixel, 1..1024
  // Tube diameter in pixels at the scene's centre; 0: from the curve spacing on the
  // meshes (a quarter of the mean distance between neighbouring passes), at least 1.5 px.
  double curve_width = 0;
};

// An 8-bit image, rows top to bottom; rgba holds 4 bytes per pixel.
struct Image {
  int32_t width = 0, height = 0;
  bool has_alpha = false; // written as RGBA if set, else RGB
  std::vector<uint8_t> rgba;
};

// "front", "back", "left", "right", "top", "iso" or "AZ,EL" in degrees ("30,20").
// Throws UsageError("view 'x': expected front, back, left, right, top, iso or AZ,EL in degrees").
View parse_view(std::string_view text);

// "white", "transparent" or "#rrggbb". Throws UsageError naming the text.
Background parse_background(std::string_view text);

// "1600x1200" into width and height, each 1..16384. Throws UsageError naming the text.
void parse_size(std::string_view text, int32_t& width, int32_t& height);

// Renders the scene with a perspective camera looking at the centre of the scene's
// bounds from `view`, fitted so that every point is inside the picture with a margin.
// Throws UsageError for a size or sample count out of range. Time: building the BVH is
// about linear in the triangles and curve segments; then width * height * samples rays
// and a few ambient-occlusion rays each.
Image render(const Scene& scene, const RenderOptions& options);

// Writes the image as PNG (RGB, or RGBA if it has alpha). Atomic: no partial file is
// left. Throws UsageError if the extension is not .png, IOError if it cannot be written.
void write_png(const Image& image, const std::filesystem::path& path);

} // namespace meander
