// glTF 2.0: reading .gltf and .glb through tinygltf, writing .glb by hand (the layout is
// small, and writing it ourselves keeps the bytes deterministic and the file valid for
// the Khronos validator: 4-byte aligned views, exact accessor bounds).
#include "io/formats.h"
#include "io/image_codec.h"
#include "io/reader_support.h"
#include "io/welder.h"
#include "meander/error.h"

#include <nlohmann/json.hpp>

// Images are decoded by Meander's own loader (image_decode.cpp owns stb_image), and
// tinygltf writes nothing.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <new>
#include <optional>
#include <unordered_map>

namespace meander::io {
namespace {

namespace fs = std::filesystem;
using Matrix = std::array<double, 16>; // column-major, as glTF stores it

constexpr Matrix identity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
constexpr LinearRgb default_grey{0.604f, 0.604f, 0.604f}; // sRGB 0.8, the renderer's plain grey

Matrix multiply(const Matrix& a, const Matrix& b) {
  Matrix c{};
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row)
      for (int k = 0; k < 4; ++k) c[col * 4 + row] += a[k * 4 + row] * b[col * 4 + k];
  return c;
}

Matrix local_matrix(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    Matrix m;
    std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
    return m;
  }
  // T * R * S.
  Matrix m = identity;
  if (node.scale.size() == 3)
    for (int i = 0; i < 3; ++i)
      for (int row = 0; row < 3; ++row) m[i * 4 + row] *= node.scale[i];
  if (node.rotation.size() == 4) {
    const double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
    const Matrix r{1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),     0,
                   2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),     0,
                   2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y), 0,
                   0,                       0,                       0,                       1};
    m = multiply(r, m);
  }
  if (node.translation.size() == 3)
    for (int i = 0; i < 3; ++i) m[12 + i] += node.translation[i];
  return m;
}

double determinant3(const Matrix& m) {
  return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) + m[8] * (m[1] * m[6] - m[5] * m[2]);
}

// One accessor's elements, read with every check that a file can break.
class AccessorReader {
public:
  AccessorReader(const tinygltf::Model& model, int index, const std::string& where) : where_(where) {
    if (index < 0 || size_t(index) >= model.accessors.size()) fail("accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& a = model.accessors[size_t(index)];
    where_ += ": accessor " + std::to_string(index);
    if (a.sparse.isSparse) fail("sparse accessors are not supported");
    if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size())
      fail("has no buffer view (accessors of zeros are not supported)");
    const tinygltf::BufferView& view = model.bufferViews[size_t(a.bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) fail("its buffer view has no buffer");
    const std::vector<unsigned char>& buffer = model.buffers[size_t(view.buffer)].data;
    components_ = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    component_size_ = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    if (components_ < 1 || component_size_ < 1) fail("unknown type or component type");
    type_ = a.componentType;
    normalized_ = a.normalized;
    count_ = a.count;
    const size_t element = size_t(components_) * size_t(component_size_);
    stride_ = view.byteStride != 0 ? view.byteStride : element;
    const size_t start = view.byteOffset + a.byteOffset;
    const size_t view_end = view.byteOffset + view.byteLength;
    if (view_end > buffer.size() || view_end < view.byteOffset) fail("its buffer view reaches past the end of its buffer");
    if (count_ > 0 && (start > view_end || view_end - start < element || (view_end - start - element) / stride_ < count_ - 1))
      fail("reaches past the end of its buffer view");
    data_ = buffer.data() + start;
  }

  size_t count() const { return count_; }
  int components() const { return components_; }

  // Requires `components` per element and one of the component types.
  void require(int components, std::initializer_list<int> types, std::string_view what) const {
    if (components_ != components || std::find(types.begin(), types.end(), type_) == types.end())
      fail("expected " + std::string(what));
  }

  // Component k of element i, integers scaled to 0..1 when normalized.
  double value(size_t i, int k) const {
    const unsigned char* p = data_ + i * stride_ + size_t(k) * size_t(component_size_);
    switch (type_) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized_ ? *p / 255.0 : *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return normalized_ ? load<uint16_t>(p) / 65535.0 : load<uint16_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load<uint32_t>(p);
    case TINYGLTF_COMPONENT_TYPE_BYTE: return normalized_ ? std::max(load<int8_t>(p) / 127.0, -1.0) : load<int8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return normalized_ ? std::max(load<int16_t>(p) / 32767.0, -1.0) : load<int16_t>(p);
    default: return load<double>(p);
    }
  }

