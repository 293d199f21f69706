// The Python module `meander._meander` (docs/python.md): meshes and results as numpy
// arrays, the jobs run by the job layer with the same parameters as the CLI and the
// studio (parameters.h). A job runs on a thread of its own without the GIL; the calling
// thread waits for it, passes its progress to the caller's callback and cancels it when
// the callback raises or Python has a signal to deliver (Ctrl-C).
#include "meander/check.h"
#include "meander/drawing.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/jobs.h"
#include "meander/parameters.h"
#include "meander/shapes.h"
#include "meander/textured_io.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cctype>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace py = pybind11;
using namespace pybind11::literals;

namespace meander {
namespace {

// A mesh and the name its messages give it: the file it was read from, or "mesh".
struct Mesh {
  PolygonMesh mesh;
  std::string name = "mesh";
};

// The owner of a result's array, which numpy arrays keep alive as their base: the arrays
// are views of the library's own vectors, moved here, never copied.
template <class Element> py::capsule owner_of(std::vector<Element>&& values, const Element*& data) {
  auto* held = new std::vector<Element>(std::move(values));
  data = held->data();
  return py::capsule(held, [](void* p) { delete static_cast<std::vector<Element>*>(p); });
}

// A numpy array of T (float for Vec3 and TexCoord) over `values`.
template <class T, class Element> py::array_t<T> owned(std::vector<Element>&& values, std::vector<py::ssize_t> shape) {
  static_assert(sizeof(Element) % sizeof(T) == 0);
  const Element* data = nullptr;
  py::capsule owner = owner_of(std::move(values), data);
  return py::array_t<T>(shape, reinterpret_cast<const T*>(data), owner);
}

py::array_t<float> points_array(std::vector<Vec3>&& points) {
  const auto n = py::ssize_t(points.size());
  return owned<float>(std::move(points), {n, 3});
}

// A mesh's faces as an (F, k) array when all have k corners; a ValueError names the
// first face of another size otherwise (the caller uses offsets and indices instead).
py::array_t<int32_t> faces_array(std::vector<int32_t>&& corners, const std::vector<int32_t>& start) {
  const py::ssize_t faces = py::ssize_t(start.size()) - 1;
  const int32_t k = faces > 0 ? start[1] - start[0] : 3;
  for (py::ssize_t f = 1; f < faces; ++f)
    if (start[size_t(f) + 1] - start[size_t(f)] != k)
      throw py::value_error("face " + std::to_string(f) + " has " + std::to_string(start[size_t(f) + 1] - start[size_t(f)]) +
                            " corners and face 0 has " + std::to_string(k) +
                            ": the faces are not all of one size (use offsets and indices)");
  return owned<int32_t>(std::move(corners), {faces, py::ssize_t(k)});
}

std::string type_name(py::handle value) { return py::str(py::type::of(value).attr("__name__")); }

// An array from any array-like (lists, tuples, arrays of any dtype and layout), not copied
// when it already is one.
py::array as_array(py::handle value, const char* what) {
  py::array array = py::array::ensure(value);
  if (!array) throw py::type_error(std::string(what) + ": expected an array, got " + type_name(value));
  return array;
}

// Reads the (N, 3) vertex array into positions: float32 and float64 arrays of any layout
// are read in place (a C-contiguous float32 array is one copy), other numbers converted.
std::vector<Vec3> read_vertices(py::handle value) {
  py::array array = as_array(value, "vertices");
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw py::value_error("vertices: expected an (N, 3) array, got shape " + std::string(py::str(py::tuple(py::cast(
                                                                                std::vector<py::ssize_t>(array.shape(), array.shape() + array.ndim()))))));
  const auto kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::type_error("vertices: expected numbers, got an array of dtype " + std::string(py::str(array.dtype())));
  std::vector<Vec3> positions(size_t(array.shape(0)));
  if (py::isinstance<py::array_t<float, py::array::c_style>>(array) && array.dtype().is(py::dtype::of<float>())) {
    if (!positions.empty()) std::memcpy(positions.data(), array.data(), positions.size() * sizeof(Vec3));
    return positions;
  }
  auto copy = [&](auto view) {
    for (py::ssize_t i = 0; i < view.shape(0); ++i)
      positions[size_t(i)] = {float(view(i, 0)), float(view(i, 1)), float(view(i, 2))};
  };
  if (array.dtype().is(py::dtype::of<float>())) copy(array.unchecked<float, 2>());
  else if (array.dtype().is(py::dtype::of<double>())) copy(array.unchecked<double, 2>());
  else copy(py::array_t<double, py::array::forcecast>(array).unchecked<2>());
  return positions;
}

// Integer arrays of any integer dtype and layout, as int32 indices; `what` names them in
// messages.
std::vector<int32_t> read_indices(py::handle value, const char* what, int dims) {
  py::array array = as_array(value, what);
  if (array.ndim() != dims)
    throw py::value_error(std::string(what) + ": expected a " + std::to_string(dims) + "-dimensional array, got " +
                          std::to_string(array.ndim()) + " dimensions");
  const auto kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u' && !(array.size() == 0 && kind == 'f'))
    throw py::type_error(std::string(what) + ": expected integers, got an array of dtype " + std::string(py::str(array.dtype())));
  const auto wide = py::array_t<int64_t, py::array::forcecast | py::array::c_style>(array);
  std::vector<int32_t> out(size_t(wide.size()));
  const int64_t* data = wide.data();
  for (size_t i = 0; i < out.size(); ++i) {
    if (data[i] < 0 || data[i] > INT32_MAX)
      throw py::value_error(std::string(what) + ": entry " + std::to_string(i) + " is " + std::to_string(data[i]) +
                            " (expected 0 .. " + std::to_string(INT32_MAX) + ")");
    out[i] = int32_t(data[i]);
  }
  return out;
}

// A mesh from numpy arrays: faces an (F, k) array of vertex indices, a list of faces of
// any sizes, or with `offsets` (F + 1 entries from 0) a flat array of corners.
Mesh mesh_from_arrays(py::handle vertices, py::handle faces, py::handle offsets, std::string name) {
  Mesh m{.name = std::move(name)};
  m.mesh.positions = read_vertices(vertices);
  PolygonMesh& mesh = m.mesh;
  if (!offsets.is_none()) {
    mesh.face_vertices = read_indices(faces, "faces", 1);
    mesh.face_start = read_indices(offsets, "offsets", 1);
    if (mesh.face_start.empty() || mesh.face_start.front() != 0 || mesh.face_start.back() != int32_t(mesh.face_vertices.size()))
      throw py::value_error("offsets: expected F + 1 entries from 0 to the number of corners (" +
                            std::to_string(mesh.face_vertices.size()) + ")");
  } else if (py::isinstance<py::array>(faces) || py::isinstance<py::str>(faces) || !py::isinstance<py::sequence>(faces) ||
             py::len(faces) == 0 || !py::isinstance<py::sequence>(faces[py::int_(0)])) {
    py::array array = as_array(faces, "faces");
    if (array.ndim() != 2)
      throw py::value_error("faces: expected an (F, k) array, a list of faces, or a flat array with offsets");
    const auto k = int32_t(array.shape(1));
    mesh.face_vertices = read_indices(array, "faces", 2);
    mesh.face_start.resize(size_t(array.shape(0)) + 1);
    for (size_t f = 0; f < mesh.face_start.size(); ++f) mesh.face_start[f] = int32_t(f) * k;
  } else {
    for (py::handle face : faces) {
      const std::vector<int32_t> corners = read_indices(face, "faces", 1);
      mesh.add_face(corners);
    }
  }
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    if (mesh.face_start[size_t(f) + 1] - mesh.face_start[size_t(f)] < 3)
      throw py::value_error("faces: face " + std::to_string(f) + " has " +
                            std::to_string(mesh.face_start[size_t(f) + 1] - mesh.face_start[size_t(f)]) +
                            " corners (a face has at least 3)");
    for (int32_t v : mesh.face(f))
      if (v >= mesh.num_vertices())
        throw py::value_error("faces: face " + std::to_string(f) + " uses vertex " + std::to_string(v) + ", but the mesh has " +
                              std::to_string(mesh.num_vertices()) + " vertices");
  }
  return m;
}

// Curves as a list of (N, 3) arrays, one per curve, views of the points of all.
py::list curves_list(Polylines&& curves) {
  py::list out;
  const Vec3* data = nullptr;
  py::capsule owner = owner_of(std::move(curves.points), data);
  for (int32_t k = 0; k < curves.size(); ++k)
    out.append(py::array_t<float>({py::ssize_t(curves.start[size_t(k) + 1] - curves.start[size_t(k)]), py::ssize_t(3)},
                                  reinterpret_cast<const float*>(data + curves.start[size_t(k)]), owner));
  return out;
}

// Curves from a list of (N, 3) arrays, or one array.
Polylines curves_from(py::handle value) {
  Polylines curves;
  const py::object list = py::isinstance<py::array>(value) ? py::make_tuple(value) : py::reinterpret_borrow<py::object>(value);
  for (py::handle curve : list) {
    const std::vector<Vec3> points = read_vertices(curve);
    curves.points.insert(curves.points.end(), points.begin(), points.end());
    curves.start.push_back(int32_t(curves.points.size()));
  }
  return curves;
}

// The text set_parameter reads for a Python value: None is "none" or "auto" where the
// parameter takes it, True and False are "true" and "false", two colours a list of two.
template <class T> std::string value_text(const Parameter& p, py::handle value) {
  if constexpr (std::is_same_v<T, std::optional<double>>)
    if (value.is_none()) return std::string(p.choices[0]);
  if constexpr (std::is_same_v<T, bool>)
    if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if constexpr (std::is_same_v<T, std::array<Color8, 2>>) {
    if (!py::isinstance<py::str>(value) && py::isinstance<py::sequence>(value)) {
      std::string joined;
      for (py::handle colour : value) joined += (joined.empty() ? "" : ",") + std::string(py::str(colour));
      return joined;
    }
  }
  return py::str(value); // True for a number is "True", which set_parameter refuses
}

// Sets the job's parameters from keyword arguments, as the CLI and the studio read them:
// a length may carry a unit with a model size. An unknown name is a TypeError, as for
// any Python function.
template <class Job> void set_parameters(Job& job, const py::kwargs& values, const char* function) {
  std::vector<std::pair<std::string, py::handle>> given;
  for (auto [key, value] : values) given.emplace_back(py::str(key), value);
  // The model size first: the other lengths' units need it.
  std::stable_partition(given.begin(), given.end(), [](const auto& entry) { return entry.first == parameters::model_size.name; });
  // Whether lengths may carry units: with a model size, and always in a picture's job,
  // whose lengths are millimetres on paper.
  const auto sized = [&] {
    if constexpr (std::is_same_v<Job, WireJob>) return job.curve.model_size.has_value();
    else if constexpr (std::is_same_v<Job, ImageJob>) return true;
    else return job.model_size.has_value();
  };
  for (const auto& [key, value] : given) {
    bool known = false;
    visit_parameters(job, [&](const Parameter& p, auto& field) {
      if (p.name != key) return;
      known = true;
      const std::string text = value_text<std::decay_t<decltype(field)>>(p, value);
      check_unit(p, text, sized(), parameters::model_size.name);
      set_parameter(p, text, field);
    });
    if (!known) throw py::type_error(std::string(function) + "() got an unexpected keyword argument '" + key + "'");
  }
}

// For the tests (meander._hold_next_job): the next job waits at its first check until
// cancelled, so that a test sees it in flight without making it slow.
std::atomic<bool> hold_next_job{false};

// Runs work(progress) on a thread of its own while this one, without the GIL but for
// each look, tells `callback` (stage, fraction or None) what the job is doing, and cancels
// it when the callback raises or a signal is due (KeyboardInterrupt); that exception is
// raised once the job stopped. The job's own exceptions are raised as they are.
template <class Work> auto run_job(py::handle callback, Work&& work) {
  using Result = decltype(work(std::declval<Progress&>()));
  Progress progress;
  if (hold_next_job.exchange(false)) progress.hold();
  std::optional<Result> result;
  std::exception_ptr failure;
  std::optional<py::error_already_set> python_error;
  {
    std::mutex lock;
    std::condition_variable finished;
    bool done = false;
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
        result.emplace(work(progress));
      } catch (...) {
        failure = std::current_exception();
      }
      const std::lock_guard guard(lock);
      done = true;
      finished.notify_all();
    });
    Progress::State told{.stage = "", .fraction = -2};
    std::unique_lock wait(lock);
    while (!finished.wait_for(wait, std::chrono::milliseconds(50), [&] { return done; })) {
      if (python_error) continue;
      wait.unlock();
      {
        py::gil_scoped_acquire acquire;
        try {
          if (PyErr_CheckSignals() != 0) throw py::error_already_set();
          const Progress::State now = progress.state();
          if (callback && !callback.is_none() && (now.stage != told.stage || now.fraction != told.fraction) && !now.stage.empty()) {
            told = now;
            callback(now.stage, now.fraction < 0 ? py::object(py::none()) : py::float_(now.fraction));
          }
        } catch (py::error_already_set& e) {
          python_error.emplace(std::move(e));
          progress.cancel();
        }
      }
      wait.lock();
    }
    wait.unlock();
    worker.join();
  }
  if (python_error) throw std::move(*python_error);
  if (failure) std::rethrow_exception(failure);
  return std::move(*result);
}

