// OBJ with its materials: vt, mtllib and usemtl in the OBJ; newmtl, Kd and map_Kd in the
// MTL; the textures those name. And the writer of the same three kinds of files.
#include "io/formats.h"
#include "io/image_codec.h"
#include "io/mapped_file.h"
#include "io/obj_indices.h"
#include "meander/error.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <map>
#include <unordered_map>
#include <utility>

namespace meander::io {
namespace {

namespace fs = std::filesystem;

// A file named inside another one, relative to that file's folder. Windows exporters
// write backslashes.
fs::path beside(const fs::path& file, std::string_view name) {
  std::string portable(name);
  std::replace(portable.begin(), portable.end(), '\\', '/');
  return file.parent_path() / portable;
}

// "bunny.obj:3: mtllib 'x.mtl': " before the message of an error about the named file,
// keeping the error's type (IOError for a file that cannot be opened, InputError for
// content that is malformed).
template <class Read> auto named_from(std::string_view file, int64_t line, std::string_view statement,
                                      std::string_view target, Read&& read) {
  const std::string where = std::string(file) + ":" + std::to_string(line) + ": " + std::string(statement) + " " +
                            quoted(target) + ": ";
  try {
    return read();
  } catch (const IOError& e) {
    throw IOError(where + e.what());
  } catch (const InputError& e) {
    throw InputError(where + e.what());
  }
}

// The rest of the line, without the blanks around it: file names may hold spaces.
std::string_view rest_of_line(TextCursor& in) {
  in.skip_blanks();
  std::string_view rest;
  while (!in.at_line_end()) {
    const std::string_view word = in.word();
    rest = rest.empty() ? word : std::string_view(rest.data(), size_t(word.data() + word.size() - rest.data()));
  }
  return rest;
}

// A material as an MTL file defines it; its texture is decoded only if a face uses it.
struct MtlMaterial {
  std::string name;
  LinearRgb kd{1, 1, 1};
  std::string map_kd;  // as written in the file; empty: none
  int64_t map_line = 0; // for messages about the texture
  fs::path mtl;         // the MTL file, which texture names are relative to
};

// map_Kd options and how many values each takes (-o, -s and -t take one to three).
int option_values(std::string_view option) {
  static const std::pair<std::string_view, int> options[] = {
      {"-blendu", 1}, {"-blendv", 1}, {"-bm", 1},   {"-boost", 1},   {"-cc", 1}, {"-clamp", 1}, {"-imfchan", 1},
      {"-mm", 2},     {"-o", 3},      {"-s", 3},    {"-t", 3},       {"-texres", 1}, {"-type", 1}};
  for (const auto& [name, values] : options)
    if (name == option) return values;
  return -1;
}

bool is_number(std::string_view word) {
  double value;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc{} && end == word.data() + word.size();
}

void read_mtl(std::string_view bytes, const fs::path& path, std::vector<MtlMaterial>& materials) {
  const std::string name = path.string();
  TextCursor in(bytes, name);
  MtlMaterial* current = nullptr;
  auto require_material = [&](std::string_view keyword) {
    if (!current) in.fail(std::string(keyword) + " before any newmtl");
  };
  while (!in.at_end()) {
    if (!in.at_line_end()) {
      const std::string_view keyword = in.word();
      if (keyword == "newmtl") {
        const std::string_view material = rest_of_line(in);
        if (material.empty()) in.fail("newmtl without a name");
        current = &materials.emplace_back(MtlMaterial{.name = std::string(material), .mtl = path});
      } else if (keyword == "Kd") {
        require_material(keyword);
        const float r = in.real("Kd value");
        // One value stands for grey.
        if (in.at_line_end()) {
          current->kd = {r, r, r};
        } else {
          const float g = in.real("Kd value");
          const float b = in.real("Kd value");
          if (!in.at_line_end()) in.fail("Kd takes 1 or 3 values, found more");
          current->kd = {r, g, b};
        }
      } else if (keyword == "map_Kd") {
        require_material(keyword);
        std::vector<std::string_view> words;
        while (!in.at_line_end()) words.push_back(in.word());
        size_t i = 0;
        while (i < words.size() && words[i].size() > 1 && words[i][0] == '-') {
          const std::string_view option = words[i++];
          const int values = option_values(option);
          if (values < 0) in.fail("map_Kd: unknown option " + quoted(option));
          // -o, -s and -t take one to three numbers: the file name follows the last one.
          int taken = 0;
          for (; taken < values && i < words.size() && (taken == 0 || is_number(words[i])); ++taken) ++i;
          if (taken == 0) in.fail("map_Kd: option " + quoted(option) + " lacks its value");
        }
        if (i == words.size()) in.fail("map_Kd without a file name");
        // The file name is the rest of the line: it may hold spaces.
        const std::string_view rest(words[i].data(), size_t(words.back().data() + words.back().size() - words[i].data()));
        current->map_kd = std::string(rest);
        current->map_line = in.line();
      }
      // Ka, Ks, Ns, d, illum, bump and the other maps do not change the base colour.
    }
    in.next_line();
  }
}

// Reads a texture once however many materials name it.
class TextureCache {
public:
  const Texture& get(const MtlMaterial& m) {
    const fs::path path = beside(m.mtl, m.map_kd);
    auto found = textures_.find(path.string());
    if (found != textures_.end()) return found->second;
    Texture texture = named_from(m.mtl.string(), m.map_line, "map_Kd", m.map_kd, [&] { return read_texture(path); });
    return textures_.emplace(path.string(), std::move(texture)).first->second;
  }

private:
  std::map<std::string, Texture> textures_;
};

// "12", "12/5", "12//7" or "12/5/7": the vertex index and, if there is one, the texture
// coordinate index (0 when absent; OBJ indices are never 0).
std::pair<int64_t, int64_t> read_corner(TextCursor& in) {
  in.skip_blanks();
  const std::string_view word = in.word();
  auto number = [&](std::string_view text, std::string_view what) {
    int64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc{} || end != text.data() + text.size()) in.fail("bad " + std::string(what) + " " + quoted(word));
    return value;
  };
  const size_t slash = word.find('/');
  const int64_t vertex = number(word.substr(0, slash), "vertex index");
  if (slash == std::string_view::npos) return {vertex, 0};
  const std::string_view rest = word.substr(slash + 1);
  const std::string_view vt = rest.substr(0, rest.find('/'));
  if (vt.empty()) return {vertex, 0};
  const int64_t texcoord = number(vt, "texture coordinate index");
  if (texcoord == 0) in.fail("texture coordinate index 0 is invalid (OBJ indices start at 1)");
  return {vertex, texcoord};
}

// Material names as MTL files can carry them: one word, unique in the file.
std::vector<std::string> writable_names(const std::vector<Material>& materials) {
  std::vector<std::string> names;
  for (size_t k = 0; k < materials.size(); ++k) {
    const std::string& name = materials[k].name;
    const bool usable = !name.empty() && std::none_of(name.begin(), name.end(), [](unsigned char c) { return c <= ' ' || c == '#'; }) &&
                        std::find(names.begin(), names.end(), name) == names.end();
    names.push_back(usable ? name : "material_" + std::to_string(k));
  }
  return names;
}

void write_color(Sink& out, const LinearRgb& c) {
  for (float v : c) {
    out.put(' ');
    out.real(v);
  }
  out.put('\n');
}

} // namespace

