#include "io/binary.h"
#include "io/block_writer.h"
#include "io/formats.h"
#include "io/reader_support.h"
#include "io/text_cursor.h"
#include "core/chunks.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

namespace meander::io {
namespace {

enum class Scalar : uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

size_t size_of(Scalar type) {
  constexpr size_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return sizes[size_t(type)];
}

bool is_integer(Scalar type) { return type < Scalar::float32; }

// The PLY 1.0 names and the sized names most writers use now.
std::optional<Scalar> scalar_named(std::string_view name) {
  static constexpr std::pair<std::string_view, Scalar> names[] = {
      {"char", Scalar::int8},      {"int8", Scalar::int8},       {"uchar", Scalar::uint8},
      {"uint8", Scalar::uint8},    {"short", Scalar::int16},     {"int16", Scalar::int16},
      {"ushort", Scalar::uint16},  {"uint16", Scalar::uint16},   {"int", Scalar::int32},
      {"int32", Scalar::int32},    {"uint", Scalar::uint32},     {"uint32", Scalar::uint32},
      {"float", Scalar::float32},  {"float32", Scalar::float32}, {"double", Scalar::float64},
      {"float64", Scalar::float64}};
  for (const auto& [scalar_name, type] : names)
    if (scalar_name == name) return type;
  return std::nullopt;
}

// Calls f with a value of the C++ type of `type` (to pick a template instance).
template <class F> auto with_scalar_type(Scalar type, F f) {
  switch (type) {
  case Scalar::int8: return f(int8_t{});
  case Scalar::uint8: return f(uint8_t{});
  case Scalar::int16: return f(int16_t{});
  case Scalar::uint16: return f(uint16_t{});
  case Scalar::int32: return f(int32_t{});
  case Scalar::uint32: return f(uint32_t{});
  case Scalar::float32: return f(float{});
  case Scalar::float64: break;
  }
  return f(double{});
}

// What Meander takes from a property; x, y, z double as indices into a point, and
// vertex1, vertex2 as indices into an edge.
enum class Role : uint8_t { x, y, z, indices, vertex1, vertex2, none };

struct Property {
  std::string name;
  Scalar type = Scalar::float32;    // of the value, or of a list's items
  std::optional<Scalar> count_type; // set for lists only
  Role role = Role::none;
};

// tristrips: the triangle strips some scanners and older tools write instead of faces.
enum class Kind : uint8_t { vertex, face, tristrips, edge, other };

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
  Kind kind = Kind::other;

