// Reading and writing meshes and curves. Formats are chosen by the file's extension
// (case-insensitive), then the content is checked to match it.
//
// Every refusal throws InputError (malformed content) or IOError (cannot open, read or
// write) whose message starts with the file's path as given and, where there is one, the
// line (text formats) or element (binary formats): "bunny.obj:1042: face references
// vertex 9001 but only 8000 exist", "mesh.ply: face 17: vertex index -3 out of range
// (0..7)", "mesh.ply: header: unknown format 'binary_middle_endian'". An unknown
// extension is a UsageError naming the path.
// Writers never leave a partial file: they write a temporary file beside the target and
// rename it into place only when everything was written; on failure a previous file of
// that name is left as it was. Output is deterministic (the same bytes for the same input).
#pragma once

#include "meander/mesh.h"

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace meander {

enum class MeshFormat { obj, ply, stl, off, threemf };

// The format for a path's extension; throws UsageError naming the path if unknown.
MeshFormat mesh_format_from_path(const std::filesystem::path& path);

// Reads a polygon mesh. OBJ: v and f (v, v/vt, v//vn, v/vt/vn, negative indices,
// positive indices pointing forward), polygons of any size, CRLF, UTF-8 BOM; comments,
// other statements and stray lines skipped.
// PLY: ascii, binary_little_endian, binary_big_endian; any scalar types; vertex x,y,z
// and face vertex_indices (or vertex_index) lists; other elements and properties skipped.
// STL: ascii (several solids allowed) and binary (told apart by the size, not by a
// "solid" header); vertices welded by exact position, numbered by first appearance.
// OFF: [ST][C][N]OFF header (4OFF, nOFF and binary OFF are refused), counts, vertices,
// faces; colours after a face's indices are ignored.
// Vertex coordinates must be finite; face indices must be in range; faces need at least
// 3 vertices; a file without faces is refused ("no faces"), and so is one whose counts
// claim more than its bytes hold (before anything is allocated for them). The mesh is
// returned as written in the file (no repair: see check.h). Linear time in the file
// size; the file is mapped, not copied.
PolygonMesh read_mesh(const std::filesystem::path& path);

// The same from bytes in memory; `name` stands for the file in messages.
PolygonMesh read_mesh(std::string_view bytes, MeshFormat format, std::string_view name);

// Reads closed polylines from the `l` elements of an OBJ file (v/vt indices, negative
// and forward indices as for faces). Each `l` is one closed loop: a last index equal to
// the first closes it and is not kept as a point. Faces and other statements are
// skipped. Refuses lines of fewer than 2 vertices and a file without `l` ("no
// polylines"); other extensions are a UsageError (PLY edges are not read yet).
Polylines read_polylines(const std::filesystem::path& path);

struct MeshWriteOptions {
  // PLY and STL are written in binary unless this is set.
  bool ascii = false;
  // Optional face ranges [group_start[k], group_start[k+1]) written as OBJ `o group_k`
  // lines (other formats ignore it; empty groups get no line). Entries must be
  // non-decreasing face numbers in 0..num_faces (else UsageError). Empty: no groups.
  std::span<const int32_t> group_start;
};

// Writes a polygon mesh: OBJ (v, f), PLY (vertex float x,y,z; face list uchar int, or
// uint int if a face has more than 255 vertices), STL (triangles with computed normals;
// polygons are fanned from their first vertex), OFF, 3MF (through lib3mf: one mesh object
// of the triangles fanned from each polygon's first vertex, triangles that repeat a vertex
// left out, coordinates rounded to 6 decimals, unit millimetre, one build item; 3MF is
// written only: reading it is a UsageError). Floats are written in text as the shortest
// decimal that reads back to the same float. Face indices must be in range.
// Atomic: no partial file is left.
void write_mesh(const PolygonMesh& mesh, const std::filesystem::path& path, const MeshWriteOptions& options = {});

// Writes closed polylines, format by extension:
//  .obj  v lines and one closed `l` element per polyline (the first index repeated at the end)
//  .ply  binary: vertex float x,y,z and edge int vertex1,vertex2 (closing edges included)
//  .json {"polylines": [{"closed": true, "points": [[x,y,z], ...]}, ...]}
//  .svg  orthographic projection onto the x-y plane (looking down -z), fitted to a page
//        of 1000 units on its longer side
// Points must be finite; an empty polyline gets no `l` element, edge or SVG path, and a
// one-point polyline no edge. Atomic: no partial file is left.
// Throws UsageError for any other extension.
void write_polylines(const Polylines& curves, const std::filesystem::path& path);

} // namespace meander