  [[noreturn]] void fail(const std::string& message) const { throw InputError(where_ + ": " + message); }

private:
  template <class T> static T load(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof value); // glTF is little-endian, as every host Meander runs on
    return value;
  }

  std::string where_;
  const unsigned char* data_ = nullptr;
  size_t count_ = 0, stride_ = 0;
  int components_ = 0, component_size_ = 0, type_ = 0;
  bool normalized_ = false;
};

// The file reader tinygltf calls for a buffer or an image given by a relative URI. Its
// own opens a folder as a stream and takes the stream's failed position for a size of
// 2^63 bytes; this one reads regular files only.
bool read_external_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  std::error_code ec;
  const bool regular = fs::is_regular_file(path, ec);
  const uintmax_t size = regular ? fs::file_size(path, ec) : 0;
  std::ifstream in;
  if (regular && !ec) in.open(path, std::ios::binary);
  if (!in.is_open()) {
    if (err) *err += regular ? "cannot open it" : "not a regular file";
    return false;
  }
  out->resize(size_t(size));
  if (!in.read(reinterpret_cast<char*>(out->data()), std::streamsize(size))) {
    if (err) *err += "cannot read it";
    return false;
  }
  return true;
}

// The image loader tinygltf calls for every image: Meander's decoder, RGBA8 always.
bool load_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                const unsigned char* bytes, int size, void*) {
  try {
    Texture t = decode_image({reinterpret_cast<const char*>(bytes), size_t(size)}, "image " + std::to_string(index));
    image->width = t.width;
    image->height = t.height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image = std::move(t.rgba);
    return true;
  } catch (const Error& e) {
    if (err) *err += e.what();
    return false;
  }
}

class GltfReader {
public:
  // `warnings`: what tinygltf said while loading, which explains an image it could not load.
  GltfReader(const tinygltf::Model& model, std::string name, std::string warnings)
      : model_(model), name_(std::move(name)), warnings_(std::move(warnings)) {}

  TexturedMesh read() {
    const int scene = model_.defaultScene >= 0 ? model_.defaultScene : model_.scenes.empty() ? -1 : 0;
    if (scene >= int(model_.scenes.size())) fail("scene " + std::to_string(scene) + " does not exist");
    if (scene >= 0) {
      for (int node : model_.scenes[size_t(scene)].nodes) visit(node, identity, 0);
    } else {
      // A file of meshes without a scene: each mesh once, where it stands.
      for (size_t m = 0; m < model_.meshes.size(); ++m) add_mesh(int(m), identity);
    }
    require_faces(result_.mesh, name_);
    Appearance& a = result_.appearance;
    if (a.materials.size() == 1) a.face_material.clear();
    if (std::all_of(a.materials.begin(), a.materials.end(), [](const Material& m) { return m.texture.empty(); }))
      a.texcoords.clear();
    return std::move(result_);
  }

private:
  [[noreturn]] void fail(const std::string& message) const { fail_input(name_, message); }

  void visit(int index, const Matrix& parent, size_t depth) {
    if (index < 0 || size_t(index) >= model_.nodes.size()) fail("node " + std::to_string(index) + " does not exist");
    // glTF forbids cycles; a file with one would otherwise recurse forever.
    if (depth > model_.nodes.size()) fail("node " + std::to_string(index) + " is its own ancestor");
    const tinygltf::Node& node = model_.nodes[size_t(index)];
    const Matrix m = multiply(parent, local_matrix(node));
    if (node.mesh >= 0) add_mesh(node.mesh, m);
    for (int child : node.children) visit(child, m, depth + 1);
  }

  void add_mesh(int index, const Matrix& m) {
    if (size_t(index) >= model_.meshes.size()) fail("mesh " + std::to_string(index) + " does not exist");
    const tinygltf::Mesh& mesh = model_.meshes[size_t(index)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p)
      add_primitive(mesh.primitives[p], m, "mesh " + std::to_string(index) + " primitive " + std::to_string(p));
  }