  bool has_lists() const {
    return std::any_of(properties.begin(), properties.end(),
                       [](const Property& p) { return p.count_type.has_value(); });
  }
  // How many the header claims, for messages: "8 vertices", "1 face", "3 'edge' elements".
  std::string claimed() const {
    const bool one = count == 1;
    const std::string things = kind == Kind::vertex ? (one ? "vertex" : "vertices")
                               : kind == Kind::face ? (one ? "face" : "faces")
                               : kind == Kind::tristrips ? (one ? "triangle strip" : "triangle strips")
                                                    : "'" + name + (one ? "' element" : "' elements");
    return std::to_string(count) + " " + things;
  }
};

enum class Encoding { ascii, binary_little_endian, binary_big_endian };

struct Header {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
  size_t body_offset = 0;
  int64_t body_line = 0;
};

// The record of element e in messages: "face 17".
std::string record_label(const Element& e, uint64_t index) { return e.name + " " + std::to_string(index); }

std::string ends_early(const Element& e) { return "file ends early (the header claims " + e.claimed() + ")"; }

// What a file is read for: a mesh (vertex and face elements) or polylines (vertex and
// edge elements); the other elements are skipped.
enum class Target { mesh, polylines };

// Finds the vertex element and the face or edge element, and the properties Meander
// reads from them.
void assign_roles(Header& header, Target target, std::string_view name) {
  const auto fail = [&](const std::string& message) { fail_input(name, "header: " + message); };
  const std::string_view wanted = target == Target::mesh ? "face" : "edge";
  Element* vertex = nullptr;
  Element* face = nullptr;
  Element* strips = nullptr;
  for (Element& e : header.elements) {
    Element** slot = e.name == "vertex"                                     ? &vertex
                     : e.name == wanted                                     ? &face
                     : target == Target::mesh && e.name == "tristrips" ? &strips
                                                                            : nullptr;
    if (!slot) continue;
    if (*slot) fail("two " + e.name + " elements");
    *slot = &e;
    e.kind = slot == &vertex ? Kind::vertex : slot == &strips ? Kind::tristrips : target == Target::mesh ? Kind::face : Kind::edge;
  }
  if (!vertex) fail("no vertex element");
  for (Role axis : {Role::x, Role::y, Role::z}) {
    const std::string axis_name(1, char('x' + int(axis)));
    const auto p = std::find_if(vertex->properties.begin(), vertex->properties.end(),
                                [&](const Property& q) { return q.name == axis_name; });
    if (p == vertex->properties.end()) fail("element vertex has no property " + axis_name);
    if (p->count_type) fail("property " + axis_name + " of element vertex is a list");
    p->role = axis;
  }
  if (std::string message = too_many(vertex->count, "vertices"); !message.empty()) fail(message);
  if (target == Target::polylines) {
    if (!face) fail_no_polylines(name, "edge elements");
    for (Role end : {Role::vertex1, Role::vertex2}) {
      const std::string end_name = end == Role::vertex1 ? "vertex1" : "vertex2";
      const auto p = std::find_if(face->properties.begin(), face->properties.end(),
                                  [&](const Property& q) { return q.name == end_name; });
      if (p == face->properties.end()) fail("element edge has no property " + end_name);
      if (p->count_type || !is_integer(p->type)) fail("property " + end_name + " of element edge must be an integer");
      p->role = end;
    }
    if (std::string message = too_many(face->count, "edges"); !message.empty()) fail(message);
    return;
  }
  if (!face && !strips) fail_input(name, "no faces");
  for (Element* e : {face, strips}) {
    if (!e) continue;
    const auto indices = std::find_if(e->properties.begin(), e->properties.end(), [](const Property& q) {
      return q.name == "vertex_indices" || q.name == "vertex_index";
    });
    if (indices == e->properties.end() || !indices->count_type) fail("element " + e->name + " has no vertex_indices list");
    if (!is_integer(indices->type)) fail(indices->name + " must be a list of integers");
    indices->role = Role::indices;
    if (std::string message = too_many(e->count, e == face ? "faces" : "triangle strips"); !message.empty()) fail(message);
  }
}

Header read_header(std::string_view bytes, Target target, std::string_view name) {
  const auto fail = [&](const std::string& message) { fail_input(name, "header: " + message); };
  Header header;
  bool has_format = false;
  size_t pos = 0;
  std::vector<std::string_view> words;
  for (int64_t line_number = 1;; ++line_number) {
    if (pos == bytes.size()) fail("no end_header line");
    const size_t newline = bytes.find('\n', pos);
    std::string_view line =
        bytes.substr(pos, newline == std::string_view::npos ? std::string_view::npos : newline - pos);
    pos = newline == std::string_view::npos ? bytes.size() : newline + 1;
    if (line.ends_with('\r')) line.remove_suffix(1);
    if (line_number == 1) {
      if (line != "ply") fail_input(name, "not a PLY file (it does not start with 'ply')");
      continue;
    }
    words.clear();
    for (size_t i = 0; i < line.size();) {
      if (TextCursor::is_blank(line[i])) {
        ++i;
        continue;
      }
      const size_t start = i;
      while (i < line.size() && !TextCursor::is_blank(line[i])) ++i;
      words.push_back(line.substr(start, i - start));
    }
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    const std::string_view keyword = words[0];
    if (keyword == "end_header") {
      header.body_offset = pos;
      header.body_line = line_number + 1;
      break;
    }
    if (keyword == "format") {
      if (words.size() != 3) fail("bad format line " + quoted(line));
      if (words[1] == "ascii")
        header.encoding = Encoding::ascii;
      else if (words[1] == "binary_little_endian")
        header.encoding = Encoding::binary_little_endian;
      else if (words[1] == "binary_big_endian")
        header.encoding = Encoding::binary_big_endian;
      else
        fail("unknown format " + quoted(words[1]));
      if (words[2] != "1.0") fail("unsupported PLY version " + quoted(words[2]));
      has_format = true;
    } else if (keyword == "element") {
      if (words.size() != 3) fail("bad element line " + quoted(line));
      const std::string_view count_text = words[2];
      uint64_t count = 0;
      const auto [last, ec] = std::from_chars(count_text.data(), count_text.data() + count_text.size(), count);
      if (ec != std::errc() || last != count_text.data() + count_text.size())
        fail("bad element count " + quoted(count_text));
      header.elements.push_back({std::string(words[1]), count, {}});
    } else if (keyword == "property") {
      if (header.elements.empty()) fail("property before any element");
      Property property;
      const bool is_list = words.size() == 5 && words[1] == "list";
      if (!is_list && words.size() != 3) fail("bad property line " + quoted(line));
      const std::string_view type_name = words[is_list ? 3 : 1];
      const std::optional<Scalar> type = scalar_named(type_name);
      if (!type) fail("unknown property type " + quoted(type_name));
      property.type = *type;
      if (is_list) {
        property.count_type = scalar_named(words[2]);
        if (!property.count_type || !is_integer(*property.count_type))
          fail("list length type " + quoted(words[2]) + " is not an integer type");
      }
      property.name = words.back();
      header.elements.back().properties.push_back(std::move(property));
    } else {
      fail("unknown line " + quoted(line));
    }
  }
  if (!has_format) fail("no format line");
  assign_roles(header, target, name);
  return header;
}

// The values of a binary body, read in order; failures name the element and record.
class BinarySource {
public:
  BinarySource(std::string_view body, bool swap, std::string_view name)
      : p_(body.data()), end_(body.data() + body.size()), swap_(swap), name_(name) {}