// The library's notes and repairs on a mesh, as Python warnings (meander.MeshWarning).
py::object mesh_warning;
void warn_all(const std::string& name, const std::string& kind, const std::vector<std::string>& lines) {
  for (const std::string& line : lines)
    if (PyErr_WarnEx(mesh_warning.ptr(), (name + ": " + kind + ": " + line).c_str(), 1) != 0) throw py::error_already_set();
}

// work(), its topology refusals naming the mesh, as the CLI's name the file.
template <class F> auto about_mesh(const Mesh& mesh, F&& work) -> decltype(work()) {
  try {
    return work();
  } catch (const TopologyError& e) {
    const std::string message = e.what();
    if (message.starts_with(mesh.name + ":")) throw;
    throw TopologyError(mesh.name + ": " + message);
  }
}

py::object curve(const Mesh& mesh, bool certificate, bool strict, int64_t max_faces, py::handle progress, const py::kwargs& params) {
  CurveJob job;
  set_parameters(job, params, "curve");
  job.max_faces = max_faces;
  check_parameters(job);
  PolygonMesh input = mesh.mesh;
  auto [repairs, notices, made] = run_job(progress, [&](Progress& p) {
    RepairResult r = repair(std::move(input), mesh.name,
                            {.strict = strict, .max_faces = max_faces, .reorder = job.quadrangulation != Quadrangulation::none});
    CurveResult c = about_mesh(mesh, [&] { return make_curve(std::move(r.mesh), std::move(r.connectivity), job, nullptr, &p); });
    return std::tuple(std::move(r.repairs), std::move(r.notices), std::move(c));
  });
  warn_all(mesh.name, "repaired", repairs);
  warn_all(mesh.name, "note", notices);
  py::list curves = curves_list(std::move(made.curves));
  if (!certificate) return curves;
  PolygonMesh triangles = cycle_triangles(made.quads, made.cycle);
  return py::make_tuple(curves, Mesh{std::move(triangles), mesh.name + " (certificate)"},
                        owned<int32_t>(std::vector<int32_t>(made.cycle.cycle_start), {py::ssize_t(made.cycle.cycle_start.size())}));
}

