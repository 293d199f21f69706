#include "io/reader_support.h"

#include "meander/error.h"

#include <bit>
#include <charconv>

namespace meander::io {

void fail_input(std::string_view name, std::string_view message) {
  throw InputError(std::string(name) + ": " + std::string(message));
}

void fail_no_polylines(std::string_view name, std::string_view what) {
  throw NoPolylinesError(std::string(name) + ": no polylines (" + std::string(what) + ")");
}

void fail_at_line(std::string_view name, int64_t line, std::string_view message) {
  throw InputError(std::string(name) + ":" + std::to_string(line) + ": " + std::string(message));
}

std::string quoted(std::string_view text) {
  constexpr size_t longest = 40;
  std::string out = "'";
  for (char c : text.substr(0, longest)) out += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? '?' : c;
  if (text.size() > longest) out += "...";
  return out + "'";
}

std::string index_out_of_range(int64_t index, int64_t vertex_count) {
  const std::string range = vertex_count == 0 ? "there are no vertices" : "0.." + std::to_string(vertex_count - 1);
  return "vertex index " + std::to_string(index) + " out of range (" + range + ")";
}

std::string non_finite_coordinate(double value) {
  char text[32];
  const char* end = std::to_chars(text, text + sizeof text, value).ptr;
  return "non-finite vertex coordinate " + quoted({text, size_t(end - text)});
}

std::string non_finite_coordinate(Vec3 p) {
  return non_finite_coordinate(!std::isfinite(p.x) ? p.x : !std::isfinite(p.y) ? p.y : p.z);
}

std::string too_few_vertices(int64_t size) {
  return "face with " + std::to_string(size) + " vertices (at least 3 needed)";
}

std::string too_many(uint64_t count, std::string_view things) {
  if (count <= uint64_t(max_count)) return {};
  return "too many " + std::string(things) + " (" + std::to_string(count) + "; at most " + std::to_string(max_count) +
         ")";
}

int64_t first_non_finite(std::span<const Vec3> positions) {
  // Exponent bits all set means inf or NaN; a branch-free test the compiler vectorizes.
  const auto bad = [](float v) { return (std::bit_cast<uint32_t>(v) & 0x7f800000u) == 0x7f800000u; };
  bool any = false;
  for (const Vec3& p : positions) any |= bad(p.x) | bad(p.y) | bad(p.z);
  if (!any) return -1;
  for (size_t i = 0; i < positions.size(); ++i)
    if (!is_finite(positions[i])) return int64_t(i);
  return -1;
}

void require_faces(const PolygonMesh& mesh, std::string_view name) {
  if (mesh.face_start.size() < 2) fail_input(name, "no faces");
  if (const std::string message = too_many(mesh.face_vertices.size(), "face corners"); !message.empty())
    fail_input(name, message);
}

} // namespace meander::io