  void begin(const Element& e, uint64_t index) {
    element_ = &e;
    index_ = index;
  }
  float coordinate(Scalar type) {
    const char* at = take(size_of(type));
    const double value = with_scalar_type(type, [&](auto zero) { return double(load<decltype(zero)>(at, swap_)); });
    // Also refuses what a float cannot hold, whose conversion would be undefined.
    if (!(std::fabs(value) <= std::numeric_limits<float>::max())) fail(non_finite_coordinate(value));
    return float(value);
  }
  // `type` is an integer type (the header checked it).
  int64_t integer(Scalar type, std::string_view) {
    const char* at = take(size_of(type));
    return with_scalar_type(type, [&](auto zero) { return int64_t(load<decltype(zero)>(at, swap_)); });
  }
  void skip(Scalar type, int64_t count) {
    if (uint64_t(count) > bytes_left() / size_of(type)) fail(ends_early(*element_));
    p_ += size_t(count) * size_of(type);
  }
  size_t bytes_left() const { return size_t(end_ - p_); }
  static size_t value_bytes(Scalar type) { return size_of(type); }
  [[noreturn]] void fail(std::string_view message) const {
    fail_input(name_, record_label(*element_, index_) + ": " + std::string(message));
  }

  // Reads or skips the whole element if its layout has a fast path, returning false
  // otherwise. `index_limit` bounds the face indices.
  bool read_fast(const Element& e, int64_t index_limit, PolygonMesh& mesh) {
    switch (e.kind) {
    case Kind::vertex: return !swap_ && read_float_vertices(e, mesh.positions);
    case Kind::face: return !swap_ && read_byte_counted_faces(e, index_limit, mesh);
    case Kind::tristrips:
    case Kind::edge: return false;
    case Kind::other: return skip_fixed_size(e);
    }
    return false;
  }

private:
  const char* take(size_t size) {
    if (bytes_left() < size) fail(ends_early(*element_));
    const char* at = p_;
    p_ += size;
    return at;
  }
  // The bytes of one record of an element without lists; refuses a body too short for
  // all of them (before anything is allocated for them).
  size_t fixed_record_size(const Element& e) {
    size_t size = 0;
    for (const Property& p : e.properties) size += size_of(p.type);
    if (const size_t fit = bytes_left() / size; e.count > fit) {
      begin(e, fit);
      fail(ends_early(e));
    }
    return size;
  }
  // Records of fixed size with float x, y, z: copied, not converted value by value.
  bool read_float_vertices(const Element& e, std::vector<Vec3>& positions) {
    if (e.has_lists()) return false;
    size_t offset[3] = {};
    size_t at = 0;
    for (const Property& p : e.properties) {
      if (p.role != Role::none) {
        if (p.type != Scalar::float32) return false;
        offset[int(p.role)] = at;
      }
      at += size_of(p.type);
    }
    const size_t stride = fixed_record_size(e);
    positions.resize(e.count);
    if (stride == sizeof(Vec3) && offset[0] == 0 && offset[1] == 4 && offset[2] == 8 && e.count <= INT32_MAX) {
      for_chunks(int32_t(e.count), [&](int32_t, int32_t begin, int32_t end) {
        if (end > begin) std::memcpy(&positions[size_t(begin)], p_ + size_t(begin) * stride, size_t(end - begin) * stride);
      });
    } else {
      for (size_t i = 0; i < e.count; ++i) {
        const char* record = p_ + i * stride;
        std::memcpy(&positions[i].x, record + offset[0], 4);
        std::memcpy(&positions[i].y, record + offset[1], 4);
        std::memcpy(&positions[i].z, record + offset[2], 4);
      }
    }
    p_ += e.count * stride;
    if (const int64_t bad = first_non_finite(positions); bad >= 0) {
      begin(e, uint64_t(bad));
      fail(non_finite_coordinate(positions[size_t(bad)]));
    }
    return true;
  }
  // Faces whose one property is a list of int or uint indices with a uchar length:
  // what nearly every writer produces. Faces all of one size (a triangle or quad mesh)
  // have records of one length, which are checked and copied in parallel; otherwise a
  // first pass finds the sizes and checks the bounds, so the corners are allocated once
  // and copied in the second.
  bool read_byte_counted_faces(const Element& e, int64_t index_limit, PolygonMesh& mesh) {
    if (e.properties.size() != 1) return false;
    const Property& list = e.properties[0];
    if (list.count_type != Scalar::uint8 || (list.type != Scalar::int32 && list.type != Scalar::uint32)) return false;
    if (!read_same_size_faces(e, mesh)) read_any_size_faces(e, mesh);
    // A uint index above INT32_MAX reads as negative, which the unsigned comparison
    // catches too.
    const auto out_of_range = [&](int32_t v) { return uint32_t(v) >= uint64_t(index_limit); };
    const std::span<const int32_t> corners = mesh.face_vertices;
    bool bad = false;
    for_chunks(int32_t(corners.size()), [&](int32_t, int32_t begin, int32_t end) {
      bool here = false; // one branch-free sweep a chunk
      for (int32_t c = begin; c < end; ++c) here |= out_of_range(corners[size_t(c)]);
      if (here) std::atomic_ref<bool>(bad).store(true, std::memory_order_relaxed);
    });
    if (bad) {
      for (size_t c = 0;; ++c)
        if (const int32_t v = corners[c]; out_of_range(v)) {
          const auto f = std::upper_bound(mesh.face_start.begin(), mesh.face_start.end(), int32_t(c)) - 1;
          begin(e, uint64_t(f - mesh.face_start.begin()));
          fail(index_out_of_range(list.type == Scalar::uint32 ? int64_t(uint32_t(v)) : int64_t(v), index_limit));
        }
    }
    return true;
  }
  // The parallel case: false, having read nothing, unless every record has the first
  // one's size (at least 3) and the body holds them all.
  bool read_same_size_faces(const Element& e, PolygonMesh& mesh) {
    if (e.count == 0 || p_ == end_) return false;
    const size_t size = static_cast<unsigned char>(*p_);
    const size_t record = 1 + 4 * size;
    if (size < 3 || e.count > bytes_left() / record || !too_many(e.count * size, "face corners").empty()) return false;
    const int32_t faces = int32_t(e.count);
    bool mixed = false;
    for_chunks(faces, [&](int32_t, int32_t begin, int32_t end) {
      bool here = false;
      for (int32_t f = begin; f < end; ++f) here |= static_cast<unsigned char>(p_[size_t(f) * record]) != size;
      if (here) std::atomic_ref<bool>(mixed).store(true, std::memory_order_relaxed);
    });
    if (mixed) return false;
    mesh.face_start.resize(e.count + 1);
    mesh.face_vertices.resize(e.count * size);
    for_chunks(faces, [&](int32_t, int32_t begin, int32_t end) {
      for (int32_t f = begin; f < end; ++f) {
        // A constant size lets the compiler copy a triangle in two moves instead of a loop.
        int32_t* out = mesh.face_vertices.data() + size_t(f) * size;
        const char* in = p_ + size_t(f) * record + 1;
        if (size == 3)
          std::memcpy(out, in, 12);
        else
          std::memcpy(out, in, 4 * size);
        mesh.face_start[size_t(f) + 1] = int32_t(size_t(f + 1) * size);
      }
    });
    p_ += e.count * record;
    return true;
  }
  void read_any_size_faces(const Element& e, PolygonMesh& mesh) {
    size_t corners = 0;
    const char* q = p_;
    for (uint64_t f = 0; f < e.count; ++f) {
      begin(e, f);
      if (q == end_) fail(ends_early(e));
      const size_t size = static_cast<unsigned char>(*q);
      if (size < 3) fail(too_few_vertices(int64_t(size)));
      if (size_t(end_ - q) - 1 < 4 * size) fail(ends_early(e));
      q += 1 + 4 * size;
      corners += size;
    }
    if (const std::string message = too_many(corners, "face corners"); !message.empty()) fail_input(name_, message);
    mesh.face_start.resize(e.count + 1);
    mesh.face_vertices.resize(corners);
    int32_t* out = mesh.face_vertices.data();
    for (size_t f = 0; f < e.count; ++f) {
      const size_t size = static_cast<unsigned char>(*p_);
      std::memcpy(out, p_ + 1, 4 * size);
      p_ += 1 + 4 * size;
      out += size;
      mesh.face_start[f + 1] = int32_t(out - mesh.face_vertices.data());
    }
  }
  bool skip_fixed_size(const Element& e) {
    if (e.has_lists()) return false;
    // Records without properties take no bytes, however many there are.
    if (!e.properties.empty()) p_ += e.count * fixed_record_size(e);
    return true;
  }