py::object json_object(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

py::tuple wire(const Mesh& mesh, bool strict, int64_t max_faces, py::handle progress, const py::kwargs& params) {
  WireJob job;
  set_parameters(job, params, "wire");
  // As `meander wire`: the variable method starts from the shaped tree unless told.
  if (job.method == WireMethod::variable && !params.contains("tree")) job.curve.cycle.tree = TreeStrategy::shaped;
  check_parameters(job);
  CurveJob curve_job = wire_curve_job(job);
  curve_job.max_faces = max_faces;
  PolygonMesh input = mesh.mesh;
  auto [repairs, notices, notes, made] = run_job(progress, [&](Progress& p) {
    RepairResult r = repair(std::move(input), mesh.name,
                            {.strict = strict, .max_faces = max_faces, .reorder = curve_job.quadrangulation != Quadrangulation::none});
    return about_mesh(mesh, [&] {
      const CurveResult c = make_curve(std::move(r.mesh), std::move(r.connectivity), curve_job, nullptr, &p);
      return std::tuple(std::move(r.repairs), std::move(r.notices), slab_mesh_notes(c, job), make_wire(c, job, nullptr, &p));
    });
  });
  warn_all(mesh.name, "repaired", repairs);
  warn_all(mesh.name, "note", notices);
  warn_all(mesh.name, "note", notes);
  py::object report = json_object(wire_report_json(made, job));
  report["radius"] = made.radius;
  return py::make_tuple(points_array(std::move(made.mesh.positions)),
                        faces_array(std::move(made.mesh.face_vertices), made.mesh.face_start), report);
}

py::tuple duotone(const Mesh& mesh, bool strict, int64_t max_faces, py::handle progress, const py::kwargs& params) {
  DuotoneJob job;
  set_parameters(job, params, "duotone");
  job.max_faces = max_faces;
  check_parameters(job);
  if (job.shell) throw py::value_error("shell: duotone() paints the surface; a two-colour print is duotone_print()'s");
  PolygonMesh input = mesh.mesh;
  auto [repairs, notices, notes, surface, curves] = run_job(progress, [&](Progress& p) {
    RepairResult r = repair(std::move(input), mesh.name, {.strict = strict, .max_faces = max_faces});
    return about_mesh(mesh, [&] {
      const Duotone d = make_duotone(r.mesh, r.connectivity, job, &p);
      return std::tuple(std::move(r.repairs), std::move(r.notices), d.notes, paint_duotone(d, job, {}, nullptr, &p),
                        separating_curves(d, job.tiles.style));
    });
  });
  warn_all(mesh.name, "repaired", repairs);
  warn_all(mesh.name, "note", notices);
  warn_all(mesh.name, "note", notes);
  Texture& texture = surface.appearance.materials.at(0).texture;
  const py::ssize_t corners = py::ssize_t(surface.appearance.texcoords.size());
  return py::make_tuple(points_array(std::move(surface.mesh.positions)),
                        faces_array(std::move(surface.mesh.face_vertices), surface.mesh.face_start),
                        owned<float>(std::move(surface.appearance.texcoords), {corners, 2}),
                        owned<uint8_t>(std::move(texture.rgba), {py::ssize_t(texture.height), py::ssize_t(texture.width), 4}),
                        curves_list(std::move(curves)));
}

// A two-colour print, as `meander duotone --shell`: ([the two solids as Meshes], summary).
py::tuple duotone_print(const Mesh& mesh, bool strict, int64_t max_faces, py::handle progress, const py::kwargs& params) {
  DuotoneJob job;
  set_parameters(job, params, "duotone");
  job.max_faces = max_faces;
  check_parameters(job);
  if (!job.shell) throw py::value_error("shell: a two-colour print needs the wall's thickness (shell=...)");
  PolygonMesh input = mesh.mesh;
  auto [repairs, notices, notes, shell] = run_job(progress, [&](Progress& p) {
    RepairResult r = repair(std::move(input), mesh.name, {.strict = strict, .max_faces = max_faces});
    return about_mesh(mesh, [&] {
      const Duotone d = make_duotone(r.mesh, r.connectivity, job, &p);
      return std::tuple(std::move(r.repairs), std::move(r.notices), d.notes, make_shell(d, job));
    });
  });
  warn_all(mesh.name, "repaired", repairs);
  warn_all(mesh.name, "note", notices);
  warn_all(mesh.name, "note", notes);
  const std::string summary = shell_summary(shell, job);
  py::list solids;
  for (int k = 0; k < 2; ++k) solids.append(Mesh{std::move(shell.solids[size_t(k)]), mesh.name + " colour " + std::to_string(k + 1)});
  return py::make_tuple(solids, summary);
}

// A length on the paper: millimetres, or text with its unit ("10mm", "0.5in"), as the CLI reads it.
double paper_length(const char* name, py::handle value) { return millimetres(name, std::string(py::str(value))); }

// A drawing's paths: (N, 2) arrays in millimetres, a closed one ending on its first point.
py::list drawing_paths(const Drawing& drawing) {
  py::list paths;
  for (int32_t k = 0; k < drawing.size(); ++k) {
    std::vector<double> xy;
    for (int32_t i = drawing.start[size_t(k)]; i < drawing.start[size_t(k) + 1]; ++i)
      xy.insert(xy.end(), {drawing.points[size_t(i)].x, drawing.points[size_t(i)].y});
    if (drawing.closed[size_t(k)]) xy.insert(xy.end(), {xy[0], xy[1]});
    const py::ssize_t n = py::ssize_t(xy.size() / 2);
    paths.append(owned<double>(std::move(xy), {n, 2}));
  }
  return paths;
}

// The drawing of a mesh's curve (made with the curve's parameters, hidden by its surface)
// or of curves (hidden by `occluder`, if given): (paths, svg).
py::tuple draw(py::handle what, py::handle occluder, const std::string& view, bool fit, py::handle camera,
               const std::string& paper, bool landscape, py::handle margin, py::handle pen, py::handle progress,
               const py::kwargs& params) {
  DrawingOptions options{.view = parse_view(view), .framing = fit ? Framing::silhouette : Framing::bounds,
                         .paper = parse_paper(paper, landscape)};
  if (!camera.is_none()) {
    const auto [eye, target, up, fov] = camera.cast<std::tuple<std::array<double, 3>, std::array<double, 3>, std::array<double, 3>, double>>();
    options.camera = CameraPose{.eye = {eye[0], eye[1], eye[2]}, .target = {target[0], target[1], target[2]},
                                .up = {up[0], up[1], up[2]}, .fov_degrees = fov};
  }
  options.paper.margin = paper_length("margin", margin);
  options.pen = paper_length("pen", pen);
  Polylines curves;
  PolygonMesh surface;
  if (py::isinstance<Mesh>(what)) {
    if (!occluder.is_none()) throw py::value_error("occluder: a mesh hides its own curve (give curves to draw with an occluder)");
    const Mesh& mesh = what.cast<const Mesh&>();
    CurveJob job;
    set_parameters(job, params, "draw");
    check_parameters(job);
    PolygonMesh input = mesh.mesh;
    Scene scene = run_job(progress, [&](Progress& p) {
      RepairResult r = repair(std::move(input), mesh.name, {.reorder = job.quadrangulation != Quadrangulation::none});
      return curve_scene(about_mesh(mesh, [&] { return make_curve(std::move(r.mesh), std::move(r.connectivity), job, nullptr, &p); }));
    });
    curves = std::move(scene.curves.at(0).curves);
    surface = std::move(scene.meshes.at(0).mesh);
  } else {
    if (py::len(params) > 0) throw py::type_error("draw(): the curve's parameters need a mesh, not curves");
    curves = curves_from(what);
    if (!occluder.is_none()) surface = occluder.cast<const Mesh&>().mesh;
  }
  Drawing drawing = run_job(py::none(), [&](Progress&) { return draw_curves(curves, surface, options); });
  return py::make_tuple(drawing_paths(drawing), drawing_svg(drawing, options.pen));
}

// A picture from a file's path or from an (H, W), (H, W, 3) or (H, W, 4) array of bytes,
// or of numbers in 0..1.
Texture picture_from(py::handle picture, int64_t max_pixels) {
  if (py::isinstance<py::str>(picture) || py::hasattr(picture, "__fspath__"))
    return read_texture(picture.cast<std::filesystem::path>(), max_pixels);
  const py::array array = as_array(picture, "picture");
  const py::ssize_t channels = array.ndim() == 2 ? 1 : array.ndim() == 3 ? array.shape(2) : 0;
  if (channels != 1 && channels != 3 && channels != 4)
    throw py::value_error("picture: expected an (H, W), (H, W, 3) or (H, W, 4) array, or a file's path");
  const py::ssize_t height = array.shape(0), width = array.shape(1);
  if (max_pixels > 0 && int64_t(width) * height > max_pixels)
    throw py::value_error("picture: " + std::to_string(width) + "x" + std::to_string(height) + " pixels, more than the " +
                          std::to_string(max_pixels) + " allowed");
  Texture t{.width = int32_t(width), .height = int32_t(height)};
  t.rgba.resize(size_t(width) * size_t(height) * 4, 255);
  // Grey to R = G = B; alpha, where given, kept.
  const auto fill = [&](const auto* in, auto byte) {
    for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
      for (size_t c = 0; c < (channels == 1 ? 3 : size_t(channels)); ++c)
        t.rgba[4 * i + c] = byte(in[i * size_t(channels) + (channels == 1 ? 0 : c)]);
  };
  if (array.dtype().is(py::dtype::of<uint8_t>())) { // bytes, read in place when C-contiguous
    const auto bytes = py::array_t<uint8_t, py::array::forcecast | py::array::c_style>(array);
    fill(bytes.data(), [](uint8_t v) { return v; });
  } else { // numbers in 0..1, or other integers as bytes (clamped)
    const double scale = array.dtype().kind() == 'f' ? 255 : 1;
    const auto numbers = py::array_t<double, py::array::forcecast | py::array::c_style>(array);
    fill(numbers.data(), [scale](double v) { return uint8_t(std::lround(std::clamp(v * scale, 0.0, 255.0))); });
  }
  return t;
}

// A picture drawn with one closed line, as `meander image`: (path, svg, duotone svg).
py::tuple image(py::handle picture, py::handle progress, const py::kwargs& params) {
  ImageJob job;
  set_parameters(job, params, "image");
  check_parameters(job);
  const Texture pixels = picture_from(picture, job.max_pixels);
  const LinePicture drawn = run_job(progress, [&](Progress& p) { return make_line_picture(pixels, job, nullptr, &p); });
  return py::make_tuple(drawing_paths(drawn.drawing), drawing_svg(drawn.drawing, job.pen), line_picture_duotone_svg(drawn, job));
}

// A textured mesh from the arrays duotone() returns.
TexturedMesh textured_from(const py::handle vertices, const py::handle faces, const py::handle uv, const py::handle texture) {
  TexturedMesh out{.mesh = mesh_from_arrays(vertices, faces, py::none(), "duotone").mesh};
  const auto coordinates = py::array_t<float, py::array::forcecast | py::array::c_style>(as_array(uv, "uv"));
  if (coordinates.ndim() != 2 || coordinates.shape(1) != 2 || coordinates.shape(0) != out.mesh.num_corners())
    throw py::value_error("uv: expected one (u, v) per corner of the faces: (" + std::to_string(out.mesh.num_corners()) + ", 2)");
  const auto read = coordinates.unchecked<2>();
  out.appearance.texcoords.resize(size_t(coordinates.shape(0)));
  for (py::ssize_t c = 0; c < read.shape(0); ++c) out.appearance.texcoords[size_t(c)] = {read(c, 0), read(c, 1)};
  const auto pixels = py::array_t<uint8_t, py::array::forcecast | py::array::c_style>(as_array(texture, "texture"));
  if (pixels.ndim() != 3 || pixels.shape(2) != 4)
    throw py::value_error("texture: expected an (H, W, 4) array of RGBA bytes");
  Material material{.name = "duotone"};
  material.texture = {.width = int32_t(pixels.shape(1)), .height = int32_t(pixels.shape(0)),
                      .rgba = std::vector<uint8_t>(pixels.data(), pixels.data() + pixels.size())};
  out.appearance.materials.push_back(std::move(material));
  check_appearance(out.mesh, out.appearance, "duotone");
  return out;
}

// The picture, as `meander render` draws it: meshes shaded, curves as red tubes, the
// occluder hiding their back parts.
py::array_t<uint8_t> render_picture(py::handle meshes, py::handle curves, py::handle occluder, const std::string& size,
                                    const std::string& view, const std::string& background, int samples, double curve_width,
                                    const std::string& curve_style, const std::string& occluder_style, bool fit) {
  if (curve_style != "tube" && curve_style != "ribbon")
    throw ParameterError("curve_style", ": unknown value '" + curve_style + "' (expected tube or ribbon)");
  if (occluder_style != "hidden" && occluder_style != "faint" && occluder_style != "shaded")
    throw ParameterError("occluder_style", ": unknown value '" + occluder_style + "' (expected hidden, faint or shaded)");
  if (samples < 1 || samples > 1024) throw ParameterError("samples", ": expected an integer in [1, 1024], got " + std::to_string(samples));
  RenderOptions options{.view = parse_view(view),
                        .background = parse_background(background),
                        .samples = samples,
                        .curve_width = curve_width,
                        .curve_style = curve_style == "ribbon" ? CurveStyle::ribbon : CurveStyle::tube,
                        .framing = fit ? Framing::silhouette : Framing::bounds};
  parse_size(size, options.width, options.height);
  Scene scene;
  const py::object list = py::isinstance<Mesh>(meshes) ? py::make_tuple(meshes) : py::reinterpret_borrow<py::object>(meshes);
  for (py::handle m : list) scene.meshes.push_back({.mesh = m.cast<const Mesh&>().mesh});
  if (!curves.is_none()) scene.curves.push_back({.curves = curves_from(curves)});
  if (!occluder.is_none())
    scene.meshes.push_back({.mesh = occluder.cast<const Mesh&>().mesh,
                            .style = occluder_style == "faint"    ? MeshStyle::faint
                                     : occluder_style == "shaded" ? MeshStyle::shaded
                                                                  : MeshStyle::hidden});
  Image image = run_job(py::none(), [&](Progress&) { return render(scene, options); });
  return owned<uint8_t>(std::move(image.rgba), {py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(4)});
}

// One description of each job's parameters, as the CLI's help and the studio show them.
template <class Job> py::list parameter_list() {
  py::list out;
  const Job defaults;
  visit_parameters(defaults, [&](const Parameter& p, const auto& value) {
    using T = std::decay_t<decltype(value)>;
    const char* type = std::is_same_v<T, bool>                    ? "boolean"
                       : std::is_integral_v<T>                    ? "integer"
                       : std::is_floating_point_v<T>              ? "number"
                       : std::is_same_v<T, std::optional<double>> ? "number or name"
                       : std::is_enum_v<T>                        ? "name"
                       : std::is_same_v<T, Paper>                 ? "paper"
                                                                  : "colors";
    py::dict entry("name"_a = std::string(p.name), "help"_a = std::string(p.help), "default"_a = parameter_text(p, value),
                   "type"_a = type);
    if (std::isfinite(p.min)) entry["min"] = p.min;
    if (std::isfinite(p.max)) entry["max"] = p.max;
    if (!p.choices.empty()) entry["choices"] = std::vector<std::string>(p.choices.begin(), p.choices.end());
    entry["length"] = p.length;
    out.append(entry);
  });
  return out;
}

} // namespace
} // namespace meander

