// What the mesh readers share: the wording of their messages and the checks every mesh
// passes on the way out, so that the four formats refuse the same things the same way.
#pragma once

#include "meander/mesh.h"

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>

namespace meander::io {

// Meander indexes vertices, faces and corners with int32.
inline constexpr int64_t max_count = std::numeric_limits<int32_t>::max();

// Throws InputError("name: message").
[[noreturn]] void fail_input(std::string_view name, std::string_view message);
// Throws NoPolylinesError "NAME: no polylines (WHAT)".
[[noreturn]] void fail_no_polylines(std::string_view name, std::string_view what);

// Throws InputError("name:line: message").
[[noreturn]] void fail_at_line(std::string_view name, int64_t line, std::string_view message);

// `text` in single quotes for a message, shortened, with control bytes shown as '?'.
std::string quoted(std::string_view text);

// "vertex index 9 out of range (0..7)".
std::string index_out_of_range(int64_t index, int64_t vertex_count);

// "non-finite vertex coordinate 'nan'" for a coordinate read from a binary file.
std::string non_finite_coordinate(double value);
// The same for the first non-finite coordinate of p.
std::string non_finite_coordinate(Vec3 p);

// "face with 2 vertices (at least 3 needed)".
std::string too_few_vertices(int64_t size);

// "too many vertices (3000000000; at most 2147483647)" if count > max_count, else empty.
std::string too_many(uint64_t count, std::string_view things);

// The index of the first position with a NaN or infinite coordinate, or -1.
int64_t first_non_finite(std::span<const Vec3> positions);

// The last check of every reader: refuses a mesh without faces ("name: no faces") and
// one with more corners than int32 indexes.
void require_faces(const PolygonMesh& mesh, std::string_view name);

} // namespace meander::io
