#include "io/atomic_file.h"

#include "meander/error.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <condition_variable>
#include <cstring>
#include <fcntl.h>
#include <mutex>
#include <optional>
#include <sys/mman.h>
#include <sys/stat.h>
#include <system_error>
#include <thread>
#include <unistd.h>

namespace meander::io {
namespace {

constexpr size_t buffer_size = size_t(1) << 20;
constexpr uint64_t write_behind_step = uint64_t(16) << 20;
constexpr size_t write_behind_steps_cached = 8;
// fill() writes a region this large or larger direct.
constexpr uint64_t direct_region = uint64_t(16) << 20;

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

} // namespace

// The O_DIRECT writer of fill(): `buffers` page-aligned buffers that the caller fills and
// queues, and a thread that writes them in turn and gives them back.
struct AtomicFile::Direct {
  static constexpr uint64_t page = 4096; // alignment of an O_DIRECT write's offset, size and memory
  static constexpr size_t chunk = size_t(4) << 20;
  static constexpr int buffers = 4;
  struct Job {
    char* data;
    uint64_t at;
    size_t size;
  };

  int fd = -1;        // the file opened with O_DIRECT
  int cached_fd = -1; // AtomicFile's descriptor, for what O_DIRECT refuses
  char* memory = nullptr;
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<char*> idle;
  std::deque<Job> jobs;     // queued
  std::optional<Job> going; // being written
  bool stopping = false;
  int error = 0;
  bool refused = false; // the thread's alone: O_DIRECT refused a write, the page cache takes the rest
  std::thread thread;