  void add_primitive(const tinygltf::Primitive& primitive, const Matrix& m, const std::string& what) {
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
      return; // points and lines are not surfaces
    const std::string where = name_ + ": " + what;
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) fail(what + ": no POSITION attribute");
    const AccessorReader positions(model_, position->second, where + ": POSITION");
    positions.require(3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, "VEC3 of floats");

    const int32_t material = material_index(primitive.material, where);
    const Material& look = result_.appearance.materials[size_t(material)];
    std::optional<AccessorReader> texcoords;
    if (!look.texture.empty()) {
      const int set = model_.materials[size_t(primitive.material)].pbrMetallicRoughness.baseColorTexture.texCoord;
      const std::string attribute = "TEXCOORD_" + std::to_string(set);
      const auto found = primitive.attributes.find(attribute);
      if (found == primitive.attributes.end())
        fail(what + ": material " + std::to_string(primitive.material) + " has a base colour texture but the primitive has no " + attribute);
      texcoords.emplace(model_, found->second, where + ": " + attribute);
      texcoords->require(2, {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                         "VEC2 of floats or normalized unsigned bytes or shorts");
      if (texcoords->count() != positions.count())
        texcoords->fail("has " + std::to_string(texcoords->count()) + " elements for " + std::to_string(positions.count()) + " positions");
    }

    // The primitive's corners as indices into its vertices.
    std::vector<uint32_t> order;
    if (primitive.indices >= 0) {
      const AccessorReader indices(model_, primitive.indices, where + ": indices");
      indices.require(1, {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                      "SCALAR of unsigned bytes, shorts or ints");
      order.reserve(indices.count());
      for (size_t i = 0; i < indices.count(); ++i) {
        const double v = indices.value(i, 0);
        if (v >= double(positions.count()))
          indices.fail("element " + std::to_string(i) + ": " + index_out_of_range(int64_t(v), int64_t(positions.count())));
        order.push_back(uint32_t(v));
      }
    } else {
      for (size_t i = 0; i < positions.count(); ++i) order.push_back(uint32_t(i));
    }

    // Vertices welded across primitives by their transformed positions, as faces use
    // them: vertices no face uses are left out, as other readers leave them unreferenced.
    std::vector<int32_t> vertex(positions.count(), -1);
    auto welded = [&](uint32_t i) {
      if (vertex[i] >= 0) return vertex[i];
      const double x = positions.value(i, 0), y = positions.value(i, 1), z = positions.value(i, 2);
      const Vec3 p{float(m[0] * x + m[4] * y + m[8] * z + m[12]), float(m[1] * x + m[5] * y + m[9] * z + m[13]),
                   float(m[2] * x + m[6] * y + m[10] * z + m[14])};
      if (!is_finite(p)) positions.fail("element " + std::to_string(i) + ": " + non_finite_coordinate(p));
      return vertex[i] = welder_.add(p);
    };
    // A mirroring transform turns the faces inside out unless the winding is reversed.
    const bool mirrored = determinant3(m) < 0;
    auto add_triangle = [&](uint32_t a, uint32_t b, uint32_t c) {
      if (mirrored) std::swap(b, c);
      PolygonMesh& mesh = result_.mesh;
      for (uint32_t i : {a, b, c}) {
        mesh.face_vertices.push_back(welded(i));
        const TexCoord t = texcoords ? TexCoord{float(texcoords->value(i, 0)), float(1 - texcoords->value(i, 1))} : TexCoord{};
        result_.appearance.texcoords.push_back(t);
      }
      if (mesh.face_vertices.size() > size_t(max_count)) fail(too_many(mesh.face_vertices.size(), "face corners"));
      mesh.face_start.push_back(int32_t(mesh.face_vertices.size()));
      result_.appearance.face_material.push_back(material);
    };
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      for (size_t i = 0; i + 2 < order.size(); i += 3) add_triangle(order[i], order[i + 1], order[i + 2]);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (size_t i = 0; i + 2 < order.size(); ++i)
        i % 2 == 0 ? add_triangle(order[i], order[i + 1], order[i + 2]) : add_triangle(order[i + 1], order[i], order[i + 2]);
    } else {
      for (size_t i = 1; i + 1 < order.size(); ++i) add_triangle(order[0], order[i], order[i + 1]);
    }
  }

