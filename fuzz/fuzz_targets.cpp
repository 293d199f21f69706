#include "fuzz_targets.h"

#include "meander/check.h"
#include "meander/duotone.h"
#include "meander/error.h"
#include "meander/pipeline.h"
#include "meander/parameters.h"
#include "meander/studio.h"
#include "meander/textured_io.h"
#include "meander/wire.h"
#include "studio_server.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <string_view>
#include <unistd.h>

namespace meander::fuzz {

namespace {

// Takes the input a value at a time; past the end every value is 0, so that any input,
// however short, is a complete recipe.
class Bytes {
public:
  explicit Bytes(std::span<const uint8_t> bytes) : bytes_(bytes) {}
  bool empty() const { return bytes_.empty(); }
  uint8_t byte() {
    if (bytes_.empty()) return 0;
    const uint8_t b = bytes_[0];
    bytes_ = bytes_.subspan(1);
    return b;
  }
  template <class T> T value() {
    uint8_t raw[sizeof(T)] = {};
    for (uint8_t& b : raw) b = byte();
    T v;
    std::memcpy(&v, raw, sizeof(T));
    return v;
  }

private:
  std::span<const uint8_t> bytes_;
};

// What io.h promises of a mesh a reader returns, and check.h of one repair returns
// (which also needs no unused vertex); "" when it holds.
std::string mesh_problem(const PolygonMesh& mesh, bool repaired) {
  const auto& start = mesh.face_start;
  if (start.size() < 2 || start.front() != 0 || size_t(start.back()) != mesh.face_vertices.size())
    return "face_start does not span face_vertices";
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    if (mesh.face_size(f) < 3) return "face " + std::to_string(f) + " has fewer than 3 vertices";
    for (int32_t v : mesh.face(f))
      if (v < 0 || v >= mesh.num_vertices()) return "face " + std::to_string(f) + ": index out of range";
  }
  for (const Vec3& p : mesh.positions)
    if (!is_finite(p)) return "a position is not finite";
  if (!repaired) return {};
  const MeshReport r = inspect(mesh);
  if (r.degenerate_faces || r.duplicate_faces || r.non_manifold_edges || r.non_manifold_vertices ||
      r.unreferenced_vertices || r.out_of_range_indices || r.non_finite_positions)
    return "repair left a problem that inspect() reports";
  for (size_t k = 0; k < r.components.size(); ++k)
    if (r.components[k].orientable && r.components[k].misoriented_edges > 0)
      return "repair left orientable component " + std::to_string(k) + " misoriented";
  return {};
}

// Repairs a mesh and checks what comes out, including that a second repair finds nothing.
std::string repair_problem(const PolygonMesh& mesh, RepairResult& result) {
  result = repair(mesh, "fuzz");
  if (std::string problem = mesh_problem(result.mesh, true); !problem.empty()) return problem;
  if (const RepairResult again = repair(result.mesh, "fuzz"); !again.repairs.empty())
    return "a repaired mesh needs another repair: " + again.repairs.front();
  return {};
}

// A small mesh of arbitrary faces of 3 to 5 corners on points of a 4x4x4 grid: finite,
// often coplanar or collinear, sometimes coincident.
PolygonMesh grid_mesh(Bytes& bytes) {
  PolygonMesh mesh;
  mesh.positions.resize(4 + bytes.byte() % 24);
  for (Vec3& p : mesh.positions) {
    const uint8_t b = bytes.byte();
    p = {float(b & 3), float((b >> 2) & 3), float((b >> 4) & 3)};
  }
  const int faces = 1 + bytes.byte() % 48;
  for (int f = 0; f < faces; ++f) {
    std::vector<int32_t> face(3 + bytes.byte() % 3);
    for (int32_t& v : face) v = bytes.byte() % mesh.num_vertices();
    mesh.add_face(face);
  }
  return mesh;
}

// What check_appearance says of a textured mesh Meander made ("" when it fits): a
// refusal there is a finding, not a correct refusal of the input.
std::string appearance_problem(const TexturedMesh& textured) {
  try {
    check_appearance(textured.mesh, textured.appearance, "fuzz");
    return {};
  } catch (const UsageError& e) {
    return e.what();
  }
}

template <class F> std::string refusals_pass(F body) {
  try {
    return body();
  } catch (const Error&) {
    return {};
  }
}

} // namespace

std::string read_mesh_target(std::span<const uint8_t> bytes, MeshFormat format) {
  return refusals_pass([&] {
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    const PolygonMesh mesh = read_mesh(text, format, "fuzz");
    if (std::string problem = mesh_problem(mesh, false); !problem.empty()) return "read_mesh: " + problem;
    inspect(mesh);
    RepairResult repaired;
    return repair_problem(mesh, repaired);
  });
}

