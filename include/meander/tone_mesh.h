// A picture's tones as a mesh for `meander image` (docs/drawing.md): a quadtree of the
// picture's rectangle whose cells are smaller where the picture is darker, so that the
// Hamiltonian cycle through them, one closed line, lays more ink there (Bosch and
// Kaplan's TSP art, with a line that never crosses itself).
#pragma once

#include "meander/drawing.h"
#include "meander/mesh.h"
#include "meander/textured_mesh.h"

#include <cstdint>

namespace meander {

struct ToneOptions {
  // The gap between neighbouring passes of the curve in millimetres (the area it fills
  // over its length) where the picture is black and where it is white; the gap's inverse,
  // the ink, goes linearly with the darkness between them.
  double spacing = 0.6, max_spacing = 4;
  // Brightness is the picture's luma (Rec. 709, over white where it is transparent) to
  // the power 1/gamma: more than 1 lightens the middle tones.
  double gamma = 1;
  bool invert = false; // draw the light parts (a white pen on black paper)
};

// The cells of the quadtree over `area` (where the picture lies on the sheet) as polygons (z = 0): leaves of a grid of nearly
// square roots, each cell's corners and the midpoints its finer neighbours put on its
// sides (2:1 balanced, so at most one a side), all in one orientation; a connected disk.
// A cell splits where the picture's mean ink over it needs more than the cell gives: the
// part needed is diffused over each level's cells (Floyd-Steinberg), so that middle tones
// come out as an even mixture of two sizes whose ink is right on average.
// Throws ParameterError for options out of range and UsageError when the finest cells
// would number more than `max_cells`. Deterministic; O(pixels + finest cells * levels).
PolygonMesh tone_mesh(const Texture& picture, const Rect& area, const ToneOptions& options, int64_t max_cells = int64_t(1) << 23);

// About how many cells tone_mesh makes of `area` square millimetres of black, the most
// ink there is: the area over the square of the darkest cells' side (options.spacing
// times the passes a cell's line makes across it). What a caller bounds memory by.
double black_tone_cells(double area, const ToneOptions& options);

} // namespace meander
