// 3MF through lib3mf 1.8 (Debian lib3mf-dev), whose API is the plain C interface of
// NMR_DLLInterfaces.h: every call returns an error code and objects are released by hand.
#include "io/formats.h"
#include "meander/error.h"

#include <Model/COM/NMR_DLLInterfaces.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <span>
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
// of the meshes instead (a version-4 layout), so the same meshes give the same bytes.
std::string content_uuid(std::span<const PolygonMesh* const> meshes, uint64_t salt) {
  uint64_t h = 0xcbf29ce484222325ull ^ salt; // FNV-1a
  const auto mix = [&h](const void* data, size_t size) {
    for (size_t i = 0; i < size; ++i) h = (h ^ static_cast<const unsigned char*>(data)[i]) * 0x100000001b3ull;
  };
  for (const PolygonMesh* mesh : meshes) {
    mix(mesh->positions.data(), mesh->positions.size() * sizeof(Vec3));
    mix(mesh->face_vertices.data(), mesh->face_vertices.size() * sizeof(int32_t));
    mix(mesh->face_start.data(), mesh->face_start.size() * sizeof(int32_t));
  }
  const uint64_t low = h * 0x9E3779B97F4A7C15ull;
  char text[40];
  std::snprintf(text, sizeof text, "%08x-%04x-4%03x-8%03x-%012llx", unsigned(h >> 32), unsigned(h >> 16) & 0xffff,
                unsigned(h) & 0xfff, unsigned(low >> 52), (unsigned long long)(low & 0xffffffffffffull));
  return text;
}

// Text for an XML attribute's value.
std::string xml_escaped(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
    case '&': out += "&amp;"; break;
    case '<': out += "&lt;"; break;
    case '>': out += "&gt;"; break;
    case '"': out += "&quot;"; break;
    default: out += c;
    }
  }
  return out;
}

// Appends the mesh's vertices and its polygons fanned from their first vertex.
void append_geometry(const PolygonMesh& mesh, std::vector<NMR::MODELMESHVERTEX>& vertices,
                     std::vector<NMR::MODELMESHTRIANGLE>& triangles) {
  const DWORD offset = DWORD(vertices.size());
  for (const Vec3 p : mesh.positions) vertices.push_back({{p.x, p.y, p.z}});
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const std::span<const int32_t> v = mesh.face(f);
    for (size_t k = 1; k + 1 < v.size(); ++k) {
      // 3MF forbids a triangle that repeats a vertex; such a triangle has no area to lose.
      if (v[0] == v[k] || v[k] == v[k + 1] || v[k + 1] == v[0]) continue;
      triangles.push_back({{offset + DWORD(v[0]), offset + DWORD(v[k]), offset + DWORD(v[k + 1])}});
    }
  }
}

