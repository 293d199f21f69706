#include "meander/tone_mesh.h"

#include "meander/error.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace meander {

namespace {

// The gap between neighbouring passes of the curve (the area over the length) through
// a grid of square cells of side h, dual-simplest quadrangulation, B-spline curve: h / this.
// Measured on uniform grids of 100 x 80 to 400 x 320 cells (tests/image_test.cpp holds it).
constexpr double kPassesPerCell = 1.61;

// The extra ink of seams between cells of two sizes (splits below): measured on flat
// greys, the ink over 1 + p of the cells' was up to 1.12; with this, the ink is within 3%
// of the tone's from black to white (tests/image_test.cpp holds it to 5%).
constexpr double kSeams = 0.65;

// The darkness of each pixel, 0 white .. 1 black, by its 16-bit luma over white.
std::vector<float> darkness_table(const ToneOptions& options) {
  std::vector<float> table(65281);
  for (size_t i = 0; i < table.size(); ++i) {
    const double brightness = std::pow(double(i) / 65280, 1 / options.gamma);
    table[i] = float(options.invert ? brightness : 1 - brightness);
  }
  return table;
}

// The picture's mean darkness over each of nx x ny equal cells covering it (box filter:
// every pixel weighs by the part of it inside the cell), rows top to bottom.
std::vector<float> cell_darkness(const Texture& picture, int32_t nx, int32_t ny, const ToneOptions& options) {
  const std::vector<float> table = darkness_table(options);
  const int32_t w = picture.width, h = picture.height;
  // The pixels [first, last] under cell i of n over a side of `side` pixels, each with the
  // part of it inside.
  const auto overlap = [](int32_t i, int32_t n, int32_t side, int32_t j) {
    const double lo = double(i) * side / n, hi = double(i + 1) * side / n;
    return std::max(0.0, std::min(hi, j + 1.0) - std::max(lo, double(j)));
  };
  const auto first = [](int32_t i, int32_t n, int32_t side) { return int32_t(std::floor(double(i) * side / n)); };
  const auto last = [](int32_t i, int32_t n, int32_t side) {
    return std::min(side - 1, int32_t(std::ceil(double(i + 1) * side / n)) - 1);
  };
  std::vector<float> rows(size_t(h) * size_t(nx)); // each pixel row filtered across
  tbb::parallel_for(int32_t(0), h, [&](int32_t y) {
    const uint8_t* row = picture.rgba.data() + size_t(y) * size_t(w) * 4;
    for (int32_t i = 0; i < nx; ++i) {
      double sum = 0;
      for (int32_t j = first(i, nx, w); j <= last(i, nx, w); ++j) {
        const uint8_t* p = row + size_t(j) * 4;
        const uint32_t luma = 54u * p[0] + 183u * p[1] + 19u * p[2]; // Rec. 709 weights over 256
        const uint32_t over_white = (luma * p[3] + 65280u * (255u - p[3])) / 255u;
        sum += table[over_white] * overlap(i, nx, w, j);
      }
      rows[size_t(y) * size_t(nx) + size_t(i)] = float(sum * nx / w);
    }
  });
  std::vector<float> cells(size_t(nx) * size_t(ny));
  tbb::parallel_for(int32_t(0), ny, [&](int32_t k) {
    for (int32_t y = first(k, ny, h); y <= last(k, ny, h); ++y) {
      const double weight = overlap(k, ny, h, y) * ny / h;
      for (int32_t i = 0; i < nx; ++i)
        cells[size_t(k) * size_t(nx) + size_t(i)] += float(rows[size_t(y) * size_t(nx) + size_t(i)] * weight);
    }
  });
  return cells;
}

} // namespace

