#include "io/atomic_file.h"
#include "io/formats.h"
#include "io/image_codec.h"
#include "io/mapped_file.h"
#include "io/reader_support.h"
#include "meander/error.h"

#include <cctype>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace meander {

namespace io {

std::string lowercase_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

} // namespace io

MeshFormat mesh_format_from_path(const std::filesystem::path& path) {
  const std::string extension = io::lowercase_extension(path);
  if (extension == ".obj") return MeshFormat::obj;
  if (extension == ".ply") return MeshFormat::ply;
  if (extension == ".stl") return MeshFormat::stl;
  if (extension == ".off") return MeshFormat::off;
  if (extension == ".gltf" || extension == ".glb") return MeshFormat::gltf;
  if (extension == ".3mf") return MeshFormat::threemf;
  throw UsageError(path.string() + ": unknown mesh format '" + extension +
                   "' (Meander reads .obj, .ply, .stl, .off, .gltf and .glb, and writes those and .3mf)");
}

PolygonMesh read_mesh(const std::filesystem::path& path) {
  const MeshFormat format = mesh_format_from_path(path);
  const io::MappedFile file(path);
  return read_mesh(file.bytes(), format, path.string());
}

PolygonMesh read_mesh(std::string_view bytes, MeshFormat format, std::string_view name) {
  if (bytes.empty()) io::fail_input(name, "file is empty");
  switch (format) {
  case MeshFormat::obj: return io::read_obj(bytes, name);
  case MeshFormat::ply: return io::read_ply(bytes, name);
  case MeshFormat::stl: return io::read_stl(bytes, name);
  case MeshFormat::off: return io::read_off(bytes, name);
  case MeshFormat::gltf: return io::read_gltf(bytes, std::string(name)).mesh;
  case MeshFormat::threemf: break;
  }
  if (format == MeshFormat::threemf)
    throw UsageError(std::string(name) + ": reading .3mf is not supported (Meander writes 3MF only)");
  throw UsageError(std::string(name) + ": unknown mesh format");
}

TexturedMesh read_textured_mesh(const std::filesystem::path& path) {
  const MeshFormat format = mesh_format_from_path(path);
  if (format != MeshFormat::obj && format != MeshFormat::gltf) return {.mesh = read_mesh(path)};
  const io::MappedFile file(path);
  if (file.bytes().empty()) io::fail_input(path.string(), "file is empty");
  return format == MeshFormat::obj ? io::read_textured_obj(file.bytes(), path) : io::read_gltf(file.bytes(), path);
}

Texture read_texture(const std::filesystem::path& path, int64_t max_pixels) {
  const io::MappedFile file(path);
  if (file.bytes().empty()) io::fail_input(path.string(), "file is empty");
  return read_texture(file.bytes(), path.string(), max_pixels);
}

Texture read_texture(std::string_view bytes, std::string_view name, int64_t max_pixels) {
  return io::decode_image(bytes, name, max_pixels);
}

namespace {

// A textured mesh that is not an OBJ is a GLB.
void require_glb(const std::filesystem::path& path) {
  if (const std::string extension = io::lowercase_extension(path); extension != ".glb")
    throw UsageError(path.string() + ": unknown textured mesh format '" + extension + "' (expected .obj or .glb)");
}

} // namespace

void write_textured_mesh(const TexturedMesh& mesh, const std::filesystem::path& path, bool millimetres) {
  if (io::lowercase_extension(path) == ".obj") {
    std::vector<std::unique_ptr<io::AtomicFile>> files;
    io::write_textured_obj(mesh, path, [&files](const std::filesystem::path& file) -> io::Sink& {
      return *files.emplace_back(std::make_unique<io::AtomicFile>(file));
    });
    std::vector<io::AtomicFile*> all;
    for (const auto& file : files) all.push_back(file.get());
    io::AtomicFile::commit_all(all);
    return;
  }
  require_glb(path);
  check_appearance(mesh.mesh, mesh.appearance, path.string());
  io::AtomicFile out(path);
  io::write_textured_glb(mesh, millimetres, out);
  out.commit();
}