TexturedMesh read_textured_obj(std::string_view bytes, const fs::path& path) {
  const std::string name = path.string();
  TextCursor in(bytes, name);
  TexturedMesh result;
  PolygonMesh& mesh = result.mesh;
  std::vector<TexCoord> texcoords;
  std::vector<int32_t> corner_texcoord; // per corner, -1 where the face has none
  std::vector<MtlMaterial> library;
  bool has_library = false;
  // usemtl names in order of first use, the line of that use, and the first face line
  // without texture coordinates under each.
  std::vector<std::string> used;
  std::vector<int64_t> used_line, untextured_face_line;
  std::vector<int32_t> face_used; // per face, index into used or -1
  int32_t current = -1;
  ForwardIndices vertices{"vertex"}, coordinates{"texture coordinate"};
  while (!in.at_end()) {
    if (!in.at_line_end()) {
      const std::string_view keyword = in.word();
      if (keyword == "v") {
        read_position(in, mesh.positions);
      } else if (keyword == "vt") {
        if (int64_t(texcoords.size()) == max_count) in.fail(too_many(uint64_t(max_count) + 1, "texture coordinates"));
        const float u = in.real("texture coordinate");
        const float v = in.at_line_end() ? 0.0f : in.real("texture coordinate");
        texcoords.push_back({u, v});
      } else if (keyword == "f") {
        const size_t first = mesh.face_vertices.size();
        int with = 0, without = 0;
        while (!in.at_line_end()) {
          const auto [vertex, texcoord] = read_corner(in);
          mesh.face_vertices.push_back(vertices.resolve(in, vertex, "face", int64_t(mesh.positions.size())));
          corner_texcoord.push_back(texcoord == 0 ? -1 : coordinates.resolve(in, texcoord, "face", int64_t(texcoords.size())));
          ++(texcoord == 0 ? without : with);
        }
        if (const size_t size = mesh.face_vertices.size() - first; size < 3) in.fail(too_few_vertices(int64_t(size)));
        if (with > 0 && without > 0) in.fail("face gives texture coordinates for some corners only");
        if (mesh.face_vertices.size() > size_t(max_count)) in.fail(too_many(mesh.face_vertices.size(), "face corners"));
        mesh.face_start.push_back(int32_t(mesh.face_vertices.size()));
        face_used.push_back(current);
        if (current >= 0 && without > 0 && untextured_face_line[current] == 0) untextured_face_line[current] = in.line();
      } else if (keyword == "mtllib") {
        has_library = true;
        const int64_t line = in.line();
        while (!in.at_line_end()) {
          const std::string_view file = in.word();
          named_from(name, line, "mtllib", file, [&] {
            const fs::path mtl = beside(path, file);
            const MappedFile mapped(mtl);
            read_mtl(mapped.bytes(), mtl, library);
          });
        }
      } else if (keyword == "usemtl") {
        const std::string_view material = rest_of_line(in);
        if (material.empty()) in.fail("usemtl without a name");
        const auto found = std::find(used.begin(), used.end(), material);
        current = int32_t(found - used.begin());
        if (found == used.end()) {
          used.emplace_back(material);
          used_line.push_back(in.line());
          untextured_face_line.push_back(0);
        }
      }
      // vn, o, g, s, l and stray lines do not change the surface (see read_obj).
    }
    in.next_line();
  }
  vertices.check(name, "face", int64_t(mesh.positions.size()));
  coordinates.check(name, "face", int64_t(texcoords.size()));
  require_faces(mesh, name);
  // Without a material library there is nothing to paint with: a plain mesh, whatever
  // usemtl lines it has.
  if (!has_library) return result;

  Appearance& a = result.appearance;
  TextureCache cache;
  std::vector<int32_t> material_of_used(used.size());
  for (size_t k = 0; k < used.size(); ++k) {
    // The last definition of a name wins, as in other readers.
    const auto found = std::find_if(library.rbegin(), library.rend(), [&](const MtlMaterial& m) { return m.name == used[k]; });
    if (found == library.rend()) fail_at_line(name, used_line[k], "usemtl " + io::quoted(used[k]) + ": no material of that name in the mtllib files");
    Material material{.name = used[k], .base_color = found->kd};
    if (!found->map_kd.empty()) {
      if (untextured_face_line[k] != 0)
        fail_at_line(name, untextured_face_line[k],
                     "face without texture coordinates (vt) uses material " + io::quoted(used[k]) + ", which has a texture (map_Kd)");
      material.texture = cache.get(*found);
    }
    material_of_used[k] = int32_t(a.materials.size());
    a.materials.push_back(std::move(material));
  }
  // Faces before any usemtl get a light grey, as the renderer draws plain meshes.
  if (a.materials.empty() || std::find(face_used.begin(), face_used.end(), -1) != face_used.end()) {
    a.materials.push_back({.name = "default", .base_color = {0.604f, 0.604f, 0.604f}});
  }
  if (a.materials.size() > 1) {
    a.face_material.reserve(face_used.size());
    for (int32_t k : face_used) a.face_material.push_back(k < 0 ? int32_t(a.materials.size()) - 1 : material_of_used[size_t(k)]);
  }
  if (std::any_of(corner_texcoord.begin(), corner_texcoord.end(), [](int32_t t) { return t >= 0; })) {
    a.texcoords.reserve(corner_texcoord.size());
    for (int32_t t : corner_texcoord) a.texcoords.push_back(t < 0 ? TexCoord{} : texcoords[size_t(t)]);
  }
  return result;
}

