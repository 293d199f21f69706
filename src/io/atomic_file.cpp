#include "io/atomic_file.h"

#include "meander/error.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace meander::io {
namespace {

// mkstemp makes a file only its owner may read; the target should get what any new
// file gets, 0666 minus the umask. Reading the umask means setting it (a race with
// other threads creating files), so it is read from /proc instead.
mode_t new_file_mode() {
  unsigned mask = 022;
  if (FILE* status = std::fopen("/proc/self/status", "r")) {
    char line[256];
    while (std::fgets(line, sizeof line, status))
      if (std::sscanf(line, "Umask: %o", &mask) == 1) break;
    std::fclose(status);
  }
  return mode_t(0666 & ~mask);
}

std::filesystem::path folder_of(const std::filesystem::path& target) {
  return target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
}

// Flushes a folder's entries (a rename into it) to the disk; 0 or the errno.
int sync_folder(const std::filesystem::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return errno;
  const int error = ::fsync(fd) == 0 ? 0 : errno;
  ::close(fd);
  // Some file systems cannot flush a folder; the rename is still made.
  return error == EINVAL ? 0 : error;
}

} // namespace

AtomicFile::AtomicFile(const std::filesystem::path& target) : target_(target) {
  std::string temp_name = target.filename().string();
  temp_name.insert(temp_name.begin(), '.');
  temp_name += ".tmp.XXXXXX";
  temp_ = (target.parent_path() / temp_name).string();
  fd_ = ::mkstemp(temp_.data());
  if (fd_ < 0) fail("cannot create file", errno);
  // Only cosmetic: a file left owner-only is still a correct output.
  ::fchmod(fd_, new_file_mode());
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) ::unlink(temp_.c_str());
}

void AtomicFile::write_at(const char* data, size_t size, uint64_t offset) {
  while (size > 0) {
    const ssize_t written = ::pwrite(fd_, data, size, off_t(offset));
    if (written < 0) {
      if (errno == EINTR) continue;
      fail("cannot write", errno);
    }
    data += written;
    size -= size_t(written);
    offset += uint64_t(written);
  }
}

void AtomicFile::close() {
  if (fd_ < 0) return;
  flush();
  if (::fsync(fd_) != 0) fail("cannot write", errno);
  const int closed = ::close(fd_);
  fd_ = -1;
  if (closed != 0) fail("cannot write", errno);
}

void AtomicFile::rename() {
  if (std::rename(temp_.c_str(), target_.c_str()) != 0) fail("cannot write", errno);
  committed_ = true;
}

void AtomicFile::commit() {
  close();
  rename();
  if (const int error = sync_folder(folder_of(target_))) fail("cannot write", error);
}

void AtomicFile::commit_all(std::span<AtomicFile* const> files) {
  for (AtomicFile* file : files) file->close();
  size_t renamed = 0;
  try {
    for (; renamed < files.size(); ++renamed) files[renamed]->rename();
  } catch (...) {
    for (size_t i = 0; i < renamed; ++i) ::unlink(files[i]->target_.c_str());
    throw;
  }
  std::vector<std::filesystem::path> folders;
  for (AtomicFile* file : files) folders.push_back(folder_of(file->target_));
  std::sort(folders.begin(), folders.end());
  folders.erase(std::unique(folders.begin(), folders.end()), folders.end());
  for (const auto& folder : folders)
    if (const int error = sync_folder(folder)) files.front()->fail("cannot write", error);
}

void AtomicFile::fail(std::string_view what, int error) const {
  throw IOError(target_.string() + ": " + std::string(what) + ": " + std::strerror(error));
}

} // namespace meander::io
