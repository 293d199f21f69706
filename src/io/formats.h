// The readers and writers of each mesh format, behind read_mesh and write_mesh
// (mesh_io.cpp), which pick one by the file's extension. Readers take the whole file
// in memory; `name` stands for the file in messages. See meander/io.h for the contract.
#pragma once

#include "io/sink.h"
#include "meander/io.h"
#include "meander/textured_io.h"

#include <functional>
#include <span>
#include <string>
#include <string_view>

namespace meander::io {

// The extension of `path` in lower case, with its dot: ".obj".
std::string lowercase_extension(const std::filesystem::path& path);

PolygonMesh read_obj(std::string_view bytes, std::string_view name);
PolygonMesh read_ply(std::string_view bytes, std::string_view name);
PolygonMesh read_stl(std::string_view bytes, std::string_view name);
PolygonMesh read_off(std::string_view bytes, std::string_view name);
Polylines read_obj_polylines(std::string_view bytes, std::string_view name);
Polylines read_ply_polylines(std::string_view bytes, std::string_view name);

// Chains edges (2 vertex ids each, in range) into polylines: closed loops and open
// chains, each starting at its first edge in file order, in that edge's direction.
// Vertices no edge uses are left out. Refuses an edge from a vertex to itself, a
// vertex where a third edge arrives (naming that edge) and no edges at all.
Polylines chain_edges(std::span<const Vec3> positions, std::span<const int32_t> edges, std::string_view name);

// Textured formats: `path` names the file in messages and is where the files it refers
// to (MTL, textures, glTF buffers and images) are found or written beside.
TexturedMesh read_textured_obj(std::string_view bytes, const std::filesystem::path& path);
TexturedMesh read_gltf(std::string_view bytes, const std::filesystem::path& path);
// The OBJ, then its MTL and textures, each into the sink open(its path) gives.
void write_textured_obj(const TexturedMesh& mesh, const std::filesystem::path& path,
                        const std::function<Sink&(const std::filesystem::path&)>& open);
void write_glb(const PolygonMesh& mesh, const MeshWriteOptions& options, Sink& out);
void write_textured_glb(const TexturedMesh& mesh, bool millimetres, Sink& out);

void write_obj(const PolygonMesh& mesh, const MeshWriteOptions& options, Sink& out);
void write_ply(const PolygonMesh& mesh, const MeshWriteOptions& options, Sink& out);
void write_stl(const PolygonMesh& mesh, const MeshWriteOptions& options, Sink& out);
void write_off(const PolygonMesh& mesh, Sink& out);
// `name` stands for the file in lib3mf's error messages. Coordinates are rounded to 6
// decimals (lib3mf's format: a micrometre, the unit being the millimetre).
void write_3mf(const PolygonMesh& mesh, std::string_view name, Sink& out);
void write_3mf_parts(std::span<const ColoredPart> parts, std::string_view name, Sink& out);

// "x y z\n": a point as OBJ, OFF and ascii PLY write it.
inline void write_point_line(Sink& out, Vec3 p) {
  out.real(p.x);
  out.put(' ');
  out.real(p.y);
  out.put(' ');
  out.real(p.z);
  out.put('\n');
}

// Points as little-endian float x, y, z (binary PLY).
inline void write_binary_points(Sink& out, std::span<const Vec3> points) {
  static_assert(sizeof(Vec3) == 3 * sizeof(float));
  if constexpr (host_is_little_endian) {
    out.bytes(points.data(), points.size_bytes());
  } else {
    for (const Vec3& p : points) {
      out.little_endian(p.x);
      out.little_endian(p.y);
      out.little_endian(p.z);
    }
  }
}

// "n i0 ... i(n-1)\n": a face as OFF and ascii PLY write it.
inline void write_counted_indices(Sink& out, std::span<const int32_t> face) {
  out.integer(int64_t(face.size()));
  for (int32_t v : face) {
    out.put(' ');
    out.integer(v);
  }
  out.put('\n');
}

} // namespace meander::io
