// 3MF through lib3mf 1.8 (Debian lib3mf-dev), whose API is the plain C interface of
// NMR_DLLInterfaces.h: every call returns an error code and objects are released by hand.
#include "io/formats.h"
#include "meander/error.h"

#include <Model/COM/NMR_DLLInterfaces.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace meander::io {
namespace {

// Owns one lib3mf object and releases it on every way out.
class Lib3mf {
public:
  Lib3mf() = default;
  ~Lib3mf() {
    if (handle_) NMR::lib3mf_release(handle_);
  }
  Lib3mf(const Lib3mf&) = delete;
  Lib3mf& operator=(const Lib3mf&) = delete;
  NMR::PLib3MFBase* get() const { return handle_; }
  NMR::PLib3MFBase** out() { return &handle_; }

private:
  NMR::PLib3MFBase* handle_ = nullptr;
};

// Throws IOError naming the file, the step and lib3mf's own message when `result` is an error.
void check(LIB3MFRESULT result, NMR::PLib3MFBase* about, std::string_view name, const char* step) {
  if (result == LIB3MF_OK) return;
  std::string message = "lib3mf error " + std::to_string(result);
  DWORD code = 0;
  LPCSTR text = nullptr;
  if (about && NMR::lib3mf_getlasterror(about, &code, &text) == LIB3MF_OK && text && *text) message = text;
  throw IOError(std::string(name) + ": cannot write 3MF (" + step + "): " + message);
}

// The ZIP that lib3mf writes goes back to patch headers, so it is assembled in memory
// (compressed, it is a fraction of the mesh) and then written to the sink.
struct SeekableBuffer {
  std::vector<char> bytes;
  size_t position = 0;
};

// The callbacks' types as lib3mf's CExportStream_Callback declares them (nfUint32,
// nfByte, nfUint64); 0 is success.
uint32_t write_chunk(unsigned char* data, uint32_t size, void* user) {
  auto& b = *static_cast<SeekableBuffer*>(user);
  if (b.position + size > b.bytes.size()) b.bytes.resize(b.position + size);
  std::memcpy(b.bytes.data() + b.position, data, size);
  b.position += size;
  return 0;
}

uint32_t seek_to(unsigned long long position, void* user) {
  auto& b = *static_cast<SeekableBuffer*>(user);
  if (position > b.bytes.size()) b.bytes.resize(size_t(position));
  b.position = size_t(position);
  return 0;
}

// lib3mf gives every object, build and item a random UUID; these are made from a hash
// of the mesh instead (a version-4 layout), so the same mesh gives the same bytes.
std::string content_uuid(const PolygonMesh& mesh, uint64_t salt) {
  uint64_t h = 0xcbf29ce484222325ull ^ salt; // FNV-1a
  const auto mix = [&h](const void* data, size_t size) {
    for (size_t i = 0; i < size; ++i) h = (h ^ static_cast<const unsigned char*>(data)[i]) * 0x100000001b3ull;
  };
  mix(mesh.positions.data(), mesh.positions.size() * sizeof(Vec3));
  mix(mesh.face_vertices.data(), mesh.face_vertices.size() * sizeof(int32_t));
  mix(mesh.face_start.data(), mesh.face_start.size() * sizeof(int32_t));
  const uint64_t low = h * 0x9E3779B97F4A7C15ull;
  char text[40];
  std::snprintf(text, sizeof text, "%08x-%04x-4%03x-8%03x-%012llx", unsigned(h >> 32), unsigned(h >> 16) & 0xffff,
                unsigned(h) & 0xfff, unsigned(low >> 52), (unsigned long long)(low & 0xffffffffffffull));
  return text;
}

} // namespace

void write_3mf(const PolygonMesh& mesh, std::string_view name, Sink& out) {
  std::vector<NMR::MODELMESHVERTEX> vertices(mesh.positions.size());
  for (size_t v = 0; v < vertices.size(); ++v)
    vertices[v] = {{mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z}};
  std::vector<NMR::MODELMESHTRIANGLE> triangles;
  triangles.reserve(size_t(std::max(0, mesh.num_corners() - 2 * mesh.num_faces())));
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const std::span<const int32_t> v = mesh.face(f);
    for (size_t k = 1; k + 1 < v.size(); ++k) {
      const NMR::MODELMESHTRIANGLE t{{DWORD(v[0]), DWORD(v[k]), DWORD(v[k + 1])}};
      // 3MF forbids a triangle that repeats a vertex; such a triangle has no area to lose.
      if (t.m_nIndices[0] != t.m_nIndices[1] && t.m_nIndices[1] != t.m_nIndices[2] && t.m_nIndices[2] != t.m_nIndices[0])
        triangles.push_back(t);
    }
  }

  Lib3mf model, object, item, writer;
  check(NMR::lib3mf_createmodel(model.out()), nullptr, name, "create model");
  check(NMR::lib3mf_model_setunit(model.get(), NMR::MODELUNIT_MILLIMETER), model.get(), name, "set unit");
  check(NMR::lib3mf_model_addmeshobject(model.get(), object.out()), model.get(), name, "add mesh object");
  check(NMR::lib3mf_object_setnameutf8(object.get(), "meander"), object.get(), name, "name object");
  check(NMR::lib3mf_object_setuuidutf8(object.get(), content_uuid(mesh, 1).c_str()), object.get(), name, "set UUID");
  check(NMR::lib3mf_meshobject_setgeometry(object.get(), vertices.data(), DWORD(vertices.size()),
                                           triangles.data(), DWORD(triangles.size())),
        object.get(), name, "set geometry");
  check(NMR::lib3mf_model_addbuilditem(model.get(), object.get(), nullptr, item.out()), model.get(), name,
        "add build item");
  check(NMR::lib3mf_builditem_setuuidutf8(item.get(), content_uuid(mesh, 2).c_str()), item.get(), name, "set UUID");
  check(NMR::lib3mf_model_setbuilduuidutf8(model.get(), content_uuid(mesh, 3).c_str()), model.get(), name,
        "set UUID");
  check(NMR::lib3mf_model_querywriter(model.get(), "3mf", writer.out()), model.get(), name, "query writer");
  SeekableBuffer buffer;
  check(NMR::lib3mf_writer_writetocallback(writer.get(), reinterpret_cast<void*>(&write_chunk),
                                          reinterpret_cast<void*>(&seek_to), &buffer),
        writer.get(), name, "write");
  out.bytes(buffer.bytes.data(), buffer.bytes.size());
}

} // namespace meander::io
