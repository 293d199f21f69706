// The textured quad the texture tests share: two triangles covering [-1,1]^2 in the
// z = 0 plane, facing +z, with a 2x2 checker of four distinct colours mapped once across
// it, so that each colour belongs to one quadrant of a picture taken from the front.
#pragma once

#include "meander/textured_mesh.h"

#include <array>
#include <cstdint>

namespace meander::test {

// Texel colours, rows top to bottom: red top left, green top right, blue bottom left,
// yellow bottom right.
inline constexpr std::array<std::array<uint8_t, 3>, 4> checker_colors{{{220, 30, 30}, {30, 200, 40}, {40, 60, 220}, {230, 210, 20}}};

inline TexturedMesh checker_quad() {
  TexturedMesh quad;
  quad.mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.mesh.add_face({0, 1, 2});
  quad.mesh.add_face({0, 2, 3});
  Material material{.name = "checker", .base_color = {1, 1, 1}, .texture = {.width = 2, .height = 2}};
  material.texture.rgba.assign(16, 255);
  for (size_t k = 0; k < 4; ++k)
    for (size_t j = 0; j < 3; ++j) material.texture.rgba[4 * k + j] = checker_colors[k][j];
  quad.appearance.materials.push_back(std::move(material));
  for (int32_t v : quad.mesh.face_vertices) {
    const Vec3 p = quad.mesh.positions[size_t(v)];
    quad.appearance.texcoords.push_back({(p.x + 1) / 2, (p.y + 1) / 2});
  }
  return quad;
}

} // namespace meander::test
