#include "io/formats.h"
#include "io/reader_support.h"
#include "meander/error.h"

#include <cctype>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace meander {
namespace {

// Closes a file descriptor on every way out of a scope.
struct FileDescriptor {
  int fd;
  ~FileDescriptor() { ::close(fd); }
};

// A file's bytes mapped read-only: the parsers read them in place, with no copy.
class MappedFile {
public:
  explicit MappedFile(const std::filesystem::path& path) {
    const FileDescriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
    if (file.fd < 0) fail(path, "cannot open", errno);
    struct stat info {};
    if (::fstat(file.fd, &info) != 0) fail(path, "cannot read", errno);
    if (S_ISDIR(info.st_mode)) throw IOError(path.string() + ": is a directory");
    if (!S_ISREG(info.st_mode)) throw IOError(path.string() + ": not a regular file");
    if (info.st_size == 0) return;
    // MAP_POPULATE reads the whole file in one go instead of faulting page by page.
    void* data = ::mmap(nullptr, size_t(info.st_size), PROT_READ, MAP_PRIVATE | MAP_POPULATE, file.fd, 0);
    if (data == MAP_FAILED) fail(path, "cannot read", errno);
    data_ = static_cast<const char*>(data);
    size_ = size_t(info.st_size);
  }
  ~MappedFile() {
    if (size_ > 0) ::munmap(const_cast<char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::string_view bytes() const { return {data_, size_}; }

private:
  [[noreturn]] static void fail(const std::filesystem::path& path, std::string_view what, int error) {
    throw IOError(path.string() + ": " + std::string(what) + ": " + std::strerror(error));
  }

  const char* data_ = "";
  size_t size_ = 0;
};

} // namespace

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
  if (extension == ".3mf") return MeshFormat::threemf;
  throw UsageError(path.string() + ": unknown mesh format '" + extension +
                   "' (expected .obj, .ply, .stl, .off or .3mf)");
}

PolygonMesh read_mesh(const std::filesystem::path& path) {
  const MeshFormat format = mesh_format_from_path(path);
  const MappedFile file(path);
  return read_mesh(file.bytes(), format, path.string());
}

PolygonMesh read_mesh(std::string_view bytes, MeshFormat format, std::string_view name) {
  if (bytes.empty()) io::fail_input(name, "file is empty");
  switch (format) {
  case MeshFormat::obj: return io::read_obj(bytes, name);
  case MeshFormat::ply: return io::read_ply(bytes, name);
  case MeshFormat::stl: return io::read_stl(bytes, name);
  case MeshFormat::off: return io::read_off(bytes, name);
  case MeshFormat::threemf: break;
  }
  if (format == MeshFormat::threemf)
    throw UsageError(std::string(name) + ": reading .3mf is not supported (Meander writes 3MF only)");
  throw UsageError(std::string(name) + ": unknown mesh format");
}

Polylines read_polylines(const std::filesystem::path& path) {
  const std::string extension = io::lowercase_extension(path);
  if (extension != ".obj" && extension != ".ply")
    throw UsageError(path.string() + ": unknown curve format '" + extension + "' (expected .obj or .ply)");
  const MappedFile file(path);
  if (file.bytes().empty()) io::fail_input(path.string(), "file is empty");
  return extension == ".obj" ? io::read_obj_polylines(file.bytes(), path.string())
                             : io::read_ply_polylines(file.bytes(), path.string());
}

void write_mesh(const PolygonMesh& mesh, const std::filesystem::path& path, const MeshWriteOptions& options) {
  const MeshFormat format = mesh_format_from_path(path);
  const std::span<const int32_t> groups = options.group_start;
  for (size_t k = 0; format == MeshFormat::obj && k < groups.size(); ++k)
    if (groups[k] < 0 || groups[k] > mesh.num_faces() || (k > 0 && groups[k] < groups[k - 1]))
      throw UsageError(path.string() + ": group_start must be non-decreasing face numbers in 0.." +
                       std::to_string(mesh.num_faces()));
  io::AtomicFile out(path);
  switch (format) {
  case MeshFormat::obj: io::write_obj(mesh, options, out); break;
  case MeshFormat::ply: io::write_ply(mesh, options, out); break;
  case MeshFormat::stl: io::write_stl(mesh, options, out); break;
  case MeshFormat::off: io::write_off(mesh, out); break;
  case MeshFormat::threemf: io::write_3mf(mesh, path.string(), out); break;
  }
  out.commit();
}

} // namespace meander