PolygonMesh tone_mesh(const Texture& picture, const Rect& area, const ToneOptions& options, int64_t max_cells) {
  if (!(options.spacing > 0 && std::isfinite(options.spacing)))
    throw ParameterError("spacing", ": expected a positive length, got " + std::to_string(options.spacing));
  if (!(options.max_spacing >= options.spacing && std::isfinite(options.max_spacing)))
    throw ParameterError("max_spacing", ": expected a length no less than the spacing (" + std::to_string(options.spacing) +
                                            " mm), got " + std::to_string(options.max_spacing));
  if (!(options.gamma > 0 && std::isfinite(options.gamma)))
    throw ParameterError("gamma", ": expected a positive number, got " + std::to_string(options.gamma));
  if (picture.width < 1 || picture.height < 1 || picture.rgba.size() != size_t(picture.width) * size_t(picture.height) * 4)
    throw UsageError("picture: no pixels");

  // Levels 0 (roots, the widest gap) to `levels` (at most `spacing`), each halving the cell.
  const int levels = int(std::ceil(std::log2(options.max_spacing / options.spacing) - 1e-9));
  const double root = options.max_spacing * kPassesPerCell;
  const int32_t roots_x = std::max(1, int32_t(std::ceil(area.width / root - 1e-9)));
  const int32_t roots_y = std::max(1, int32_t(std::ceil(area.height / root - 1e-9)));
  const int64_t fine_x = int64_t(roots_x) << levels, fine_y = int64_t(roots_y) << levels;
  if (!(fine_x * fine_y <= max_cells))
    throw UsageError("a spacing of " + std::to_string(options.spacing) + " mm over " + std::to_string(area.width) + " x " +
                     std::to_string(area.height) + " mm needs " + std::to_string(fine_x * fine_y) +
                     " of the finest cells, more than " + std::to_string(max_cells) + ": choose a larger spacing");
  const int32_t nx = int32_t(fine_x), ny = int32_t(fine_y);

  // Mean darkness per cell at each level, finest first computed from the pixels.
  std::vector<std::vector<float>> mean(size_t(levels) + 1);
  mean[size_t(levels)] = cell_darkness(picture, nx, ny, options);
  for (int k = levels - 1; k >= 0; --k) {
    const int32_t cx = roots_x << k, cy = roots_y << k;
    const std::vector<float>& fine = mean[size_t(k) + 1];
    std::vector<float>& coarse = mean[size_t(k)];
    coarse.resize(size_t(cx) * size_t(cy));
    for (int32_t y = 0; y < cy; ++y)
      for (int32_t x = 0; x < cx; ++x) {
        const size_t a = size_t(2 * y) * size_t(2 * cx) + size_t(2 * x), b = a + size_t(2 * cx);
        coarse[size_t(y) * size_t(cx) + size_t(x)] = (fine[a] + fine[a + 1] + fine[b] + fine[b + 1]) / 4;
      }
  }

  // A cell of level k should split where its ink density (passes per millimetre, the
  // gap's inverse) falls short of the picture's, by the part of what splitting adds that
  // it lacks (the children's density is twice the cell's). Where a part p of the cells
  // split, the line winds more along the seams between the two sizes: measured, the ink is
  // the cells' times 1 + p + kSeams p (1 - p), which p is solved from. Each level's cells
  // then split or not by error diffusion of p (Floyd-Steinberg, serpentine), so that a
  // middle tone is an even, unpatterned mixture of two sizes with the right ink.
  const double cell_x = area.width / nx, cell_y = area.height / ny;
  const double finest_gap = std::sqrt(cell_x * cell_y) / kPassesPerCell;
  std::vector<std::vector<uint8_t>> split(static_cast<size_t>(levels));
  for (int k = 0; k < levels; ++k) {
    const int32_t cx = roots_x << k, cy = roots_y << k;
    const double has = 1 / (finest_gap * double(1 << (levels - k)));
    split[size_t(k)].resize(size_t(cx) * size_t(cy));
    std::vector<double> error(size_t(cx) + 2), below(size_t(cx) + 2); // one cell of slack at each end
    for (int32_t y = 0; y < cy; ++y) {
      const int step = y % 2 == 0 ? 1 : -1;
      for (int32_t i = 0; i < cx; ++i) {
        const int32_t x = step > 0 ? i : cx - 1 - i;
        const size_t cell = size_t(y) * size_t(cx) + size_t(x);
        const double wanted = 1 / options.max_spacing + mean[size_t(k)][cell] * (1 / options.spacing - 1 / options.max_spacing);
        const double more = (wanted - has) / has;
        const double part =
            more >= 1 ? 1 : std::max(0.0, (1 + kSeams - std::sqrt((1 + kSeams) * (1 + kSeams) - 4 * kSeams * more)) / (2 * kSeams));
        const double value = part + error[size_t(x + 1)];
        split[size_t(k)][cell] = value > 0.5;
        const double e = value - split[size_t(k)][cell];
        error[size_t(x + 1 + step)] += e * 7 / 16;
        below[size_t(x + 1 - step)] += e * 3 / 16;
        below[size_t(x + 1)] += e * 5 / 16;
        below[size_t(x + 1 + step)] += e / 16;
      }
      std::swap(error, below);
      std::fill(below.begin(), below.end(), 0.0);
    }
  }
  std::vector<uint8_t> level(size_t(nx) * size_t(ny));
  tbb::parallel_for(int32_t(0), ny, [&](int32_t y) {
    for (int32_t x = 0; x < nx; ++x) {
      int k = 0;
      while (k < levels && split[size_t(k)][size_t(y >> (levels - k)) * size_t(roots_x << k) + size_t(x >> (levels - k))]) ++k;
      level[size_t(y) * size_t(nx) + size_t(x)] = uint8_t(k);
    }
  });

  // 2:1 balance: neighbouring cells at most one level apart. A cell of level j splits the
  // coarser neighbours of levels below j - 1 down to j - 1 (each split gives the block
  // around the neighbour one level more); from the finest level down, so that what a
  // split makes is seen by the levels after.
  const auto at = [&](int32_t x, int32_t y) -> uint8_t& { return level[size_t(y) * size_t(nx) + size_t(x)]; };
  for (int j = levels; j >= 2; --j)
    for (int32_t y = 0; y < ny; ++y)
      for (int32_t x = 0; x < nx; ++x) {
        if (at(x, y) != j) continue;
        const std::array<std::array<int32_t, 2>, 4> next{{{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}}};
        for (const auto& [px, py] : next) {
          if (px < 0 || py < 0 || px >= nx || py >= ny) continue;
          for (int t = at(px, py) + 1; t <= j - 1; ++t) {
            const int32_t size = int32_t(1) << (levels - t + 1);
            const int32_t bx = px & ~(size - 1), by = py & ~(size - 1);
            for (int32_t v = by; v < by + size; ++v)
              for (int32_t u = bx; u < bx + size; ++u) at(u, v) = std::max<uint8_t>(at(u, v), uint8_t(t));
          }
        }
      }

  // The leaves, each from its top-left finest cell, as polygons on the lattice of the
  // finest cells' corners, numbered as first used.
  PolygonMesh mesh;
  std::vector<int32_t> vertex(size_t(nx + 1) * size_t(ny + 1), -1);
  const auto corner = [&](int32_t u, int32_t v) {
    int32_t& id = vertex[size_t(v) * size_t(nx + 1) + size_t(u)];
    if (id < 0) {
      id = mesh.num_vertices();
      mesh.positions.push_back({float(area.x + u * cell_x), float(area.y + v * cell_y), 0});
    }
    return id;
  };
  const auto finer = [&](int32_t x, int32_t y, int k) { return x >= 0 && y >= 0 && x < nx && y < ny && at(x, y) > k; };
  std::vector<int32_t> face;
  for (int32_t y = 0; y < ny; ++y)
    for (int32_t x = 0; x < nx; ++x) {
      const int k = at(x, y);
      const int32_t size = int32_t(1) << (levels - k), half = size / 2;
      if ((x & (size - 1)) != 0 || (y & (size - 1)) != 0) continue;
      face.clear();
      face.push_back(corner(x, y));
      if (finer(x, y - 1, k)) face.push_back(corner(x + half, y));
      face.push_back(corner(x + size, y));
      if (finer(x + size, y, k)) face.push_back(corner(x + size, y + half));
      face.push_back(corner(x + size, y + size));
      if (finer(x, y + size, k)) face.push_back(corner(x + half, y + size));
      face.push_back(corner(x, y + size));
      if (finer(x - 1, y, k)) face.push_back(corner(x, y + half));
      mesh.add_face(face);
    }
  return mesh;
}

double black_tone_cells(double area, const ToneOptions& options) {
  const double side = kPassesPerCell * options.spacing;
  return area / (side * side);
}

} // namespace meander
