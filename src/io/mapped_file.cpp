#include "io/mapped_file.h"

#include "meander/error.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace meander::io {
namespace {

// Closes a file descriptor on every way out of a scope.
struct FileDescriptor {
  int fd;
  ~FileDescriptor() { ::close(fd); }
};

[[noreturn]] void fail(const std::filesystem::path& path, std::string_view what, int error) {
  throw IOError(path.string() + ": " + std::string(what) + ": " + std::strerror(error));
}

} // namespace

MappedFile::MappedFile(const std::filesystem::path& path) {
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

MappedFile::~MappedFile() {
  if (size_ > 0) ::munmap(const_cast<char*>(data_), size_);
}

} // namespace meander::io