std::string repair_target(std::span<const uint8_t> input) {
  Bytes bytes(input);
  PolygonMesh mesh;
  // Few vertices, so that faces meet often: fans, bow-ties, duplicates, flipped faces.
  mesh.positions.resize(bytes.byte() % 16);
  for (Vec3& p : mesh.positions) p = {bytes.value<float>(), bytes.value<float>(), bytes.value<float>()};
  const int faces = bytes.byte() % 32;
  for (int f = 0; f < faces && !bytes.empty(); ++f) {
    std::vector<int32_t> face(bytes.byte() % 8);
    // Mostly small indices, sometimes any int32 (negative, huge).
    for (int32_t& v : face) v = bytes.byte() == 0xff ? bytes.value<int32_t>() : bytes.byte() % 20;
    mesh.add_face(face);
  }
  inspect(mesh);
  return refusals_pass([&] {
    RepairResult repaired;
    return repair_problem(mesh, repaired);
  });
}

std::string curve_target(std::span<const uint8_t> input) {
  Bytes bytes(input);
  CurveJob job;
  job.quadrangulation = Quadrangulation(bytes.byte() % 3);
  job.cycle.tree = TreeStrategy(bytes.byte() % 5); // all five strategies, shaped too
  job.cycle.seed = bytes.byte();
  job.curve.smoothing = Smoothing(bytes.byte() % 3);
  job.curve.samples = 1 + bytes.byte() % 4;
  // As `meander wire --method variable` makes it: polygons split, caps flipped, needles
  // and folds collapsed.
  if (bytes.byte() % 2) job.slab_mesh = SlabMeshOptions{};
  PolygonMesh mesh = grid_mesh(bytes);
  return refusals_pass([&]() -> std::string {
    RepairResult repaired;
    if (std::string problem = repair_problem(mesh, repaired); !problem.empty()) return problem;
    const size_t components = inspect(repaired.mesh).components.size();
    const CurveResult result = make_curve(std::move(repaired.mesh), std::move(repaired.connectivity), job);
    const QuadMesh& quads = result.quads;
    const TriangleCycle& cycle = result.cycle;
    if (std::string problem = verify_cycle(quads, cycle); !problem.empty()) return "verify_cycle: " + problem;
    // The same again without the library's verifier: the triangles are distinct, and
    // neighbours in each cycle share at least two vertices (all three where two quads have
    // the same corners, as on a projective plane of three quads).
    if (std::set<int32_t>(cycle.order.begin(), cycle.order.end()).size() != cycle.order.size())
      return "a triangle appears twice in the cycles";
    for (int32_t k = 0; k < cycle.num_cycles(); ++k) {
      const int32_t first = cycle.cycle_start[size_t(k)], end = cycle.cycle_start[size_t(k) + 1];
      for (int32_t i = first; end - first > 1 && i < end; ++i) {
        auto a = cycle_triangle(quads, cycle.order[size_t(i)]);
        auto b = cycle_triangle(quads, cycle.order[size_t(i + 1 < end ? i + 1 : first)]);
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        std::vector<int32_t> shared;
        std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(shared));
        if (shared.size() < 2)
          return "cycle " + std::to_string(k) + ": triangles " + std::to_string(i - first) + " and the next share " +
                 std::to_string(shared.size()) + " vertices";
      }
    }
    if (size_t(cycle.num_cycles()) != components)
      return std::to_string(cycle.num_cycles()) + " cycles for " + std::to_string(components) + " components";
    if (result.curves.size() != cycle.num_cycles()) return "not one curve per cycle";
    for (const Vec3& p : result.curves.points)
      if (!is_finite(p)) return "a curve point is not finite";
    return {};
  });
}

