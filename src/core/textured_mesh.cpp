#include "meander/textured_mesh.h"

#include "meander/error.h"

#include <cmath>
#include <string>

namespace meander {
namespace {

// sRGB's exact transfer curve for the 256 byte values: textures are filtered in linear
// light, or a checker's edges would blur towards a too-dark colour.
struct SrgbTable {
  float value[256];
  SrgbTable() {
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      value[i] = float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
  }
};
const SrgbTable srgb_to_linear;

[[noreturn]] void refuse(std::string_view what, const std::string& message) {
  throw UsageError(std::string(what) + ": " + message);
}

} // namespace

void check_appearance(const PolygonMesh& mesh, const Appearance& a, std::string_view what) {
  if (a.materials.empty()) {
    if (!a.face_material.empty() || !a.texcoords.empty()) refuse(what, "face materials or texture coordinates without materials");
    return;
  }
  const int32_t count = int32_t(a.materials.size());
  if (!a.face_material.empty() && a.face_material.size() != size_t(mesh.num_faces()))
    refuse(what, std::to_string(a.face_material.size()) + " face materials for " + std::to_string(mesh.num_faces()) + " faces");
  for (size_t f = 0; f < a.face_material.size(); ++f)
    if (a.face_material[f] < 0 || a.face_material[f] >= count)
      refuse(what, "face " + std::to_string(f) + ": material " + std::to_string(a.face_material[f]) + " out of range (0.." +
                       std::to_string(count - 1) + ")");
  bool textured = false;
  for (const Material& m : a.materials) {
    for (float c : m.base_color)
      if (!std::isfinite(c)) refuse(what, "material '" + m.name + "': non-finite base colour");
    if (m.texture.empty()) continue;
    textured = true;
    if (m.texture.width < 1 || m.texture.height < 1 ||
        m.texture.rgba.size() != size_t(m.texture.width) * size_t(m.texture.height) * 4)
      refuse(what, "material '" + m.name + "': texture of " + std::to_string(m.texture.width) + "x" +
                       std::to_string(m.texture.height) + " pixels has " + std::to_string(m.texture.rgba.size()) + " bytes");
  }
  if (a.texcoords.empty()) {
    if (textured) refuse(what, "a material has a texture but the mesh has no texture coordinates");
    return;
  }
  if (a.texcoords.size() != mesh.face_vertices.size())
    refuse(what, std::to_string(a.texcoords.size()) + " texture coordinates for " + std::to_string(mesh.num_corners()) +
                     " face corners");
  for (size_t c = 0; c < a.texcoords.size(); ++c)
    if (!std::isfinite(a.texcoords[c].u) || !std::isfinite(a.texcoords[c].v))
      refuse(what, "corner " + std::to_string(c) + ": non-finite texture coordinate");
}

LinearRgb sample_texture(const Texture& t, TexCoord uv) {
  // Texel centres sit at half-integers; v counts up from the bottom row.
  const double x = double(uv.u) * t.width - 0.5, y = (1 - double(uv.v)) * t.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  auto wrap = [](double i, int32_t n) {
    const double r = std::fmod(i, double(n));
    return int32_t(r < 0 ? r + n : r);
  };
  const int32_t xs[2] = {wrap(x0, t.width), wrap(x0 + 1, t.width)};
  const int32_t ys[2] = {wrap(y0, t.height), wrap(y0 + 1, t.height)};
  LinearRgb out{0, 0, 0};
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const float w = float((i ? fx : 1 - fx) * (j ? fy : 1 - fy));
      const uint8_t* p = &t.rgba[(size_t(ys[j]) * t.width + xs[i]) * 4];
      for (int k = 0; k < 3; ++k) out[k] += w * srgb_to_linear.value[p[k]];
    }
  return out;
}

} // namespace meander