  // The index in result_'s materials of glTF material `index` (-1: the default),
  // added with its texture on first use.
  int32_t material_index(int index, const std::string& where) {
    const auto known = materials_.find(index);
    if (known != materials_.end()) return known->second;
    Material material{.name = "default", .base_color = default_grey};
    if (index >= 0) {
      if (size_t(index) >= model_.materials.size()) throw InputError(where + ": material " + std::to_string(index) + " does not exist");
      const tinygltf::Material& m = model_.materials[size_t(index)];
      material.name = m.name.empty() ? "material_" + std::to_string(index) : m.name;
      const std::vector<double>& factor = m.pbrMetallicRoughness.baseColorFactor;
      for (size_t k = 0; k < 3 && k < factor.size(); ++k) material.base_color[k] = float(factor[k]);
      if (const int texture = m.pbrMetallicRoughness.baseColorTexture.index; texture >= 0)
        material.texture = image_of(texture, "material " + std::to_string(index));
    }
    const int32_t added = int32_t(result_.appearance.materials.size());
    result_.appearance.materials.push_back(std::move(material));
    materials_.emplace(index, added);
    return added;
  }

  Texture image_of(int texture, const std::string& what) const {
    const std::string where = what + ": texture " + std::to_string(texture);
    if (size_t(texture) >= model_.textures.size()) fail(where + " does not exist");
    const int source = model_.textures[size_t(texture)].source;
    if (source < 0 || size_t(source) >= model_.images.size())
      fail(where + " has no image Meander can read (only PNG, JPEG and the like, not extension formats)");
    const tinygltf::Image& image = model_.images[size_t(source)];
    if (image.image.empty() || image.component != 4 || image.bits != 8)
      fail(where + ": image " + std::to_string(source) + (image.uri.empty() ? "" : " " + io::quoted(image.uri)) +
           ": cannot load (" + (warnings_.empty() ? "no data" : warnings_) + ")");
    return {.width = image.width, .height = image.height, .rgba = image.image};
  }

  const tinygltf::Model& model_;
  std::string name_, warnings_;
  TexturedMesh result_;
  Welder welder_{result_.mesh.positions, 0, name_};
  std::map<int, int32_t> materials_;
};

// --- Writing -------------------------------------------------------------------------

constexpr int array_buffer = 34962, element_array_buffer = 34963;

// The binary chunk and the JSON that describes it, built up together. The chunk's data
// is not copied: the views point into arrays that must live until write().
class GlbBuilder {
public:
  GlbBuilder() {
    json_ = {{"asset", {{"version", "2.0"}, {"generator", "Meander"}}}, {"scene", 0}, {"scenes", {nlohmann::json::object()}}};
  }

  // Adds bytes as a new buffer view, 4-byte aligned; returns its index.
  int view(const void* data, size_t size, int target) {
    bin_size_ = padded(bin_size_);
    nlohmann::json v = {{"buffer", 0}, {"byteOffset", bin_size_}, {"byteLength", size}};
    if (target != 0) v["target"] = target;
    views_.push_back({static_cast<const char*>(data), size});
    bin_size_ += size;
    return push("bufferViews", std::move(v));
  }

  int vec3_accessor(const std::vector<Vec3>& values, bool bounds) {
    nlohmann::json a = accessor(view(values.data(), values.size() * sizeof(Vec3), array_buffer), 5126, values.size(), "VEC3");
    if (bounds) {
      Box3 box;
      for (const Vec3& p : values) box.extend(p);
      a["min"] = {box.min.x, box.min.y, box.min.z};
      a["max"] = {box.max.x, box.max.y, box.max.z};
    }
    return push("accessors", std::move(a));
  }

  int vec2_accessor(const std::vector<TexCoord>& values) {
    return push("accessors", accessor(view(values.data(), values.size() * sizeof(TexCoord), array_buffer), 5126, values.size(), "VEC2"));
  }