  const char* p_;
  const char* end_;
  bool swap_;
  std::string_view name_;
  const Element* element_ = nullptr;
  uint64_t index_ = 0;
};

// The values of an ascii body: numbers separated by any space.
class TextSource {
public:
  explicit TextSource(TextCursor& in) : in_(in) {}

  void begin(const Element& e, uint64_t index) {
    element_ = &e;
    index_ = index;
  }
  float coordinate(Scalar) {
    next();
    return in_.real("vertex coordinate");
  }
  int64_t integer(Scalar, std::string_view what) {
    next();
    return in_.integer(what);
  }
  void skip(Scalar, int64_t count) {
    for (int64_t k = 0; k < count; ++k) {
      next();
      in_.skip_number("value");
    }
  }
  size_t bytes_left() const { return in_.bytes_left(); }
  // A digit and a separator.
  static size_t value_bytes(Scalar) { return 2; }
  [[noreturn]] void fail(std::string_view message) const {
    in_.fail(record_label(*element_, index_) + ": " + std::string(message));
  }

private:
  void next() {
    in_.skip_space();
    if (in_.at_end()) fail(ends_early(*element_));
  }

  TextCursor& in_;
  const Element* element_ = nullptr;
  uint64_t index_ = 0;
};

// How many records of e the rest of the body can hold at the least: a bound on what to
// reserve, since the header's count is only a claim.
template <class Source> size_t records_that_fit(const Source& in, const Element& e) {
  size_t least = 0;
  for (const Property& p : e.properties) {
    least += p.count_type ? Source::value_bytes(*p.count_type) : Source::value_bytes(p.type);
    if (p.role == Role::indices) least += 3 * Source::value_bytes(p.type);
  }
  return size_t(std::min<uint64_t>(e.count, in.bytes_left() / least));
}

// The triangles of a strip record: index -1 restarts the strip; every other triangle is
// wound backwards so that all agree; triangles with a repeated vertex, which strips use
// to turn corners and to join strips, are not faces and are left out.
template <class Source>
void read_strip(Source& in, const Property& p, int64_t index_limit, PolygonMesh& mesh) {
  const int64_t size = in.integer(*p.count_type, "list length");
  if (size < 0) in.fail("negative list length " + std::to_string(size));
  int32_t last[2] = {-1, -1};
  int64_t in_strip = 0;
  for (int64_t k = 0; k < size; ++k) {
    const int64_t index = in.integer(p.type, "vertex index");
    if (index == -1) {
      in_strip = 0;
      continue;
    }
    if (index < 0 || index >= index_limit) in.fail(index_out_of_range(index, index_limit));
    const int32_t v = int32_t(index);
    if (in_strip >= 2 && last[0] != last[1] && last[1] != v && v != last[0]) {
      if (in_strip % 2 == 0)
        mesh.face_vertices.insert(mesh.face_vertices.end(), {last[0], last[1], v});
      else
        mesh.face_vertices.insert(mesh.face_vertices.end(), {last[1], last[0], v});
      if (mesh.face_vertices.size() > size_t(max_count)) in.fail(too_many(mesh.face_vertices.size(), "face corners"));
      mesh.face_start.push_back(int32_t(mesh.face_vertices.size()));
    }
    last[0] = last[1];
    last[1] = v;
    ++in_strip;
  }
}

// Reads (vertex, face, tristrips, edge) or skips (others) an element value by value: any
// layout, any types, either body encoding. Edges go to `edges`, 2 vertex ids each.
template <class Source>
void read_element(Source& in, const Element& e, int64_t index_limit, PolygonMesh& mesh, std::vector<int32_t>& edges) {
  // Records without properties take no bytes: nothing to read, however many.
  if (e.properties.empty()) return;
  if (e.kind == Kind::vertex) mesh.positions.reserve(records_that_fit(in, e));
  if (e.kind == Kind::face) {
    mesh.face_start.reserve(records_that_fit(in, e) + 1);
    mesh.face_vertices.reserve(3 * records_that_fit(in, e));
  }
  if (e.kind == Kind::edge) edges.reserve(2 * records_that_fit(in, e));
  for (uint64_t i = 0; i < e.count; ++i) {
    in.begin(e, i);
    float point[3] = {};
    int32_t ends[2] = {};
    for (const Property& p : e.properties) {
      if (p.role == Role::vertex1 || p.role == Role::vertex2) {
        const int64_t index = in.integer(p.type, "vertex index");
        if (index < 0 || index >= index_limit) in.fail(index_out_of_range(index, index_limit));
        ends[p.role == Role::vertex2] = int32_t(index);
      } else if (p.role == Role::indices && e.kind == Kind::tristrips) {
        read_strip(in, p, index_limit, mesh);
      } else if (p.role == Role::indices) {
        const int64_t size = in.integer(*p.count_type, "list length");
        if (size < 3) in.fail(too_few_vertices(size));
        for (int64_t k = 0; k < size; ++k) {
          const int64_t index = in.integer(p.type, "vertex index");
          if (index < 0 || index >= index_limit) in.fail(index_out_of_range(index, index_limit));
          mesh.face_vertices.push_back(int32_t(index));
        }
      } else if (p.count_type) {
        const int64_t length = in.integer(*p.count_type, "list length");
        if (length < 0) in.fail("negative list length " + std::to_string(length));
        in.skip(p.type, length);
      } else if (p.role == Role::none) {
        in.skip(p.type, 1);
      } else {
        point[int(p.role)] = in.coordinate(p.type);
      }
    }
    if (e.kind == Kind::vertex) mesh.positions.push_back({point[0], point[1], point[2]});
    if (e.kind == Kind::face) mesh.face_start.push_back(int32_t(mesh.face_vertices.size()));
    if (e.kind == Kind::edge) edges.insert(edges.end(), {ends[0], ends[1]});
  }
}

template <class Source>
void read_body(Source& in, const Header& header, std::string_view name, PolygonMesh& mesh, std::vector<int32_t>& edges) {
  bool vertices_read = false, faces_first = false;
  for (const Element& e : header.elements) {
    // Faces and edges before vertices are checked against the count once it is known.
    const int64_t index_limit = vertices_read ? mesh.num_vertices() : max_count;
    faces_first |= (e.kind == Kind::face || e.kind == Kind::tristrips || e.kind == Kind::edge) && !vertices_read;
    bool done = false;
    if constexpr (std::is_same_v<Source, BinarySource>) done = in.read_fast(e, index_limit, mesh);
    if (!done) read_element(in, e, index_limit, mesh, edges);
    vertices_read |= e.kind == Kind::vertex;
  }
  if (!faces_first) return;
  for (int32_t f = 0; f < mesh.num_faces(); ++f)
    for (int32_t v : mesh.face(f))
      if (v >= mesh.num_vertices())
        fail_input(name, "face " + std::to_string(f) + ": " + index_out_of_range(v, mesh.num_vertices()));
  for (size_t c = 0; c < edges.size(); ++c)
    if (edges[c] >= mesh.num_vertices())
      fail_input(name, "edge " + std::to_string(c / 2) + ": " + index_out_of_range(edges[c], mesh.num_vertices()));
}

// Reads the body of a PLY file: the mesh's positions and faces, or edges.
void read_ply_body(std::string_view bytes, const Header& header, std::string_view name, PolygonMesh& mesh,
                   std::vector<int32_t>& edges) {
  const std::string_view body = bytes.substr(header.body_offset);
  if (header.encoding == Encoding::ascii) {
    TextCursor cursor(body, name, header.body_line);
    TextSource in(cursor);
    read_body(in, header, name, mesh, edges);
    cursor.skip_space();
    if (!cursor.at_end()) cursor.fail("unexpected " + quoted(cursor.word()) + " after the last element");
  } else {
    const bool swap = (header.encoding == Encoding::binary_big_endian) == host_is_little_endian;
    BinarySource in(body, swap, name);
    read_body(in, header, name, mesh, edges);
  }
}

} // namespace

