// Reading and writing meshes with their appearance (textured_mesh.h): OBJ with MTL and
// textures, and glTF. Refusals and atomic writes as in io.h.
#pragma once

#include "meander/textured_mesh.h"

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace meander {

// Reads a mesh with its appearance (textured_mesh.h):
//  .obj  as read_mesh, plus `vt` texture coordinates, `mtllib` (MTL files relative to the
//        OBJ's folder, read at that line) and `usemtl` (one material per face, several
//        per mesh). From the MTL: newmtl, Kd (linear base colour) and map_Kd (a texture
//        relative to the MTL's folder, options like -s skipped; PNG, JPEG, BMP, TGA...).
//        Without mtllib the appearance is empty (a plain mesh) and usemtl is ignored;
//        faces before the first usemtl get a light grey "default" material.
//  .gltf/.glb  every triangle primitive (triangles, strips, fans; points and lines are
//        skipped) of every mesh in the default scene (or scene 0), with the node
//        transforms applied (winding reversed under a mirroring transform); POSITION,
//        TEXCOORD_n for the base colour texture, baseColorFactor and baseColorTexture
//        (embedded in the GLB, data: URIs, or files beside a .gltf). Exactly equal
//        positions are welded into one vertex; texture coordinates stay per corner.
//  other mesh formats: as read_mesh, with an empty appearance.
// Refusals name the file and line that is wrong: "bunny.obj:3: mtllib 'x.mtl': x.mtl:
// cannot open: No such file or directory", "x.mtl:5: map_Kd 'tex.png': tex.png: cannot
// decode image: ...", "bunny.obj:7: usemtl 'red': no material of that name in the
// mtllib files", "bunny.obj:9: face references texture coordinate 12 but only 4 exist",
// "model.glb: <tinygltf's message>", "model.glb: mesh 0 primitive 1: POSITION: accessor 3
// reaches past the end of its buffer view". IOError for files that cannot be opened,
// InputError for malformed content.
TexturedMesh read_textured_mesh(const std::filesystem::path& path);

// Reads an image file as an RGBA8 texture: JPEG as libjpeg-turbo decodes it; PNG, BMP,
// TGA, GIF, ... as stb_image does. IOError if it cannot be opened, InputError("path:
// cannot decode image: ..."), as for an image of more than `max_pixels` pixels unless it
// is 0 (before they are decoded).
Texture read_texture(const std::filesystem::path& path, int64_t max_pixels = 0);

// The same from bytes in memory; `name` stands for the file in messages.
Texture read_texture(std::string_view bytes, std::string_view name, int64_t max_pixels = 0);

// Writes a mesh with its appearance (check_appearance must accept it, else UsageError):
//  .obj  OBJ with v, vt and f v/vt, `usemtl` before each run of faces of one material,
//        beside it NAME.mtl (newmtl, Kd, map_Kd) and the textures as PNG files
//        NAME_texture.png (NAME_texture_K.png for material K when several have one), all
//        referred to by relative paths. Without materials: the OBJ alone.
//  .glb  one binary glTF 2.0 file: vertices split where texture coordinates differ
//        (smooth normals kept across the seams), one primitive per used material, each
//        texture embedded as PNG; double-sided, non-metallic materials.
// Atomic as a whole: every file is written before any is renamed into place, and if a
// rename fails the files already renamed are removed. Other extensions: UsageError.
// `millimetres`: as MeshWriteOptions::millimetres.
void write_textured_mesh(const TexturedMesh& mesh, const std::filesystem::path& path, bool millimetres = false);

struct NamedFile {
  std::string name; // a file name, no folder
  std::string bytes;
};

// The files write_textured_mesh would write for `name` (the OBJ first, then its MTL and
// textures, or the one GLB), in memory, named as they would be: for a caller that sends
// them on rather than to disk. Throws what write_textured_mesh throws but IOError.
std::vector<NamedFile> textured_mesh_files(const TexturedMesh& mesh, const std::filesystem::path& name,
                                           bool millimetres = false);

// The files in one zip archive in memory, stored (not compressed; Zip64 where a file or
// the whole passes 4 GiB), through libzip: one download for a result of several files.
// The same bytes for the same files. Throws IOError if libzip fails.
std::string zip_archive(std::span<const NamedFile> files);

} // namespace meander