  int index_accessor(const std::vector<uint32_t>& indices) {
    return push("accessors", accessor(view(indices.data(), indices.size() * 4, element_array_buffer), 5125, indices.size(), "SCALAR"));
  }

  int push(const char* array, nlohmann::json value) {
    nlohmann::json& list = json_[array];
    list.push_back(std::move(value));
    return int(list.size()) - 1;
  }

  nlohmann::json& json() { return json_; }

  void write(Sink& out) {
    if (bin_size_ > 0) json_["buffers"] = {{{"byteLength", bin_size_}}};
    std::string text = json_.dump();
    text.resize(padded(text.size()), ' ');
    const size_t bin_chunk = padded(bin_size_);
    const size_t total = 12 + 8 + text.size() + (bin_size_ == 0 ? 0 : 8 + bin_chunk);
    if (total > UINT32_MAX) throw UsageError("GLB of " + std::to_string(total) + " bytes: glTF files hold at most 4 GiB");
    out.little_endian(uint32_t(0x46546C67)); // "glTF"
    out.little_endian(uint32_t(2));
    out.little_endian(uint32_t(total));
    out.little_endian(uint32_t(text.size()));
    out.little_endian(uint32_t(0x4E4F534A)); // "JSON"
    out.text(text);
    if (bin_size_ == 0) return;
    out.little_endian(uint32_t(bin_chunk));
    out.little_endian(uint32_t(0x004E4942)); // "BIN\0"
    size_t written = 0;
    for (const auto& [data, size] : views_) {
      for (; written % 4 != 0; ++written) out.put('\0');
      out.bytes(data, size);
      written += size;
    }
    for (; written < bin_chunk; ++written) out.put('\0');
  }

private:
  static nlohmann::json accessor(int view, int component_type, size_t count, const char* type) {
    return {{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}};
  }

  static size_t padded(size_t size) { return (size + 3) / 4 * 4; }

  nlohmann::json json_;
  std::vector<std::pair<const char*, size_t>> views_;
  size_t bin_size_ = 0;
};

// The checks every GLB write makes first: a valid file needs finite positions and
// indices in range.
void require_writable(const PolygonMesh& mesh) {
  if (const int64_t v = first_non_finite(mesh.positions); v >= 0)
    throw UsageError("vertex " + std::to_string(v) + ": " + non_finite_coordinate(mesh.positions[size_t(v)]));
  for (int32_t f = 0; f < mesh.num_faces(); ++f)
    for (int32_t v : mesh.face(f))
      if (v < 0 || v >= mesh.num_vertices()) throw UsageError("face " + std::to_string(f) + ": " + index_out_of_range(v, mesh.num_vertices()));
}

// Fans face f into triangles of `corner` numbers (indices of the corners' vertices).
template <class Corner> void fan(const PolygonMesh& mesh, int32_t f, Corner&& corner, std::vector<uint32_t>& out) {
  const int32_t first = mesh.face_start[f], size = mesh.face_size(f);
  for (int32_t i = 1; i + 1 < size; ++i)
    for (int32_t c : {first, first + i, first + i + 1}) out.push_back(corner(c));
}

// A vertex of the mesh with one texture coordinate (its bits: -0 and +0 are one).
struct SplitKey {
  int32_t vertex;
  uint32_t u, v;
  friend bool operator==(const SplitKey&, const SplitKey&) = default;
  struct Hash {
    size_t operator()(const SplitKey& k) const {
      uint64_t h = uint64_t(uint32_t(k.vertex)) * 0x9E3779B97F4A7C15ull ^ uint64_t(k.u) * 0xC2B2AE3D27D4EB4Full ^ uint64_t(k.v) * 0x165667B19E3779F9ull;
      return size_t(h ^ (h >> 29));
    }
  };
};

nlohmann::json primitive(int positions, int normals, int texcoords, int indices, int material) {
  nlohmann::json p = {{"attributes", {{"POSITION", positions}}}, {"indices", indices}, {"mode", 4}};
  if (normals >= 0) p["attributes"]["NORMAL"] = normals;
  if (texcoords >= 0) p["attributes"]["TEXCOORD_0"] = texcoords;
  if (material >= 0) p["material"] = material;
  return p;
}