PolygonMesh read_ply(std::string_view bytes, std::string_view name) {
  const Header header = read_header(bytes, Target::mesh, name);
  PolygonMesh mesh;
  std::vector<int32_t> no_edges;
  read_ply_body(bytes, header, name, mesh, no_edges);
  require_faces(mesh, name);
  return mesh;
}

Polylines read_ply_polylines(std::string_view bytes, std::string_view name) {
  const Header header = read_header(bytes, Target::polylines, name);
  PolygonMesh vertices;
  std::vector<int32_t> edges;
  read_ply_body(bytes, header, name, vertices, edges);
  return chain_edges(vertices.positions, edges, name);
}

void write_ply(const PolygonMesh& mesh, const MeshWriteOptions& options, Sink& out) {
  int32_t largest_face = 0;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) largest_face = std::max(largest_face, mesh.face_size(f));
  // A uchar length, as every reader expects, unless a face is too large for it.
  const bool wide_lengths = largest_face > 255;
  out.text(options.ascii ? "ply\nformat ascii 1.0\n" : "ply\nformat binary_little_endian 1.0\n");
  out.text("element vertex ");
  out.integer(mesh.num_vertices());
  out.text("\nproperty float x\nproperty float y\nproperty float z\nelement face ");
  out.integer(mesh.num_faces());
  out.text(wide_lengths ? "\nproperty list uint int vertex_indices\n" : "\nproperty list uchar int vertex_indices\n");
  out.text("end_header\n");
  if (options.ascii) {
    for (const Vec3& p : mesh.positions) write_point_line(out, p);
    for (int32_t f = 0; f < mesh.num_faces(); ++f) write_counted_indices(out, mesh.face(f));
    return;
  }
  write_binary_points(out, mesh.positions);
  const size_t length_bytes = wide_lengths ? 4 : 1;
  write_blocks(out, mesh.num_faces(), 1 << 16, [&](int64_t begin, int64_t end, std::vector<char>& bytes) {
    const size_t corners = size_t(mesh.face_start[size_t(end)] - mesh.face_start[size_t(begin)]);
    bytes.resize(length_bytes * size_t(end - begin) + 4 * corners);
    char* at = bytes.data();
    for (int64_t f = begin; f < end; ++f) {
      const std::span<const int32_t> face = mesh.face(int32_t(f));
      if (wide_lengths)
        store_little_endian(at, uint32_t(face.size()));
      else
        store_little_endian(at, uint8_t(face.size()));
      at += length_bytes;
      for (const int32_t v : face) {
        store_little_endian(at, v);
        at += 4;
      }
    }
  });
}

} // namespace meander::io