void write_textured_obj(const TexturedMesh& textured, const fs::path& path, const std::function<Sink&(const fs::path&)>& open) {
  const PolygonMesh& mesh = textured.mesh;
  const Appearance& a = textured.appearance;
  check_appearance(mesh, a, path.string());
  const std::vector<std::string> names = writable_names(a.materials);
  // Textures are named after the OBJ, not after a material, so that two OBJ files in one
  // folder never share one; "_texture" keeps them apart from a picture of the result.
  const int textured_count = int(std::count_if(a.materials.begin(), a.materials.end(), [](const Material& m) { return !m.texture.empty(); }));
  const std::string stem = path.stem().string();
  std::vector<std::string> texture_names(a.materials.size());
  for (size_t k = 0; k < a.materials.size(); ++k)
    if (!a.materials[k].texture.empty())
      texture_names[k] = stem + (textured_count == 1 ? "_texture.png" : "_texture_" + std::to_string(k) + ".png");

  Sink& obj = open(path);
  if (!a.materials.empty()) {
    fs::path mtl_path = path;
    mtl_path.replace_extension(".mtl");
    Sink& mtl = open(mtl_path);
    for (size_t k = 0; k < a.materials.size(); ++k) {
      mtl.text(k == 0 ? "newmtl " : "\nnewmtl ");
      mtl.text(names[k]);
      mtl.text("\nKd");
      write_color(mtl, a.materials[k].base_color);
      if (texture_names[k].empty()) continue;
      mtl.text("map_Kd ");
      mtl.text(texture_names[k]);
      mtl.put('\n');
      const Texture& t = a.materials[k].texture;
      const fs::path png_path = path.parent_path() / texture_names[k];
      Sink& png = open(png_path);
      const std::string bytes = encode_png(t.rgba.data(), t.width, t.height, 4, png_path.string());
      png.bytes(bytes.data(), bytes.size());
    }
    obj.text("mtllib ");
    obj.text(mtl_path.filename().string());
    obj.put('\n');
  }
  for (const Vec3& p : mesh.positions) {
    obj.text("v ");
    write_point_line(obj, p);
  }
  // Each distinct coordinate once, numbered in order of first use.
  std::vector<int32_t> corner_vt(a.texcoords.size());
  std::unordered_map<uint64_t, int32_t> numbers;
  for (size_t c = 0; c < a.texcoords.size(); ++c) {
    const TexCoord t = a.texcoords[c];
    const uint64_t key = uint64_t(std::bit_cast<uint32_t>(t.u + 0.0f)) << 32 | std::bit_cast<uint32_t>(t.v + 0.0f);
    const auto [it, added] = numbers.emplace(key, int32_t(numbers.size()));
    corner_vt[c] = it->second;
    if (!added) continue;
    obj.text("vt ");
    obj.real(t.u);
    obj.put(' ');
    obj.real(t.v);
    obj.put('\n');
  }
  int32_t material = -1;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const int32_t m = a.materials.empty() ? -1 : a.face_material.empty() ? 0 : a.face_material[size_t(f)];
    if (m != material) {
      obj.text("usemtl ");
      obj.text(names[size_t(m)]);
      obj.put('\n');
      material = m;
    }
    obj.put('f');
    for (int32_t c = mesh.face_start[f]; c < mesh.face_start[f + 1]; ++c) {
      obj.put(' ');
      obj.integer(int64_t(mesh.face_vertices[size_t(c)]) + 1);
      if (corner_vt.empty()) continue;
      obj.put('/');
      obj.integer(int64_t(corner_vt[size_t(c)]) + 1);
    }
    obj.put('\n');
  }
}

} // namespace meander::io
