// vibromap._core: the compiled core of the Python package (postprocess/vibromap/), made with
// pybind11 from the same libraries as the vibromap executable. Deliberately thin: the Python
// package's modules give the API its shape, names, docstrings and types; this module offers
// the scene (read, overridden and checked by io/scene exactly as the command line does), the
// key table (core/model/keys.hpp), and the point solve, census and trajectory of `vibromap run
// [--census | --trajectory]`
// (io/point_run.hpp), whose answer is the very JSON text the command prints. Reading a scene
// releases the GIL too (a loop over points in threads reads one scene per point).
//
// A changed copy of a scene whose keys are model parameters set to numbers is made without
// reading the scene again (HeldScene::with_numbers): the keys are set and checked on the point
// as a sweep sets a cell's (Key::set, Key::check, validate), and the scene's text, which only
// provenance, pickling and equality read, is made from the overrides when first asked for.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "interrupt.hpp"
#include "vibromap/core/model/keys.hpp"
#include "vibromap/core/model/parameters.hpp"
#include "vibromap/io/point_run.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/io/trajectory_file.hpp"

namespace vibromap::python {
namespace {

namespace py = pybind11;

// The scene a Python Scene() starts from: no file, every key at its default.
constexpr const char* kDefaultScenePath = "Scene()";

// A scene as the package holds it: a checked Scene whose point (params, options, path) is
// always current, and the batches of `--set` overrides that with_numbers applied to the point
// directly and that the scene's text does not record yet. text() replays them through the
// reader, batch by batch as the chain of copies was made, so the text is the one
// parse_scene(text, path, batch) would have given at each step. GIL held for text().
class HeldScene {
 public:
  explicit HeldScene(Scene scene) : scene_(std::move(scene)) {}

  const Scene& point() const { return scene_; }
  // The scene with its text made (the overrides replayed).
  const Scene& full();
  // This scene with `overrides` given to the reader (the command line's --set).
  HeldScene with_overrides(const std::vector<std::string>& overrides);
  // This scene with model parameters `names` (full names) set to `values`, `overrides` their
  // --set texts; nullopt when the reader is needed: a key that is not a model parameter, a
  // value or a point a check refuses (the reader then gives the message), a scene with a
  // [sweep], [optimise] or [census] section (whose checks read the point too), D under a
  // partly given [initial] state (its unset components follow D), or a long chain of copies.
  std::optional<HeldScene> with_numbers(const std::vector<std::string>& names, const std::vector<double>& values,
                                        const std::vector<std::string>& overrides) const;

 private:
  static constexpr std::size_t kMaxPending = 16;  // override batches kept before the text is made
  Scene scene_;
  std::vector<std::vector<std::string>> pending_;
};

const Scene& HeldScene::full() {
  for (const std::vector<std::string>& batch : pending_) scene_.text = parse_scene(scene_.text, scene_.path, batch).text;
  pending_.clear();
  return scene_;
}

HeldScene HeldScene::with_overrides(const std::vector<std::string>& overrides) {
  const Scene& s = full();
  std::string text = s.text, path = s.path;
  py::gil_scoped_release release;
  return HeldScene(parse_scene(text, path, overrides));
}

std::optional<HeldScene> HeldScene::with_numbers(const std::vector<std::string>& names, const std::vector<double>& values,
                                                 const std::vector<std::string>& overrides) const {
  if (names.size() != values.size() || names.size() != overrides.size()) throw std::invalid_argument("with_numbers: lengths differ");
  if (scene_.sweep || scene_.optimise || scene_.census || pending_.size() >= kMaxPending) return std::nullopt;
  HeldScene out(scene_);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::optional<Key> key = Key::find(names[i]);
    if (!key || !key->is_parameter() || key->full_name() != names[i] || !key->check(values[i]).empty()) return std::nullopt;
    if (names[i] == "system.D" && scene_.params.initial) return std::nullopt;
    key->set(out.scene_.params, out.scene_.options, values[i]);
  }
  if (!validate(out.scene_.params).empty()) return std::nullopt;
  out.pending_ = pending_;
  out.pending_.push_back(overrides);
  return out;
}

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
std::string run_json(HeldScene& held) {
  const std::optional<std::string> periods = trajectory_override(held.point(), false);
  const Scene& scene = periods ? held.full() : held.point();
  std::string json;
  run_released([&] {
    const Scene run_scene = periods ? parse_scene(scene.text, scene.path, {*periods}) : scene;
    json = summary_json(solve_scene_point(run_scene));
  });
  return json;
}

// The JSON `vibromap run SCENE --census [--labels] [--shock] --format json` prints in one
// process (io/point_run.hpp).
std::string census_json_of(const HeldScene& held, bool labels, bool shock) {
  const Scene& scene = held.point();
  std::string json;
  run_released([&] { json = census_json(census_scene_point(scene, run_census_options(scene, labels, shock))); });
  return json;
}

// The point solved as `vibromap run SCENE --trajectory FILE --format json` solves it: its JSON,
// the scene text the file would record, and the file's columns as (name, units, description,
// values). GIL held on return only.
py::tuple trajectory_of(HeldScene& held) {
  const Scene& scene = held.full();
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
  py::class_<HeldScene>(m, "Scene", "A checked scene (io/scene): one parameter point and how to solve it.")
      .def_static(
          "load",
          [](const std::string& path, const std::vector<std::string>& overrides) {
            return HeldScene(load_scene(path, overrides));
          },
          py::arg("path"), py::arg("overrides") = std::vector<std::string>{}, py::call_guard<py::gil_scoped_release>(),
          "Reads a scene file with --set overrides.")
      .def_static(
          "parse",
          [](const std::string& text, const std::string& path, const std::vector<std::string>& overrides) {
            return HeldScene(parse_scene(text, path, overrides));
          },
          py::arg("text"), py::arg("path") = kDefaultScenePath, py::arg("overrides") = std::vector<std::string>{},
          py::call_guard<py::gil_scoped_release>(), "Reads scene text (named `path` in messages) with --set overrides.")
      .def("with_overrides", &HeldScene::with_overrides, py::arg("overrides"), "This scene with --set overrides.")
      .def("with_numbers", &HeldScene::with_numbers, py::arg("names"), py::arg("values"), py::arg("overrides"),
           "This scene with model parameters set to numbers without reading it again; None when the "
           "reader is needed (with_overrides then gives the scene or the message).")
      .def_property_readonly("path", [](const HeldScene& s) { return s.point().path; })
      .def_property_readonly("text", [](HeldScene& s) { return s.full().text; })
      .def("get", [](const HeldScene& s, const std::string& name) { return key_value(s.point(), find_key(name)); },
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