PYBIND11_MODULE(_meander, m) {
  using namespace meander;
  m.doc() = "Hamiltonian cycle art: one closed curve over any polygon mesh, and the wires, ribbons and duotones made from it";

  static py::exception<Error> mesh_error(m, "MeshError", PyExc_ValueError);
  mesh_error.doc() = "A mesh refused: malformed, or of a topology the job cannot take (a ValueError)";
  mesh_warning = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "meander.MeshWarning", "What was repaired in a mesh before the job, or worth telling about it", PyExc_UserWarning, nullptr));
  m.attr("MeshWarning") = mesh_warning;
  py::register_exception_translator([](std::exception_ptr failure) {
    try {
      if (failure) std::rethrow_exception(failure);
    } catch (const UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const IOError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const InputError& e) {
      PyErr_SetString(mesh_error.ptr(), e.what());
    } catch (const TopologyError& e) {
      PyErr_SetString(mesh_error.ptr(), e.what());
    } catch (const Error& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  py::class_<Mesh>(m, "Mesh", "A polygon mesh: vertices (N, 3) float32, faces as offsets into a flat index array")
      .def(py::init(&mesh_from_arrays), "vertices"_a, "faces"_a, py::kw_only(), "offsets"_a = py::none(), "name"_a = "mesh",
           "A mesh from arrays: vertices (N, 3) of any float or integer dtype; faces an (F, k) integer array, a list of "
           "faces of any sizes, or a flat integer array of corners with offsets (F + 1 entries from 0). Arrays are "
           "copied once into the mesh (float32 C-contiguous vertices without conversion). `name` is what messages call it.")
      .def_property_readonly(
          "vertices",
          [](const py::object& self) {
            const Mesh& mesh = self.cast<const Mesh&>();
            py::array_t<float> view({py::ssize_t(mesh.mesh.num_vertices()), py::ssize_t(3)},
                                    reinterpret_cast<const float*>(mesh.mesh.positions.data()), self);
            py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
            return view;
          },
          "(N, 3) float32, read-only, sharing the mesh's memory")
      .def_property_readonly(
          "faces",
          [](const Mesh& mesh) {
            return faces_array(std::vector<int32_t>(mesh.mesh.face_vertices), mesh.mesh.face_start);
          },
          "(F, k) int32 when every face has k corners (a ValueError otherwise: use offsets and indices)")
      .def_property_readonly(
          "offsets", [](const Mesh& mesh) { return owned<int32_t>(std::vector<int32_t>(mesh.mesh.face_start), {py::ssize_t(mesh.mesh.face_start.size())}); },
          "(F + 1,) int32: face f's corners are indices[offsets[f]:offsets[f + 1]]")
      .def_property_readonly(
          "indices", [](const Mesh& mesh) { return owned<int32_t>(std::vector<int32_t>(mesh.mesh.face_vertices), {py::ssize_t(mesh.mesh.face_vertices.size())}); },
          "(C,) int32: every face's vertices, one face after another")
      .def_property_readonly("name", [](const Mesh& mesh) { return mesh.name; }, "what messages call it: the file it was read from, or the name given")
      .def_property_readonly("num_vertices", [](const Mesh& mesh) { return mesh.mesh.num_vertices(); })
      .def_property_readonly("num_faces", [](const Mesh& mesh) { return mesh.mesh.num_faces(); })
      .def("__repr__", [](const Mesh& mesh) {
        return "<meander.Mesh '" + mesh.name + "': " + std::to_string(mesh.mesh.num_vertices()) + " vertices, " +
               std::to_string(mesh.mesh.num_faces()) + " faces>";
      });

  m.def(
      "read",
      [](const std::filesystem::path& path) {
        py::gil_scoped_release release;
        return Mesh{read_mesh(path), path.string()};
      },
      "path"_a, "Reads a mesh: .obj .ply .stl .off .gltf .glb (a MeshError names the line or element that is wrong)");
  m.def(
      "read_curves", [](const std::filesystem::path& path) { return curves_list(read_polylines(path)); }, "path"_a,
      "Reads curves (.obj l elements, .ply edges, .json) as a list of (N, 3) float32 arrays");
  m.def(
      "generate", [](const std::string& shape, int64_t faces, int genus) { return Mesh{make_shape(shape, faces, genus), shape}; },
      "shape"_a, "faces"_a = 6400, "genus"_a = 2,
      "A mesh made by code, as `meander generate`: sphere, torus, pretzel (genus 2), genus (of `genus`), grid (an open disk), "
      "moebius");

  m.def("curve", &curve, "mesh"_a, py::kw_only(), "certificate"_a = false, "strict"_a = false, "max_faces"_a = 0,
        "progress"_a = py::none(),
        "The closed curve(s) that cover the mesh, one per connected component, as a list of (N, 3) float32 arrays.\n\n"
        "Keyword parameters are the CLI's (`meander curve --help`, meander.parameters('curve')): model_size, spacing, relax, "
        "quad, tree, branches, seed, smooth, samples. With certificate=True, returns (curves, triangles, cycle_start): the "
        "triangulated quad mesh with its triangles in cycle order, cycle k being triangles cycle_start[k]:cycle_start[k+1].\n"
        "strict refuses a mesh that needs repair (repairs are MeshWarnings otherwise); max_faces refuses larger inputs or "
        "remeshed surfaces (0: no limit); progress(stage, fraction or None) is called as the job goes, and cancels it by "
        "raising.");
  m.def("wire", &wire, "mesh"_a, py::kw_only(), "strict"_a = false, "max_faces"_a = 0, "progress"_a = py::none(),
        "A wire or ribbon along the curve: (vertices (N, 3) float32, faces (F, k) int32 (quads or triangles), report "
        "dict), the report being "
        "`--report`'s printability (with the radius used).\n\n"
        "Parameters are the CLI's (`meander wire --help`, meander.parameters('wire')): method, shape, radius, sides, bridges, "
        "s, t, thickness, levels, min_thickness, nozzle, and the curve's (with bridges, the report has a bridges dict). strict, max_faces and progress as in curve().");
  m.def("duotone", &duotone, "mesh"_a, py::kw_only(), "strict"_a = false, "max_faces"_a = 0, "progress"_a = py::none(),
        "The surface painted in two colours split by one curve per component: (vertices (N, 3) float32, faces (F, 4) int32, "
        "uv (4F, 2) float32 per corner, texture (H, W, 4) uint8, separating curves).\n\n"
        "Parameters are the CLI's (`meander duotone --help`, meander.parameters('duotone')): quad, rule, tree, seed, colors, "
        "tiles, texture_size, subdivide, model_size, spacing.");
  m.def("duotone_print", &duotone_print, "mesh"_a, py::kw_only(), "strict"_a = false, "max_faces"_a = 0,
        "progress"_a = py::none(),
        "A two-colour print, as `meander duotone --shell`: ([solid_1, solid_2] as Meshes, summary): the surface thickened "
        "inward by `shell` and cut along the curve into two closed solids, one per colour; write them with write_print() "
        "(one 3MF a slicer prints in two filaments) or write_mesh().\n\n"
        "Parameters are duotone()'s, with shell (required) and min_thickness.");
  m.def("draw", &draw, "what"_a, py::kw_only(), "occluder"_a = py::none(), "view"_a = "iso", "fit"_a = false,
        "camera"_a = py::none(), "paper"_a = "A4", "landscape"_a = false, "margin"_a = 10.0, "pen"_a = 0.3, "progress"_a = py::none(),
        "A pen plotter's drawing, as `meander draw`: (paths, svg). `what` is a Mesh, whose curve is made with the curve's "
        "parameters and hidden by its surface, or curves (a list of (N, 3) arrays), hidden by `occluder` if given. "
        "paths: (N, 2) float64 arrays in millimetres from the sheet's top-left corner (y down) in drawing order, a closed "
        "one ending on its first point; svg: the SVG text. camera: (eye, target, up, vertical field of view in degrees) in "
        "place of view and fit. paper: A3, A4, A5, letter, legal or WIDTHxHEIGHT (mm); margin and pen in millimetres, or "
        "text with a unit.");
  m.def("image", &image, "picture"_a, py::kw_only(), "progress"_a = py::none(),
        "A picture drawn with one closed line that never crosses itself, as `meander image`: (paths, svg, duotone_svg). "
        "picture: a file's path, or an (H, W), (H, W, 3) or (H, W, 4) array of bytes or of numbers in 0..1. paths: the "
        "line as one (N, 2) float64 array in millimetres from the sheet's top-left corner (y down), ending on its first "
        "point; svg: the drawing; duotone_svg: the two regions it bounds in the two colors.\n\n"
        "Parameters are the CLI's (`meander image --help`, meander.parameters('image')): paper, margin, width, pen, "
        "spacing, max_spacing, gamma, invert, tree, branches, seed, smooth, samples, max_pixels, colors; lengths in "
        "millimetres or text with a unit.");
  m.def("render", &render_picture, py::kw_only(), "meshes"_a = py::tuple(), "curves"_a = py::none(), "occluder"_a = py::none(),
        "size"_a = "1600x1200", "view"_a = "iso", "background"_a = "white", "samples"_a = 4, "curve_width"_a = 0.0,
        "curve_style"_a = "tube", "occluder_style"_a = "hidden", "fit"_a = false,
        "A picture, as `meander render` draws it: (H, W, 4) uint8 RGBA. meshes (a Mesh or several) are shaded, curves (a list "
        "of (N, 3) arrays) drawn as tubes or ribbons, occluder (a Mesh) hides their back parts.");

  m.def(
      "write_mesh",
      [](const std::filesystem::path& path, const Mesh& mesh, bool millimetres) {
        write_mesh(mesh.mesh, path, {.millimetres = millimetres});
      },
      "path"_a, "mesh"_a, py::kw_only(), "millimetres"_a = false,
      "Writes a mesh: .obj .ply .stl .off .glb .3mf (millimetres: the mesh is in mm; a GLB is then scaled to metres)");
  m.def(
      "write_curves",
      [](const std::filesystem::path& path, py::handle curves, bool millimetres) {
        // An SVG is the curves' drawing from the front (curve_svg), as the CLI's.
        const Polylines c = curves_from(curves);
        std::string extension = path.extension().string();
        std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char x) { return char(std::tolower(x)); });
        if (extension == ".svg") write_bytes(path, curve_svg(c, {}, millimetres));
        else write_polylines(c, path);
      },
      "path"_a, "curves"_a, py::kw_only(), "millimetres"_a = false,
      "Writes closed curves (a list of (N, 3) arrays): .obj .ply .json, or .svg: their plotter drawing seen from the front "
      "(millimetres: at true size, else fitted to an A4 sheet)");
  m.def(
      "write_duotone",
      [](const std::filesystem::path& path, py::handle vertices, py::handle faces, py::handle uv, py::handle texture,
         bool millimetres) { write_textured_mesh(textured_from(vertices, faces, uv, texture), path, millimetres); },
      "path"_a, "vertices"_a, "faces"_a, "uv"_a, "texture"_a, py::kw_only(), "millimetres"_a = false,
      "Writes a duotone() surface: .obj (with its .mtl and .png beside it) or .glb");
  m.def(
      "write_print",
      [](const std::filesystem::path& path, const Mesh& first, const Mesh& second, py::handle colors) {
        DuotoneJob job;
        py::kwargs given;
        given["colors"] = colors;
        set_parameters(job, given, "write_print");
        write_3mf_parts(colored_parts(first.mesh, second.mesh, job.tiles.colors), path);
      },
      "path"_a, "first"_a, "second"_a, py::kw_only(), "colors"_a = "yellow,blue",
      "Writes a two-colour print (.3mf): one object of two parts, each with its colour as a 3MF material and PrusaSlicer's "
      "extruder (1 and 2): duotone_print()'s solids, in millimetres");
  m.def(
      "write_png",
      [](const std::filesystem::path& path, py::handle picture) {
        const auto pixels = py::array_t<uint8_t, py::array::forcecast | py::array::c_style>(as_array(picture, "picture"));
        if (pixels.ndim() != 3 || pixels.shape(2) != 4) throw py::value_error("picture: expected an (H, W, 4) array of RGBA bytes");
        write_png({.width = int32_t(pixels.shape(1)), .height = int32_t(pixels.shape(0)), .has_alpha = true,
                   .rgba = std::vector<uint8_t>(pixels.data(), pixels.data() + pixels.size())},
                  path);
      },
      "path"_a, "picture"_a, "Writes an (H, W, 4) uint8 RGBA picture as PNG");

  m.def(
      "_hold_next_job", [] { hold_next_job = true; },
      "For tests: the next job waits at its first check until its progress callback raises");
  m.def(
      "parameters",
      [](const std::string& job) {
        if (job == "curve") return parameter_list<CurveJob>();
        if (job == "wire") return parameter_list<WireJob>();
        if (job == "duotone") return parameter_list<DuotoneJob>();
        if (job == "image") return parameter_list<ImageJob>();
        throw py::value_error("job: unknown value '" + job + "' (expected curve, wire, duotone or image)");
      },
      "job"_a,
      "The job's parameters as the CLI and the studio describe them: dicts of name, help, default (as text), type "
      "(boolean, integer, number, name, 'number or name' (a number, or its one choice for none), colors, paper), min, max, "
      "choices, and whether it is a length");
}
