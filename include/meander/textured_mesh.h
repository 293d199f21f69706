// A polygon mesh with materials and texture coordinates: what OBJ + MTL and glTF carry,
// what the renderer paints, and what duotone surfaces are written as. PolygonMesh stays
// the plain geometry every other stage speaks; the appearance sits beside it in arrays
// indexed by the same face and corner handles.
#pragma once

#include "meander/mesh.h"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace meander {

// A point on a texture: u to the right, v up from the image's bottom row, 0..1 across
// the image and repeating outside it (OBJ's convention; glTF's v down is flipped on the
// way in and out).
struct TexCoord {
  float u = 0, v = 0;
  friend bool operator==(TexCoord, TexCoord) = default;
};

// An 8-bit RGBA image, rows top to bottom, 4 bytes per pixel, colour sRGB-encoded as
// image files store it.
struct Texture {
  int32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;
  bool empty() const { return rgba.empty(); }
};

// Linear-light RGB, each component 0..1 (glTF's baseColorFactor; MTL's Kd is read as
// the same, as Blender and three.js do).
using LinearRgb = std::array<float, 3>;

// A surface's colour is base_color times the texture's colour (decoded to linear light)
// at the point's texture coordinate, or base_color alone without a texture.
struct Material {
  std::string name;
  LinearRgb base_color{1, 1, 1};
  Texture texture; // empty: no texture
};

// How the faces of a mesh look. Empty `materials`: the mesh has none (a plain mesh).
struct Appearance {
  std::vector<Material> materials;
  // Per face, an index into materials; empty: every face uses materials[0].
  std::vector<int32_t> face_material;
  // Per corner, parallel to PolygonMesh::face_vertices (a vertex may get a different
  // coordinate in each face around it, as on a texture seam); empty when no face has
  // any. Required when a material has a texture.
  std::vector<TexCoord> texcoords;
};

struct TexturedMesh {
  PolygonMesh mesh;
  Appearance appearance;
};

// Throws UsageError("what: ...") if the appearance does not fit the mesh: face_material
// or texcoords of the wrong size, a material index out of range, a texture whose pixel
// count does not match its size, texture coordinates missing while a texture needs them,
// or non-finite colours or texture coordinates. Linear in the mesh size.
void check_appearance(const PolygonMesh& mesh, const Appearance& appearance, std::string_view what);

// The texture's colour at uv in linear light: the four nearest texels decoded from sRGB,
// then blended bilinearly, wrapping around at the borders (repeat). The texture must not
// be empty.
LinearRgb sample_texture(const Texture& texture, TexCoord uv);

} // namespace meander
