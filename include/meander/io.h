// Reading and writing meshes and curves. Formats are chosen by the file's extension
// (case-insensitive), then the content is checked to match it.
//
// Every refusal throws InputError (malformed content) or IOError (cannot open, read or
// write) whose message starts with the file's path and, where there is one, the line
// (text formats) or element (binary formats): "bunny.obj:1042: face references vertex
// 9001 but only 8000 exist", "mesh.ply: face 17: vertex index -3 out of range".
// Writers never leave a partial file: they write a temporary file beside the target and
// rename it into place only when everything was written.
#pragma once

#include "meander/mesh.h"

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace meander {

enum class MeshFormat { obj, ply, stl, off };

// The format for a path's extension; throws UsageError naming the path if unknown.
MeshFormat mesh_format_from_path(const std::filesystem::path& path);

// Reads a polygon mesh. OBJ: v and f (v, v/vt, v//vn, v/vt/vn, negative indices),
// polygons of any size, CRLF, UTF-8 BOM, comments and other statements skipped.
// PLY: ascii, binary_little_endian, binary_big_endian; any scalar types; vertex x,y,z
// and face vertex_indices (or vertex_index) lists; other elements and properties skipped.
// STL: ascii and binary; vertices welded by exact position. OFF: OFF header,
// counts, vertices, faces. Vertex coordinates must be finite; face indices must be in
// range; faces need at least 3 vertices. The mesh is returned as written in the file
// (no repair: see check.h). Linear time in the file size.
PolygonMesh read_mesh(const std::filesystem::path& path);

// The same from bytes in memory; `name` stands for the file in messages.
PolygonMesh read_mesh(std::string_view bytes, MeshFormat format, std::string_view name);

struct MeshWriteOptions {
  // PLY and STL are written in binary unless this is set.
  bool ascii = false;
  // Optional face ranges [group_start[k], group_start[k+1]) written as OBJ `o` groups
  // (other formats ignore it). Empty: no groups.
  std::span<const int32_t> group_start;
};

// Writes a polygon mesh: OBJ (v, f), PLY (vertex float x,y,z; face list uchar int),
// STL (triangles; polygons are fan-triangulated), OFF. Atomic: no partial file is left.
void write_mesh(const PolygonMesh& mesh, const std::filesystem::path& path, const MeshWriteOptions& options = {});

// Writes closed polylines, format by extension:
//  .obj  v lines and one closed `l` element per polyline (the first index repeated at the end)
//  .ply  binary: vertex float x,y,z and edge int vertex1,vertex2 (closing edges included)
//  .json {"polylines": [{"closed": true, "points": [[x,y,z], ...]}, ...]}
//  .svg  orthographic projection onto the x-y plane (looking down -z), fitted to the page
// Atomic: no partial file is left. Throws UsageError for any other extension.
void write_polylines(const Polylines& curves, const std::filesystem::path& path);

} // namespace meander