  // Null where the file system refuses O_DIRECT or the buffers or the thread cannot be had.
  static std::unique_ptr<Direct> open(const std::string& path, int cached_fd) {
    auto d = std::make_unique<Direct>();
    d->cached_fd = cached_fd;
    d->fd = ::open(path.c_str(), O_WRONLY | O_DIRECT | O_CLOEXEC);
    if (d->fd < 0) return nullptr;
    void* memory = ::mmap(nullptr, chunk * buffers, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (memory == MAP_FAILED) return nullptr;
    d->memory = static_cast<char*>(memory);
    ::madvise(memory, chunk * buffers, MADV_HUGEPAGE); // advice only
    for (int i = 0; i < buffers; ++i) d->idle.push_back(d->memory + chunk * size_t(i));
    try {
      d->thread = std::thread([raw = d.get()] { raw->run(); });
    } catch (const std::system_error&) {
      return nullptr;
    }
    return d;
  }

  // Stops at once: what is still queued is dropped (the file is not kept, or was drained).
  ~Direct() {
    {
      std::lock_guard lock(mutex);
      stopping = true;
    }
    changed.notify_all();
    if (thread.joinable()) thread.join();
    if (fd >= 0) ::close(fd);
    if (memory) ::munmap(memory, chunk * buffers);
  }

  void run() {
    std::unique_lock lock(mutex);
    for (;;) {
      changed.wait(lock, [&] { return stopping || !jobs.empty(); });
      if (stopping) return;
      going = jobs.front();
      jobs.pop_front();
      const bool skip = error != 0;
      lock.unlock();
      const int failure = skip ? 0 : write(*going);
      lock.lock();
      idle.push_back(going->data);
      going.reset();
      if (failure != 0 && error == 0) error = failure;
      changed.notify_all();
    }
  }

  // 0, or the errno of the write that failed.
  int write(const Job& job) {
    for (size_t done = 0; done < job.size;) {
      const ssize_t n = ::pwrite(refused ? cached_fd : fd, job.data + done, job.size - done, off_t(job.at + done));
      if (n >= 0)
        done += size_t(n);
      else if (errno == EINVAL && !refused)
        refused = true; // an alignment this file system does not take, or a short write left one
      else if (errno != EINTR)
        return errno;
    }
    return 0;
  }

  // An idle buffer once one is, or null once a write failed (its errno in `failure`).
  char* take(int& failure) {
    std::unique_lock lock(mutex);
    changed.wait(lock, [&] { return !idle.empty() || error != 0; });
    failure = error;
    if (error != 0) return nullptr;
    char* data = idle.back();
    idle.pop_back();
    return data;
  }

  void queue(const Job& job) {
    {
      std::lock_guard lock(mutex);
      jobs.push_back(job);
    }
    changed.notify_all();
  }

  // Waits until no write queued or going overlaps the pages of [begin, end) (all of them
  // for the whole file); returns the errno of a write that failed, or 0.
  int settle(uint64_t begin, uint64_t end) {
    begin = begin / page * page;
    const auto overlaps = [&](const Job& j) { return j.at < end && begin < j.at + j.size; };
    std::unique_lock lock(mutex);
    changed.wait(lock, [&] {
      return error != 0 || ((!going || !overlaps(*going)) && std::none_of(jobs.begin(), jobs.end(), overlaps));
    });
    return error;
  }
};

AtomicFile::AtomicFile(const std::filesystem::path& target) : target_(target) {
  std::string temp_name = target.filename().string();
  temp_name.insert(temp_name.begin(), '.');
  temp_name += ".tmp.XXXXXX";
  temp_ = (target.parent_path() / temp_name).string();
  fd_ = ::mkstemp(temp_.data());
  if (fd_ < 0) fail("cannot create file", errno);
  // Only cosmetic: a file left owner-only is still a correct output.
  ::fchmod(fd_, new_file_mode());
  buffer_.resize(buffer_size);
}

AtomicFile::~AtomicFile() {
  direct_.reset(); // its thread writes to fd_
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) ::unlink(temp_.c_str());
}

void AtomicFile::real(float value) {
  constexpr size_t longest = 16; // "-1.17549435e-38"
  char* first = room(longest);
  used_ = size_t(std::to_chars(first, first + longest, value).ptr - buffer_.data());
}

void AtomicFile::fixed(double value, int decimals) {
  constexpr size_t longest = 400; // 309 integer digits of the largest double, the sign, decimals
  char* first = room(longest);
  used_ = size_t(std::to_chars(first, first + longest, value, std::chars_format::fixed, decimals).ptr - buffer_.data());
}

void AtomicFile::integer(int64_t value) {
  constexpr size_t longest = 20;
  char* first = room(longest);
  used_ = size_t(std::to_chars(first, first + longest, value).ptr - buffer_.data());
}

void AtomicFile::bytes(const void* data, size_t size) {
  if (size == 0) return; // data may be null then, which memcpy does not allow
  // A block as large as a quarter of the buffer is written as it is: copying it first
  // would cost a pass over it (2.4 GB for a 10M-triangle curve).
  if (buffer_.size() - used_ < size || size >= buffer_.size() / 4) {
    flush();
    if (size >= buffer_.size() / 4) {
      write_all(static_cast<const char*>(data), size);
      return;
    }
  }
  std::memcpy(buffer_.data() + used_, data, size);
  used_ += size;
}

void AtomicFile::flush() {
  write_all(buffer_.data(), used_);
  used_ = 0;
}

void AtomicFile::reserve(uint64_t end) {
  if (!reserving_ || end <= reserved_) return;
  constexpr uint64_t first_step = uint64_t(1) << 20, largest_step = uint64_t(64) << 20;
  const uint64_t step = std::clamp(reserved_, first_step, largest_step);
  const uint64_t to = std::max(end, std::min(reserved_ + step, expected_));
  // Not supported, or no room for a whole step: write() says whether the bytes fit.
  if (::fallocate(fd_, 0, off_t(reserved_), off_t(to - reserved_)) != 0) {
    reserving_ = false;
    return;
  }
  reserved_ = to;
}

void AtomicFile::expect_size(uint64_t size) {
  expected_ = size;
  reserve(size);
}

void AtomicFile::write_behind(uint64_t begin, uint64_t end) {
  if (!writing_behind_) return;
  if (begin != unsent_end_) unsent_begin_ = begin; // after a seek: an earlier run too short to send stays cached
  unsent_end_ = end;
  if (unsent_end_ - unsent_begin_ < write_behind_step) return;
  // Starts the writes without waiting for them; may wait while the disk's queue is full.
  if (::sync_file_range(fd_, off_t(unsent_begin_), off_t(unsent_end_ - unsent_begin_), SYNC_FILE_RANGE_WRITE) != 0) {
    if (errno == EIO || errno == ENOSPC) fail("cannot write", errno);
    writing_behind_ = false; // not supported here: the page cache keeps everything
    return;
  }
  sent_.emplace_back(unsent_begin_, unsent_end_);
  unsent_begin_ = unsent_end_;
  if (sent_.size() > write_behind_steps_cached) {
    // Drops the pages written out; those still dirty or being written stay.
    const auto [from, to] = sent_.front();
    sent_.pop_front();
    ::posix_fadvise(fd_, off_t(from), off_t(to - from), POSIX_FADV_DONTNEED);
  }
}

void AtomicFile::write_all(const char* data, size_t size) {
  reserve(offset_ + size);
  write_cached(data, size, offset_);
  offset_ += size;
  written_ = std::max(written_, offset_);
}

void AtomicFile::write_cached(const char* data, size_t size, uint64_t at) {
  if (size == 0) return;
  if (direct_)
    if (const int error = direct_->settle(at, at + size)) fail("cannot write", error);
  const uint64_t begin = at;
  while (size > 0) {
    const ssize_t written = ::pwrite(fd_, data, size, off_t(at));
    if (written < 0) {
      if (errno == EINTR) continue;
      fail("cannot write", errno);
    }
    data += written;
    size -= size_t(written);
    at += uint64_t(written);
  }
  write_behind(begin, at);
}

void AtomicFile::fill(uint64_t size, const Fill& make) {
  flush();
  const uint64_t begin = offset_, end = offset_ + size;
  reserve(end);
  if (size >= direct_region && !direct_tried_) {
    direct_tried_ = true;
    direct_ = Direct::open(temp_, fd_);
  }
  uint64_t at = begin;
  // Up to `to` through the buffer and the page cache.
  const auto cached = [&](uint64_t to) {
    for (size_t n; at < to; at += n) {
      n = size_t(std::min<uint64_t>(to - at, buffer_.size()));
      make(at - begin, n, buffer_.data());
      write_cached(buffer_.data(), n, at);
    }
  };
  if (direct_ && size >= direct_region) {
    constexpr uint64_t page = Direct::page;
    const uint64_t last = end / page * page;
    cached((begin + page - 1) / page * page);
    while (at < last) {
      const size_t n = size_t(std::min<uint64_t>(last - at, Direct::chunk));
      int failure = 0;
      char* buffer = direct_->take(failure);
      if (failure != 0) fail("cannot write", failure);
      make(at - begin, n, buffer);
      direct_->queue({buffer, at, n});
      at += n;
    }
  }
  cached(end);
  offset_ = end;
  written_ = std::max(written_, end);
}

uint64_t AtomicFile::position() {
  flush();
  return offset_;
}

void AtomicFile::seek(uint64_t offset) {
  flush();
  offset_ = offset;
}

void AtomicFile::close() {
  if (fd_ < 0) return;
  flush();
  if (direct_) {
    if (const int error = direct_->settle(0, UINT64_MAX)) fail("cannot write", error);
    direct_.reset();
  }
  if (reserved_ > written_ && ::ftruncate(fd_, off_t(written_)) != 0) fail("cannot write", errno);
  const int closed = ::close(fd_);
  fd_ = -1;
  if (closed != 0) fail("cannot write", errno);
}

void AtomicFile::commit() {
  close();
  if (std::rename(temp_.c_str(), target_.c_str()) != 0) fail("cannot write", errno);
  committed_ = true;
}

void AtomicFile::commit_all(std::span<AtomicFile* const> files) {
  for (AtomicFile* file : files) file->close();
  size_t renamed = 0;
  try {
    for (; renamed < files.size(); ++renamed) files[renamed]->commit();
  } catch (...) {
    for (size_t i = 0; i < renamed; ++i) ::unlink(files[i]->target_.c_str());
    throw;
  }
}

void AtomicFile::fail(std::string_view what, int error) const {
  throw IOError(target_.string() + ": " + std::string(what) + ": " + std::strerror(error));
}

} // namespace meander::io
