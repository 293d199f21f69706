// Reading and writing meshes and curves, and writing pictures (textured meshes:
// textured_io.h). Formats are chosen by the file's extension
// (case-insensitive), then the content is checked to match it.
//
// Every refusal throws InputError (malformed content) or IOError (cannot open, read or
// write) whose message starts with the file's path as given and, where there is one, the
// line (text formats) or element (binary formats): "bunny.obj:1042: face references
// vertex 9001 but only 8000 exist", "mesh.ply: face 17: vertex index -3 out of range
// (0..7)", "mesh.ply: header: unknown format 'binary_middle_endian'". An unknown
// extension is a UsageError naming the path.
// Writers never leave a partial file: they write a temporary file beside the target,
// flush it to the disk and rename it into place only when everything was written (then
// flush the folder), so even after a power cut the target is whole; on failure a previous
// file of that name is left as it was. The *_file_bytes functions give the same bytes in
// memory instead. Output is deterministic (the same bytes for the same input).
#pragma once

#include "meander/image.h"
#include "meander/mesh.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace meander {

// gltf is glTF 2.0 in either form: .gltf (JSON) or .glb (binary), told apart by content.
enum class MeshFormat { obj, ply, stl, off, gltf, threemf };

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
// glTF (.gltf, .glb): see read_textured_mesh; only the geometry is returned.
// Vertex coordinates must be finite; face indices must be in range; faces need at least
// 3 vertices; a file without faces is refused ("no faces"), and so is one whose counts
// claim more than its bytes hold (before anything is allocated for them). The mesh is
// returned as written in the file (no repair: see check.h). Linear time in the file
// size; the file is mapped, not copied.
PolygonMesh read_mesh(const std::filesystem::path& path);

// The same from bytes in memory; `name` stands for the file in messages.
PolygonMesh read_mesh(std::string_view bytes, MeshFormat format, std::string_view name);

// Reads polylines (closed loops and open polylines, see Polylines), format by extension:
//  .obj  `l` elements (v/vt indices, negative and forward indices as for faces); an `l`
//        whose last index equals its first is a closed loop (that point is not kept
//        twice), any other is open. Faces and other statements are skipped.
//  .ply  ascii or binary: vertex x,y,z and edge vertex1,vertex2 (any scalar types, as
//        write_polylines writes them), the edges chained into closed loops and open
//        chains, each starting at its first edge in the file, in that edge's direction;
//        vertices no edge uses are left out, faces and other elements skipped.
// What write_polylines writes reads back point for point. Refuses an `l` of fewer than
// 2 vertices, a file without `l` elements or edges ("no polylines"), an edge from a
// vertex to itself and a vertex where a third edge arrives ("mesh.ply: edge 7: vertex 4
// already joins edges 2 and 5 (a polyline does not branch)"); other extensions are a
// UsageError.
Polylines read_polylines(const std::filesystem::path& path);

struct MeshWriteOptions {
  // PLY and STL are written in binary unless this is set.
  bool ascii = false;
  // Optional face ranges [group_start[k], group_start[k+1]) written as OBJ `o group_k`
  // lines (other formats ignore it; empty groups get no line). Entries must be
  // non-decreasing face numbers in 0..num_faces (else UsageError). Empty: no groups.
  std::span<const int32_t> group_start;
  // GLB: also write area-weighted vertex normals, so that viewers shade the surface
  // smooth rather than faceted (other formats ignore it).
  bool normals = true;
  // The mesh is in millimetres (CurveJob::model_size): a GLB's node scales it by 1/1000,
  // as glTF's unit is the metre; other formats have no unit, 3MF's is the millimetre.
  bool millimetres = false;
};

// Writes a polygon mesh: OBJ (v, f), PLY (vertex float x,y,z; face list uchar int, or
// uint int if a face has more than 255 vertices), STL (triangles with computed normals;
// polygons are fanned from their first vertex), OFF, GLB (binary glTF 2.0: one mesh of
// triangles fanned from each polygon's first vertex, float positions with their min/max,
// optional normals, uint32 indices; valid for the Khronos glTF validator; .gltf is
// refused with a UsageError), 3MF (through lib3mf: one mesh object of the triangles
// fanned from each polygon's first vertex, triangles that repeat a vertex left out,
// coordinates rounded to 6 decimals, unit millimetre, one build item; 3MF is written
// only: reading it is a UsageError). Floats are written in text as the shortest decimal
// that reads back to the same float. Face indices must be in range. Atomic: no partial
// file is left.
void write_mesh(const PolygonMesh& mesh, const std::filesystem::path& path, const MeshWriteOptions& options = {});

// The bytes write_mesh would write to a file named `name` (format by its extension), in
// memory, for a caller that sends them on rather than to disk (the studio's downloads).
// Throws what write_mesh throws but IOError.
std::string mesh_file_bytes(const PolygonMesh& mesh, const std::filesystem::path& name, const MeshWriteOptions& options = {});

// One part of a print in several filaments: a closed solid, its name and its colour
// (sRGB).
struct ColoredPart {
  const PolygonMesh& mesh;
  std::string name;
  std::array<uint8_t, 3> color;
};

// Writes a 3MF (.3mf, else UsageError) that a slicer opens as one object printed in as
// many filaments as there are parts: one mesh object holding the parts' triangles (fanned
// as write_mesh fans them) part after part, in one build item, unit millimetre; each
// triangle with its part's base material (the 3MF materials extension: a group of one
// material per part, named and coloured as given), and PrusaSlicer's own model
// configuration (Metadata/Slic3r_PE_model.config): the object's parts as volumes,
// part k printed by extruder k + 1. PrusaSlicer ignores 3MF materials and drops each
// object of a 3MF onto its bed on its own, which would take the pieces apart (measured
// with PrusaSlicer 2.5: docs/printing.md). Atomic: no partial file is left.
void write_3mf_parts(std::span<const ColoredPart> parts, const std::filesystem::path& path);

// The bytes write_3mf_parts would write, in memory.
std::string parts_3mf_bytes(std::span<const ColoredPart> parts, const std::filesystem::path& name);

// Writes polylines, format by extension:
//  .obj  v lines and one `l` element per polyline (a closed one repeats its first index
//        at the end)
//  .ply  binary: vertex float x,y,z and edge int vertex1,vertex2 (closed polylines with
//        their closing edge)
//  .json {"polylines": [{"closed": true, "points": [[x,y,z], ...]}, ...]}
// Points must be finite; an empty polyline gets no `l` element or edge, and a one-point
// polyline no edge (and no `l` if open). Atomic: no partial file is left. Throws
// UsageError for any other extension: an SVG of curves is a drawing (drawing.h,
// curve_svg in jobs.h).
void write_polylines(const Polylines& curves, const std::filesystem::path& path);

// The bytes write_polylines would write to a file named `name`, in memory.
std::string polylines_file_bytes(const Polylines& curves, const std::filesystem::path& name);

// Writes bytes as the file `path`. Atomic: no partial file is left. Throws IOError.
void write_bytes(const std::filesystem::path& path, std::string_view bytes);

// Throws UsageError("path: unknown image format ...") unless the path ends in .png (any
// case): what write_png refuses, for callers that check before they render.
void require_png_path(const std::filesystem::path& path);

// Writes the image as PNG (RGB, or RGBA if it has alpha). Atomic: no partial file is
// left. Throws UsageError if the extension is not .png, IOError if it cannot be written.
void write_png(const Image& image, const std::filesystem::path& path);

// The bytes write_png would write, in memory.
std::string png_file_bytes(const Image& image);

} // namespace meander