std::string wire_target(std::span<const uint8_t> input) {
  Bytes bytes(input);
  const bool variable = bytes.byte() % 2;
  const WireShape shape = WireShape(bytes.byte() % 2);
  CurveJob job{.cycle = {.tree = TreeStrategy(bytes.byte() % 5), .seed = bytes.byte()},
               .curve = {.smoothing = Smoothing(bytes.byte() % 3), .samples = 1 + bytes.byte() % 3}};
  ConstantWireOptions constant{.shape = shape, .sides = 3 + bytes.byte() % 6, .curve = job.curve};
  if (const uint8_t r = bytes.byte(); r != 0) constant.radius = r / 256.0; // 0: auto
  const VariableWireOptions options{.shape = shape, .s = bytes.byte() / 255.0, .t = bytes.byte() / 255.0,
                                    .thickness = (bytes.byte() % 4) * 0.05, .levels = bytes.byte() % 3};
  // As `meander wire --method variable` prepares the mesh for its slabs.
  if (variable) job.slab_mesh = SlabMeshOptions{};
  PolygonMesh mesh = grid_mesh(bytes);
  return refusals_pass([&]() -> std::string {
    RepairResult repaired;
    if (std::string problem = repair_problem(mesh, repaired); !problem.empty()) return problem;
    const CurveResult curve = make_curve(std::move(repaired.mesh), std::move(repaired.connectivity), job);
    const int64_t triangles = curve.cycle.num_triangles();
    PolygonMesh wire;
    int64_t expected = 0;
    if (variable) {
      wire = variable_wire(curve.quads, curve.cycle, options).mesh;
      expected = variable_wire_triangles(triangles, options);
    } else {
      ConstantWire made = constant_wire(curve.quads, curve.cycle, constant);
      // No radius avoids a self-intersection: no wire, and the radius says so.
      if (made.mesh.num_faces() == 0) return made.radius == 0 && !constant.radius ? "" : "an empty wire of a given radius";
      wire = std::move(made.mesh);
      expected = constant_wire_triangles(triangles, constant);
    }
    if (std::string problem = mesh_problem(wire, false); !problem.empty()) return "wire: " + problem;
    int64_t made = 0;
    for (int32_t f = 0; f < wire.num_faces(); ++f) made += wire.face_size(f) - 2;
    if (made != expected)
      return "the wire has " + std::to_string(made) + " triangles, not the " + std::to_string(expected) + " announced";
    return {};
  });
}

std::string duotone_target(std::span<const uint8_t> input) {
  Bytes bytes(input);
  const DuotoneOptions options{.quadrangulation = Quadrangulation(bytes.byte() % 3),
                               .rule = DuotoneRule(bytes.byte() % 2),
                               .tree = TreeStrategy(bytes.byte() % 4),
                               .seed = bytes.byte()};
  const TileOptions tiles{.style = TileStyle(bytes.byte() % 5), .texture_size = 64};
  const PolygonMesh mesh = grid_mesh(bytes);
  return refusals_pass([&]() -> std::string {
    RepairResult repaired;
    if (std::string problem = repair_problem(mesh, repaired); !problem.empty()) return problem;
    const size_t components = inspect(repaired.mesh).components.size();
    const Duotone d = make_duotone(repaired.mesh, repaired.connectivity, options);
    for (int32_t q = 0; q < d.quads.num_quads(); ++q) {
      if (d.quads.is_half(q)) continue;
      const auto& c = d.quads.quads[size_t(q)];
      for (int k = 0; k < 4; ++k)
        if (d.color[size_t(c[size_t(k)])] == d.color[size_t(c[size_t((k + 1) % 4)])])
          return "quad " + std::to_string(q) + ": a side joins two corners of one colour";
    }
    if (size_t(d.cycle.num_cycles()) != components)
      return std::to_string(d.cycle.num_cycles()) + " separating loops for " + std::to_string(components) + " components";
    const Polylines curves = separating_curves(d, tiles.style);
    if (size_t(curves.size()) != components) return "not one separating curve per component";
    for (const Vec3& p : curves.points)
      if (!is_finite(p)) return "a separating curve's point is not finite";
    for (const PolygonMesh& region : duotone_regions(d, tiles.style))
      if (region.num_faces() > 0)
        if (std::string problem = mesh_problem(region, false); !problem.empty()) return "region: " + problem;
    return appearance_problem(duotone_surface(d, tiles));
  });
}