std::vector<NamedFile> textured_mesh_files(const TexturedMesh& mesh, const std::filesystem::path& name, bool millimetres) {
  std::vector<std::pair<std::filesystem::path, std::unique_ptr<io::MemorySink>>> sinks;
  const auto open = [&sinks](const std::filesystem::path& file) -> io::Sink& {
    return *sinks.emplace_back(file, std::make_unique<io::MemorySink>()).second;
  };
  if (io::lowercase_extension(name) == ".obj") {
    io::write_textured_obj(mesh, name, open);
  } else {
    require_glb(name);
    check_appearance(mesh.mesh, mesh.appearance, name.string());
    io::write_textured_glb(mesh, millimetres, open(name));
  }
  std::vector<NamedFile> files;
  for (auto& [file, sink] : sinks) files.push_back({file.filename().string(), sink->take()});
  return files;
}

Polylines read_polylines(const std::filesystem::path& path) {
  const std::string extension = io::lowercase_extension(path);
  if (extension != ".obj" && extension != ".ply")
    throw UsageError(path.string() + ": unknown curve format '" + extension + "' (expected .obj or .ply)");
  const io::MappedFile file(path);
  if (file.bytes().empty()) io::fail_input(path.string(), "file is empty");
  return extension == ".obj" ? io::read_obj_polylines(file.bytes(), path.string())
                             : io::read_ply_polylines(file.bytes(), path.string());
}

namespace {

// write_mesh's format, checks and bytes, into any sink.
void write_mesh_to(const PolygonMesh& mesh, const std::filesystem::path& path, const MeshWriteOptions& options,
                   const std::function<io::Sink&()>& open) {
  const MeshFormat format = mesh_format_from_path(path);
  if (format == MeshFormat::gltf && io::lowercase_extension(path) != ".glb")
    throw UsageError(path.string() + ": writing .gltf is not supported (write .glb: one binary file)");
  const std::span<const int32_t> groups = options.group_start;
  for (size_t k = 0; format == MeshFormat::obj && k < groups.size(); ++k)
    if (groups[k] < 0 || groups[k] > mesh.num_faces() || (k > 0 && groups[k] < groups[k - 1]))
      throw UsageError(path.string() + ": group_start must be non-decreasing face numbers in 0.." +
                       std::to_string(mesh.num_faces()));
  io::Sink& out = open();
  switch (format) {
  case MeshFormat::obj: io::write_obj(mesh, options, out); break;
  case MeshFormat::ply: io::write_ply(mesh, options, out); break;
  case MeshFormat::stl: io::write_stl(mesh, options, out); break;
  case MeshFormat::off: io::write_off(mesh, out); break;
  case MeshFormat::gltf: io::write_glb(mesh, options, out); break;
  case MeshFormat::threemf: io::write_3mf(mesh, path.string(), out); break;
  }
}

} // namespace

void write_mesh(const PolygonMesh& mesh, const std::filesystem::path& path, const MeshWriteOptions& options) {
  std::optional<io::AtomicFile> out;
  write_mesh_to(mesh, path, options, [&]() -> io::Sink& { return out.emplace(path); });
  out->commit();
}

std::string mesh_file_bytes(const PolygonMesh& mesh, const std::filesystem::path& name, const MeshWriteOptions& options) {
  io::MemorySink out;
  write_mesh_to(mesh, name, options, [&]() -> io::Sink& { return out; });
  return out.take();
}

void write_3mf_parts(std::span<const ColoredPart> parts, const std::filesystem::path& path) {
  if (mesh_format_from_path(path) != MeshFormat::threemf)
    throw UsageError(path.string() + ": a print in several filaments is written as .3mf");
  io::AtomicFile out(path);
  io::write_3mf_parts(parts, path.string(), out);
  out.commit();
}

std::string parts_3mf_bytes(std::span<const ColoredPart> parts, const std::filesystem::path& name) {
  io::MemorySink out;
  io::write_3mf_parts(parts, name.string(), out);
  return out.take();
}

void write_bytes(const std::filesystem::path& path, std::string_view bytes) {
  io::AtomicFile out(path);
  out.bytes(bytes.data(), bytes.size());
  out.commit();
}

} // namespace meander
