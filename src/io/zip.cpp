#include "meander/textured_io.h"

#include "meander/error.h"

#include <zip.h>

#include <memory>

namespace meander {

namespace {

struct SourceFree {
  void operator()(zip_source_t* source) const { zip_source_free(source); }
};
struct ArchiveDiscard {
  void operator()(zip_t* archive) const { zip_discard(archive); }
};

[[noreturn]] void fail(const std::string& what, zip_error_t* error) {
  throw IOError("zip archive: " + what + ": " + zip_error_strerror(error));
}

} // namespace

std::string zip_archive(std::span<const NamedFile> entries) {
  struct ErrorScope {
    zip_error_t error;
    ErrorScope() { zip_error_init(&error); }
    ~ErrorScope() { zip_error_fini(&error); }
  } opening;
  // The archive is written into this growing buffer, kept past zip_close to be read back.
  std::unique_ptr<zip_source_t, SourceFree> buffer(zip_source_buffer_create(nullptr, 0, 0, &opening.error));
  if (!buffer) fail("buffer", &opening.error);
  zip_source_keep(buffer.get());
  std::unique_ptr<zip_t, ArchiveDiscard> archive(zip_open_from_source(buffer.get(), ZIP_TRUNCATE, &opening.error));
  if (!archive) {
    zip_source_free(buffer.get()); // the reference zip_open_from_source did not take
    fail("open", &opening.error);
  }
  for (const NamedFile& e : entries) {
    // Read at zip_close, while the entries are still alive.
    zip_source_t* source = zip_source_buffer(archive.get(), e.bytes.data(), e.bytes.size(), 0);
    const zip_int64_t index = source ? zip_file_add(archive.get(), e.name.c_str(), source, ZIP_FL_ENC_UTF_8) : -1;
    if (index < 0) {
      if (source) zip_source_free(source);
      fail(e.name, zip_get_error(archive.get()));
    }
    // Stored, so the files read as they are; a fixed date (1980-01-01, as the DOS time and
    // date fields, not through the local time zone) keeps the same bytes for the same files.
    if (zip_set_file_compression(archive.get(), zip_uint64_t(index), ZIP_CM_STORE, 0) < 0 ||
        zip_file_set_dostime(archive.get(), zip_uint64_t(index), 0, 0x21, 0) < 0)
      fail(e.name, zip_get_error(archive.get()));
  }
  if (zip_close(archive.get()) < 0) fail("write", zip_get_error(archive.get()));
  archive.release(); // zip_close freed it
  // libzip writes nothing for an archive without entries; every reader takes this one.
  if (zip_source_is_deleted(buffer.get())) return std::string("PK\5\6", 4) + std::string(18, '\0');

  zip_stat_t stat;
  if (zip_source_stat(buffer.get(), &stat) < 0 || zip_source_open(buffer.get()) < 0)
    fail("read", zip_source_error(buffer.get()));
  std::string out(stat.size, '\0');
  const zip_int64_t read = zip_source_read(buffer.get(), out.data(), out.size());
  zip_source_close(buffer.get());
  if (read != zip_int64_t(out.size())) fail("read", zip_source_error(buffer.get()));
  return out;
}

} // namespace meander