// One mesh object of the meshes' triangles, one after another, in one build item.
// `parts`, if not empty, gives each mesh a base material (a colour): per triangle, as
// the 3MF materials extension says.
void write_model(std::span<const PolygonMesh* const> meshes, std::span<const ColoredPart> parts,
                 std::string_view name, Sink& out) {
  std::vector<NMR::MODELMESHVERTEX> vertices;
  std::vector<NMR::MODELMESHTRIANGLE> triangles;
  std::vector<DWORD> first{0}; // each mesh's first triangle
  for (const PolygonMesh* mesh : meshes) {
    append_geometry(*mesh, vertices, triangles);
    first.push_back(DWORD(triangles.size()));
  }
  Lib3mf model, object, item, writer;
  check(NMR::lib3mf_createmodel(model.out()), nullptr, name, "create model");
  check(NMR::lib3mf_model_setunit(model.get(), NMR::MODELUNIT_MILLIMETER), model.get(), name, "set unit");
  Lib3mf materials;
  DWORD group = 0;
  if (!parts.empty()) {
    check(NMR::lib3mf_model_addbasematerialgroup(model.get(), materials.out()), model.get(), name, "add materials");
    for (const ColoredPart& part : parts) {
      DWORD index = 0;
      check(NMR::lib3mf_basematerial_addmaterialutf8(materials.get(), part.name.c_str(), part.color[0], part.color[1],
                                                    part.color[2], &index),
            materials.get(), name, "add material");
      // Opaque: lib3mf leaves the alpha of a colour given as RGB at 0, which viewers show
      // as invisible.
      check(NMR::lib3mf_basematerial_setdisplaycolorrgba(materials.get(), index, part.color[0], part.color[1],
                                                        part.color[2], 255),
            materials.get(), name, "colour material");
    }
    check(NMR::lib3mf_basematerial_getresourceid(materials.get(), &group), materials.get(), name, "material group");
  }
  check(NMR::lib3mf_model_addmeshobject(model.get(), object.out()), model.get(), name, "add mesh object");
  check(NMR::lib3mf_object_setnameutf8(object.get(), "meander"), object.get(), name, "name object");
  check(NMR::lib3mf_object_setuuidutf8(object.get(), content_uuid(meshes, 1).c_str()), object.get(), name, "set UUID");
  check(NMR::lib3mf_meshobject_setgeometry(object.get(), vertices.data(), DWORD(vertices.size()),
                                           triangles.data(), DWORD(triangles.size())),
        object.get(), name, "set geometry");
  if (!parts.empty()) {
    std::vector<DWORD> groups(triangles.size(), group), indices(triangles.size());
    for (size_t k = 0; k + 1 < first.size(); ++k) std::fill(indices.begin() + first[k], indices.begin() + first[k + 1], DWORD(k));
    Lib3mf properties, defaults;
    check(NMR::lib3mf_meshobject_createpropertyhandler(object.get(), properties.out()), object.get(), name,
          "property handler");
    check(NMR::lib3mf_propertyhandler_setbasematerialarray(properties.get(), groups.data(), indices.data()),
          properties.get(), name, "set materials");
    check(NMR::lib3mf_object_createdefaultpropertyhandler(object.get(), defaults.out()), object.get(), name,
          "default property handler");
    check(NMR::lib3mf_defaultpropertyhandler_setbasematerial(defaults.get(), group, 0), defaults.get(), name,
          "set default material");
    // PrusaSlicer ignores 3MF materials and drops each object of a 3MF to its bed on its
    // own (which would take the pieces of a print apart); its own model configuration
    // makes one object of parts ("volumes": ranges of its triangles), each printed by an
    // extruder of its own.
    DWORD id = 0;
    check(NMR::lib3mf_resource_getresourceid(object.get(), &id), object.get(), name, "object id");
    std::string config = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<config>\n <object id=\"" + std::to_string(id) +
                         "\" instances_count=\"1\">\n  <metadata type=\"object\" key=\"name\" value=\"meander\"/>\n";
    for (size_t k = 0; k < parts.size(); ++k) {
      if (first[k] == first[k + 1]) continue;
      config += "  <volume firstid=\"" + std::to_string(first[k]) + "\" lastid=\"" + std::to_string(first[k + 1] - 1) +
                "\">\n   <metadata type=\"volume\" key=\"name\" value=\"" + xml_escaped(parts[k].name) +
                "\"/>\n   <metadata type=\"volume\" key=\"extruder\" value=\"" + std::to_string(k + 1) +
                "\"/>\n  </volume>\n";
    }
    config += " </object>\n</config>\n";
    Lib3mf attachment;
    char path[] = "/Metadata/Slic3r_PE_model.config";
    char relationship[] = "http://schemas.slic3r.org/3mf/2017/06/model-config";
    check(NMR::lib3mf_model_addattachmentutf8(model.get(), path, relationship, attachment.out()), model.get(), name,
          "add PrusaSlicer configuration");
    check(NMR::lib3mf_attachment_readfrombuffer(attachment.get(), reinterpret_cast<BYTE*>(config.data()), config.size()),
          attachment.get(), name, "write PrusaSlicer configuration");
  }
  check(NMR::lib3mf_model_addbuilditem(model.get(), object.get(), nullptr, item.out()), model.get(), name,
        "add build item");
  check(NMR::lib3mf_builditem_setuuidutf8(item.get(), content_uuid(meshes, 2).c_str()), item.get(), name, "set UUID");
  check(NMR::lib3mf_model_setbuilduuidutf8(model.get(), content_uuid(meshes, 3).c_str()), model.get(), name,
        "set UUID");
  check(NMR::lib3mf_model_querywriter(model.get(), "3mf", writer.out()), model.get(), name, "query writer");
  SeekableBuffer buffer;
  check(NMR::lib3mf_writer_writetocallback(writer.get(), reinterpret_cast<void*>(&write_chunk),
                                          reinterpret_cast<void*>(&seek_to), &buffer),
        writer.get(), name, "write");
  out.bytes(buffer.bytes.data(), buffer.bytes.size());
}

} // namespace

void write_3mf(const PolygonMesh& mesh, std::string_view name, Sink& out) {
  const PolygonMesh* meshes[] = {&mesh};
  write_model(meshes, {}, name, out);
}

void write_3mf_parts(std::span<const ColoredPart> parts, std::string_view name, Sink& out) {
  std::vector<const PolygonMesh*> meshes;
  for (const ColoredPart& part : parts) meshes.push_back(&part.mesh);
  write_model(meshes, parts, name, out);
}

} // namespace meander::io