// Adds the node and mesh if there are primitives: a glTF mesh needs at least one. A mesh
// in millimetres gets a node that scales it to metres, glTF's unit.
void add_scene_mesh(GlbBuilder& glb, nlohmann::json primitives, bool millimetres) {
  if (primitives.empty()) return;
  glb.push("meshes", {{"primitives", std::move(primitives)}});
  nlohmann::json node = {{"mesh", 0}};
  if (millimetres) node["scale"] = {0.001, 0.001, 0.001};
  glb.push("nodes", std::move(node));
  glb.json()["scenes"][0]["nodes"] = {0};
}

// tinygltf copies `extras` and `extensions` into its own values recursively, one stack
// frame per level, so JSON nested a few ten thousand levels deep overflows the stack.
// glTF itself nests about 6 levels; 64 leaves room for any sensible extras.
constexpr int max_json_depth = 64;

// The JSON of a .gltf, or the first chunk of a .glb (when its header can be read).
std::string_view json_text(std::string_view bytes, bool binary) {
  if (!binary) return bytes;
  constexpr size_t header = 20; // magic, version, length, then chunk length and type
  if (bytes.size() < header) return {};
  return bytes.substr(header, load_little_endian<uint32_t>(bytes.data() + 12));
}

// The deepest nesting of arrays and objects, brackets inside strings not counted.
int json_depth(std::string_view json) {
  int depth = 0, deepest = 0;
  bool in_string = false;
  for (size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

} // namespace

TexturedMesh read_gltf(std::string_view bytes, const fs::path& path) {
  const std::string name = path.string();
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(load_image, nullptr);
  loader.SetFsCallbacks({.FileExists = tinygltf::FileExists, .ExpandFilePath = tinygltf::ExpandFilePath,
                         .ReadWholeFile = read_external_file, .WriteWholeFile = tinygltf::WriteWholeFile,
                         .user_data = nullptr});
  tinygltf::Model model;
  std::string error, warnings;
  if (bytes.size() > UINT32_MAX) fail_input(name, "file too large for glTF (over 4 GiB)");
  const std::string folder = path.parent_path().empty() ? "." : path.parent_path().string();
  const bool binary = bytes.starts_with("glTF");
  if (json_depth(json_text(bytes, binary)) > max_json_depth)
    fail_input(name, "JSON nested deeper than " + std::to_string(max_json_depth) + " levels");
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(&model, &error, &warnings, reinterpret_cast<const unsigned char*>(bytes.data()),
                                              unsigned(bytes.size()), folder)
                : loader.LoadASCIIFromString(&model, &error, &warnings, bytes.data(), unsigned(bytes.size()), folder);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    // tinygltf reports most problems in `error`, but its JSON library may still throw.
    error = e.what();
  }
  auto trimmed = [](std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    for (char& c : s) c = c == '\n' ? ';' : c;
    return s;
  };
  if (!ok) fail_input(name, error.empty() ? "not a glTF file" : trimmed(error));
  return GltfReader(model, name, trimmed(warnings)).read();
}

void write_glb(const PolygonMesh& mesh, const MeshWriteOptions& options, Sink& out) {
  require_writable(mesh);
  std::vector<uint32_t> indices;
  std::vector<Vec3> normals;
  GlbBuilder glb; // after the arrays its views point into
  indices.reserve(3 * size_t(std::max(0, mesh.num_corners() - 2 * mesh.num_faces())));
  for (int32_t f = 0; f < mesh.num_faces(); ++f) fan(mesh, f, [&](int32_t c) { return uint32_t(mesh.face_vertices[c]); }, indices);
  nlohmann::json primitives = nlohmann::json::array();
  if (!indices.empty()) {
    const int positions = glb.vec3_accessor(mesh.positions, true);
    if (options.normals) normals = vertex_normals(mesh);
    const int normal_accessor = options.normals ? glb.vec3_accessor(normals, false) : -1;
    primitives.push_back(primitive(positions, normal_accessor, -1, glb.index_accessor(indices), -1));
  }
  add_scene_mesh(glb, std::move(primitives), options.millimetres);
  glb.write(out);
}