std::string textured_obj_target(std::span<const uint8_t> input) {
  // A folder of this process's own, with a texture that map_Kd may name.
  static const struct Folder {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("meander_fuzz_obj_" + std::to_string(::getpid()));
    Folder() {
      std::filesystem::create_directories(path);
      write_png({.width = 2, .height = 1, .has_alpha = true, .rgba = {255, 0, 0, 255, 0, 0, 255, 128}}, path / "t.png");
    }
    ~Folder() { std::filesystem::remove_all(path); }
  } folder;
  const std::string_view all(reinterpret_cast<const char*>(input.data()), input.size());
  const size_t split = std::min(all.find('\0'), all.size());
  // Plain writes: through atomic files (a temporary file renamed) this target ran 12 times slower.
  const auto put = [&](const char* name, std::string_view bytes) {
    std::ofstream(folder.path / name, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
  };
  put("m.mtl", all.substr(std::min(split + 1, all.size())));
  put("f.obj", all.substr(0, split));
  return refusals_pass([&]() -> std::string {
    const TexturedMesh textured = read_textured_mesh(folder.path / "f.obj");
    if (std::string problem = mesh_problem(textured.mesh, false); !problem.empty()) return "mesh: " + problem;
    return appearance_problem(textured);
  });
}

std::string image_target(std::span<const uint8_t> input) {
  return refusals_pass([&]() -> std::string {
    const Texture t = read_texture({reinterpret_cast<const char*>(input.data()), input.size()}, "fuzz");
    if (t.width < 1 || t.height < 1 || t.rgba.size() != size_t(t.width) * size_t(t.height) * 4)
      return "a " + std::to_string(t.width) + "x" + std::to_string(t.height) + " texture of " +
             std::to_string(t.rgba.size()) + " bytes";
    return {};
  });
}

std::string make_request_target(std::span<const uint8_t> bytes) {
  MakeRequest request;
  try {
    request = parse_make_request({reinterpret_cast<const char*>(bytes.data()), bytes.size()});
  } catch (const UsageError&) {
    return {};
  }
  // What the parser accepts, the jobs take.
  try {
    check_parameters(request.params.wire);
    check_parameters(request.params.duotone);
  } catch (const UsageError& e) {
    return std::string("accepted a value the job refuses: ") + e.what();
  }
  return {};
}

std::string upload_target(std::span<const uint8_t> input) {
  const std::string_view all(reinterpret_cast<const char*>(input.data()), input.size());
  const size_t newline = std::min(all.find('\n'), all.size());
  return refusals_pass([&] {
    // As the server reads an upload, its picture size bounded as the server's default does.
    const StudioSurface surface = load_studio_surface(all.substr(0, newline), all.substr(std::min(newline + 1, all.size())),
                                                      0, StudioServerOptions{}.max_pixels);
    if (!surface.picture.empty())
      return surface.picture.rgba.size() == size_t(surface.picture.width) * size_t(surface.picture.height) * 4
                 ? std::string()
                 : "a picture whose pixels are not width x height x 4 bytes";
    return mesh_problem(surface.repaired.mesh, true);
  });
}

std::string http_target(std::span<const uint8_t> bytes) {
  // One server for the whole run, its limits small enough that no request's work takes
  // long; sessions come and go as the inputs make them.
  static StudioServer server(
      {.port = 0, .max_upload = size_t(1) << 20, .max_faces = 5'000, .max_pixels = 1 << 16, .max_result = 50'000});
  static const std::string cube = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                  "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  static const std::string upload_body = "--b\r\nContent-Disposition: form-data; name=\"mesh\"; filename=\"cube.obj\"\r\n\r\n" +
                                         cube + "\r\n--b--\r\n";
  static const std::string upload = "POST /api/mesh HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: multipart/form-data; "
                                    "boundary=b\r\nContent-Length: " +
                                    std::to_string(upload_body.size()) + "\r\n\r\n" + upload_body;
  const std::string made = server.serve_bytes(upload);
  const size_t made_body = made.find("\r\n\r\n");
  if (!made.starts_with("HTTP/1.1 200 ") || made_body == std::string::npos) return "the cube's upload failed: " + made;
  const std::string session = nlohmann::json::parse(made.substr(made_body + 4))["session"];

  std::string input(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  constexpr std::string_view placeholder = "SESSION-ID-OF-THE-FUZZ-TARGET-00";
  for (size_t at = input.find(placeholder); at != std::string::npos; at = input.find(placeholder, at))
    input.replace(at, placeholder.size(), session);
  const std::string answer = server.serve_bytes(input);

  // Answer after answer: a status line, headers, a body of Content-Length bytes (none
  // after a HEAD, which is told by what follows).
  std::string_view rest = answer;
  for (int answers = 1; !rest.empty(); ++answers) {
    if (answers > 100) return "more than 100 answers on one connection";
    if (!rest.starts_with("HTTP/1.1 ") || rest.size() < 13) return "an answer does not start with a status line";
    const int status = std::atoi(std::string(rest.substr(9, 3)).c_str());
    if (status < 100 || status >= 500) return "answer " + std::to_string(answers) + " has status " + std::to_string(status);
    const size_t end = rest.find("\r\n\r\n");
    if (end == std::string::npos) return "an answer's headers do not end";
    const std::string_view headers = rest.substr(0, end + 2);
    size_t length = 0;
    if (const size_t at = headers.find("\r\nContent-Length: "); at != std::string_view::npos)
      length = std::strtoull(headers.data() + at + 18, nullptr, 10);
    rest.remove_prefix(end + 4);
    const bool body_follows = length <= rest.size() && (length == rest.size() || rest.substr(length).starts_with("HTTP/1.1 "));
    if (body_follows) rest.remove_prefix(length);
    else if (!rest.empty() && !rest.starts_with("HTTP/1.1 ")) return "an answer's body is not Content-Length bytes";
  }
  return {};
}

} // namespace meander::fuzz
