// vibromap._core: the compiled core of the Python package (postprocess/vibromap/), made with
// pybind11 from the same libraries as the vibromap executable. Deliberately thin: the Python
// package's modules give the API its shape, names, docstrings and types; this module offers
// the scene (read, overridden and checked by io/scene exactly as the command line does), the
// key table (core/model/keys.hpp), and the point solve, census and trajectory of `vibromap run
// [--census | --trajectory]`
// (io/point_run.hpp), whose answer is the very JSON text the command prints. Reading a scene
// releases the GIL too (a loop over points in threads reads one scene per point).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "interrupt.hpp"
#include "vibromap/core/model/keys.hpp"
#include "vibromap/io/point_run.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/io/trajectory_file.hpp"

namespace vibromap::python {
namespace {

namespace py = pybind11;

// The scene a Python Scene() starts from: no file, every key at its default.
constexpr const char* kDefaultScenePath = "Scene()";

const char* type_name(KeyType t) {
  switch (t) {
    case KeyType::real: return "real";
    case KeyType::integer: return "integer";
    case KeyType::choice: return "choice";
    case KeyType::boolean: return "boolean";
  }
  return "?";
}

// The key named `name` (in full or by a name one section alone has); KeyError otherwise.
Key find_key(const std::string& name) {
  const std::optional<Key> key = Key::find(name);
  if (!key) throw py::key_error("no key '" + name + "' (or a name several sections have: give section.key)");
  return *key;
}

// A key's value at the scene's point as Python sees it: a float, an int, the name of a choice,
// a bool. A key of the point's model left to its partner or to the rest state is derived
// (Key::value: k2 from omega2); a solver or analysis key not given is None.
py::object key_value(const Scene& scene, Key key) {
  std::optional<double> v = key.stored(scene.params, scene.options);
  const KeyInfo& info = key.info();
  if (!v && info.section != "solver" && info.section != "analysis") v = key.value(scene.params);
  if (!v) return py::none();
  switch (info.type) {
    case KeyType::real: return py::float_(*v);
    case KeyType::integer: return py::int_(static_cast<long long>(*v));
    case KeyType::choice: return py::str(std::string(info.choices.at(static_cast<std::size_t>(*v))));
    case KeyType::boolean: return py::bool_(*v != 0);
  }
  return py::none();
}

// One row of the key table as a dict (the fields of KeyInfo, and the value at the default point).
py::dict key_row(Key key, const Scene& defaults) {
  const KeyInfo& k = key.info();
  py::dict d;
  d["name"] = k.full_name();
  d["section"] = std::string(k.section);
  d["key"] = std::string(k.name);
  d["type"] = type_name(k.type);
  d["unit"] = std::string(k.unit);
  d["meaning"] = std::string(k.meaning);
  d["allowed"] = k.allowed();
  d["bounds"] = py::make_tuple(k.bounds.lo, k.bounds.hi, k.bounds.lo_open, k.bounds.hi_open);
  std::vector<std::string> choices(k.choices.begin(), k.choices.end());
  d["choices"] = choices;
  d["partner"] = std::string(k.partner);
  d["default_text"] = k.default_text;
  d["default_given"] = k.default_given;
  d["default"] = key_value(defaults, key);
  return d;
}

py::list key_table() {
  const Scene defaults = parse_scene("", kDefaultScenePath);
  py::list rows;
  for (const Key& key : Key::all()) rows.append(key_row(key, defaults));
  return rows;
}

// The JSON `vibromap run SCENE --format json` prints for the scene's point: the same scene
// adjustment (no trajectory), solve and writer as the command (io/point_run.hpp).
std::string run_json(const Scene& scene) {
  std::string json;
  run_released([&] {
    const std::optional<std::string> periods = trajectory_override(scene, false);
    const Scene run_scene = periods ? parse_scene(scene.text, scene.path, {*periods}) : scene;
    json = summary_json(solve_scene_point(run_scene));
  });
  return json;
}

// The JSON `vibromap run SCENE --census [--labels] [--shock] --format json` prints in one
// process (io/point_run.hpp).
std::string census_json_of(const Scene& scene, bool labels, bool shock) {
  std::string json;
  run_released([&] { json = census_json(census_scene_point(scene, run_census_options(scene, labels, shock))); });
  return json;
}

// The point solved as `vibromap run SCENE --trajectory FILE --format json` solves it: its JSON,
// the scene text the file would record, and the file's columns as (name, units, description,
// values). GIL held on return only.
py::tuple trajectory_of(const Scene& scene) {
  std::string json;
  Scene run_scene;
  PointSummary summary;
  run_released([&] {
    const std::optional<std::string> periods = trajectory_override(scene, true);
    run_scene = periods ? parse_scene(scene.text, scene.path, {*periods}) : scene;
    summary = solve_scene_point(run_scene);
    json = summary_json(summary);
  });
  py::list columns;
  for (const TrajectoryColumn& c : trajectory_columns()) {
    py::array_t<double> values(static_cast<py::ssize_t>(summary.trajectory.size()));
    double* out = values.mutable_data();
    for (const TrajectorySample& sample : summary.trajectory) *out++ = sample.*c.member;
    columns.append(py::make_tuple(c.name, c.units, c.description, values));
  }
  return py::make_tuple(json, run_scene.text, columns);
}

void declare_scene(py::module_& m) {
  py::class_<Scene>(m, "Scene", "A checked scene (io/scene): one parameter point and how to solve it.")
      .def_static(
          "load", [](const std::string& path, const std::vector<std::string>& overrides) { return load_scene(path, overrides); },
          py::arg("path"), py::arg("overrides") = std::vector<std::string>{}, py::call_guard<py::gil_scoped_release>(),
          "Reads a scene file with --set overrides.")
      .def_static(
          "parse",
          [](const std::string& text, const std::string& path, const std::vector<std::string>& overrides) {
            return parse_scene(text, path, overrides);
          },
          py::arg("text"), py::arg("path") = kDefaultScenePath, py::arg("overrides") = std::vector<std::string>{},
          py::call_guard<py::gil_scoped_release>(), "Reads scene text (named `path` in messages) with --set overrides.")
      .def(
          "with_overrides",
          [](const Scene& s, const std::vector<std::string>& overrides) {
            return parse_scene(s.text, s.path, overrides);
          },
          py::arg("overrides"), py::call_guard<py::gil_scoped_release>(), "This scene with --set overrides.")
      .def_readonly("path", &Scene::path)
      .def_readonly("text", &Scene::text)
      .def("get", [](const Scene& s, const std::string& name) { return key_value(s, find_key(name)); },
           py::arg("name"), "A key's value at the scene's point.");
}

}  // namespace

void declare_module(py::module_& m) {
  m.doc() = "The compiled core of vibromap: scenes, the key table and the point solver.";
  remember_main_thread();
  py::register_exception<SceneError>(m, "SceneError", PyExc_ValueError);
  declare_scene(m);
  m.def("keys", &key_table, "Every key of a point: the rows of the key table, in table order.");
  m.def("run_json", &run_json, py::arg("scene"),
        "Solves the scene's point as `vibromap run --format json` does and returns that JSON text.");
  m.def("census_json", &census_json_of, py::arg("scene"), py::arg("labels") = false, py::arg("shock") = false,
        "The census of the scene's point as `vibromap run --census --format json` prints it (one process).");
  m.def("trajectory", &trajectory_of, py::arg("scene"),
        "The point solved keeping its trajectory, as `vibromap run --trajectory`: (json, scene text, columns).");
  m.attr("default_scene_path") = kDefaultScenePath;
}

}  // namespace vibromap::python

PYBIND11_MODULE(_core, m) { vibromap::python::declare_module(m); }