void write_textured_glb(const TexturedMesh& textured, bool millimetres, Sink& out) {
  const PolygonMesh& mesh = textured.mesh;
  const Appearance& a = textured.appearance;
  if (a.materials.empty()) return write_glb(mesh, {.millimetres = millimetres}, out);
  require_writable(mesh);
  // glTF vertices carry one texture coordinate: split each vertex into one per distinct
  // coordinate around it, numbered in order of first use.
  std::vector<Vec3> positions, normals;
  std::vector<TexCoord> texcoords;
  const std::vector<Vec3> smooth = vertex_normals(mesh);
  std::vector<uint32_t> corner_vertex(size_t(mesh.num_corners()));
  std::unordered_map<SplitKey, uint32_t, SplitKey::Hash> split;
  for (int32_t c = 0; c < mesh.num_corners(); ++c) {
    const int32_t v = mesh.face_vertices[c];
    // glTF's v runs down the image.
    const TexCoord t = a.texcoords.empty() ? TexCoord{} : TexCoord{a.texcoords[size_t(c)].u, 1 - a.texcoords[size_t(c)].v};
    const auto [it, added] = split.emplace(SplitKey{v, std::bit_cast<uint32_t>(t.u + 0.0f), std::bit_cast<uint32_t>(t.v + 0.0f)},
                                           uint32_t(positions.size()));
    corner_vertex[size_t(c)] = it->second;
    if (!added) continue;
    positions.push_back(mesh.positions[size_t(v)]);
    normals.push_back(smooth[size_t(v)]);
    texcoords.push_back(t);
  }

  std::vector<std::string> pngs(a.materials.size());
  std::vector<std::vector<uint32_t>> indices(a.materials.size());
  GlbBuilder glb; // after the arrays its views point into
  int sampler = -1;
  for (size_t k = 0; k < a.materials.size(); ++k) {
    const Material& m = a.materials[k];
    nlohmann::json pbr = {{"baseColorFactor", {m.base_color[0], m.base_color[1], m.base_color[2], 1.0}},
                          {"metallicFactor", 0.0},
                          {"roughnessFactor", 1.0}};
    if (!m.texture.empty()) {
      const std::string& png = pngs[k] = encode_png(m.texture.rgba.data(), m.texture.width, m.texture.height, 4, m.name);
      // Linear filtering without mipmaps: a texture atlas must not bleed between its tiles.
      if (sampler < 0) sampler = glb.push("samplers", {{"magFilter", 9729}, {"minFilter", 9729}});
      const int image = glb.push("images", {{"bufferView", glb.view(png.data(), png.size(), 0)}, {"mimeType", "image/png"}});
      pbr["baseColorTexture"] = {{"index", glb.push("textures", {{"source", image}, {"sampler", sampler}})}};
    }
    glb.push("materials", {{"name", m.name}, {"pbrMetallicRoughness", std::move(pbr)}, {"doubleSided", true}});
  }

  nlohmann::json primitives = nlohmann::json::array();
  if (!positions.empty()) {
    const int position_accessor = glb.vec3_accessor(positions, true);
    const int normal_accessor = glb.vec3_accessor(normals, false);
    const bool any_texture = std::any_of(a.materials.begin(), a.materials.end(), [](const Material& m) { return !m.texture.empty(); });
    const int texcoord_accessor = any_texture ? glb.vec2_accessor(texcoords) : -1;
    // One primitive per material, its faces in mesh order.
    for (int32_t f = 0; f < mesh.num_faces(); ++f) {
      const size_t m = a.face_material.empty() ? 0 : size_t(a.face_material[size_t(f)]);
      fan(mesh, f, [&](int32_t c) { return corner_vertex[size_t(c)]; }, indices[m]);
    }
    for (size_t m = 0; m < indices.size(); ++m)
      if (!indices[m].empty())
        primitives.push_back(primitive(position_accessor, normal_accessor, a.materials[m].texture.empty() ? -1 : texcoord_accessor,
                                       glb.index_accessor(indices[m]), int(m)));
  }
  add_scene_mesh(glb, std::move(primitives), millimetres);
  glb.write(out);
}

} // namespace meander::io
