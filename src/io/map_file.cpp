#include "vibromap/io/map_file.hpp"

#include <algorithm>
#include <limits>
#include <span>
#include <stdexcept>
#include <string_view>
#include <type_traits>

#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"

// The layout is documented in map_file.hpp. CF conventions (cfconventions.org, 1.8): a
// coordinate variable is a 1-D variable named after its dimension (here an HDF5 dimension
// scale, which netCDF-4 reads as such); flag_values/flag_meanings label the integer codes
// of status and regime (CF section 3.5); _FillValue marks float cells not computed.

namespace vibromap {
namespace detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::string_view kStableLongName =
    "stability of the periodic orbit from its Floquet multipliers (unknown where not computed)";


// CF flag_meanings: the enum's names from to_string, with '_' for '-' (CF meanings are
// blank-separated words), preceded by not_computed for code -1. Codes run -1..last.
template <class Enum>
std::string flag_meanings(Enum last, std::int8_t (*code)(Enum)) {
  std::string meanings = "not_computed";
  for (int i = 0; i <= code(last); ++i) {
    std::string name = to_string(static_cast<Enum>(i));
    std::replace(name.begin(), name.end(), '-', '_');
    meanings.append(" ").append(name);
  }
  return meanings;
}

std::vector<std::int8_t> flag_values(std::int8_t last) {
  std::vector<std::int8_t> values;
  for (int v = kNotComputed; v <= last; ++v) values.push_back(static_cast<std::int8_t>(v));
  return values;
}

// ---- writing ----------------------------------------------------------------------------

// Refuses a map the layout cannot hold, before any file is touched.
void check_writable(const std::string& path, const SweepMap& map) {
  const auto refuse = [&](std::string_view why) { fail(path, cat("cannot write map: ", why)); };
  const std::string cells = std::to_string(map.grid.size());
  if (map.grid.axes().empty()) refuse("the grid has no axes");
  if (map.cells.size() != map.grid.size())
    refuse(cat(std::to_string(map.cells.size()), " cell records for ", cells, " cells"));
  if (map.done.size() != map.grid.size())
    refuse(cat(std::to_string(map.done.size()), " done flags for ", cells, " cells"));
  const auto& axes = map.grid.axes();
  for (std::size_t i = 0; i < axes.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (axes[i].name == axes[j].name) refuse(cat("axis '", axes[i].name, "' appears twice"));
  for (std::size_t i = 0; i < map.stored.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (map.stored[i] == map.stored[j]) refuse(cat("quantity '", to_string(map.stored[i]), "' is stored twice"));
}

// One value per cell: get(cell) where the cell is done, `not_done` elsewhere.
template <class T, class Get>
std::vector<T> per_cell(const SweepMap& map, Get get, T not_done) {
  std::vector<T> values(map.cells.size(), not_done);
  for (std::size_t i = 0; i < values.size(); ++i)
    if (map.done[i] != 0) values[i] = static_cast<T>(get(map.cells[i]));
  return values;
}

// The coordinate datasets, made dimension scales named after their axes.
std::vector<Dataset> write_axes(Hdf5File& file, const Grid& grid) {
  std::vector<Dataset> scales;
  for (const Axis& axis : grid.axes()) {
    Dataset coordinate = file.write_dataset(axis.name, axis.values);
    coordinate.make_dimension_scale(axis.name);
    coordinate.set_attribute("units", axis.units);
    coordinate.set_attribute("long_name", axis.long_name);
    coordinate.set_attribute("scale", to_string(axis.scale));
    scales.push_back(std::move(coordinate));
  }
  return scales;
}

// Writes one N-D field over the grid, labels its dimensions with the axes and names it.
template <class T>
Dataset write_field(Hdf5File& file, std::string_view name, const std::vector<T>& values, const Grid& grid,
                    const std::vector<Dataset>& scales, std::string_view long_name, std::string_view units = {}) {
  DatasetOptions options;
  if constexpr (std::is_floating_point_v<T>) options.fill_value = kNaN;
  Dataset dataset = file.write_dataset(name, std::span<const T>(values), grid.shape(), options);
  for (std::size_t d = 0; d < scales.size(); ++d) dataset.attach_dimension_scale(scales[d], d);
  dataset.set_attribute("long_name", long_name);
  if (!units.empty()) dataset.set_attribute("units", units);
  return dataset;
}

// An int8 code dataset with its CF flag_values / flag_meanings (CF section 3.5).
template <class Get>
void write_flags(Hdf5File& file, const SweepMap& map, const std::vector<Dataset>& scales, std::string_view name,
                 Get get, std::string_view long_name, const std::vector<std::int8_t>& values,
                 std::string_view meanings) {
  Dataset d = write_field(file, name, per_cell<std::int8_t>(map, get, kNotComputed), map.grid, scales, long_name);
  d.set_attribute("flag_values", values);
  d.set_attribute("flag_meanings", meanings);
}

void write_codes(Hdf5File& file, const SweepMap& map, const std::vector<Dataset>& scales) {
  const std::vector<std::uint8_t> done = per_cell<std::uint8_t>(map, [](const CellResult&) { return 1; }, 0);
  write_field(file, "done", done, map.grid, scales, "1 where the cell has been computed");
  write_flags(file, map, scales, "status", [](const CellResult& c) { return c.status; },
              "outcome of the point solver", flag_values(status_code(SolveStatus::invalid_input)),
              flag_meanings(SolveStatus::invalid_input, &status_code));
  write_flags(file, map, scales, "regime", [](const CellResult& c) { return c.regime; },
              "motion regime; periodic (n,k) with n and k", flag_values(regime_code(RegimeKind::failed)),
              flag_meanings(RegimeKind::failed, &regime_code));
  write_flags(file, map, scales, "stable", [](const CellResult& c) { return c.stable; }, kStableLongName,
              {-1, 0, 1}, "unknown unstable stable");
  write_field(file, "n", per_cell<int>(map, [](const CellResult& c) { return c.n; }, 0), map.grid, scales,
              "period of the regime in forcing periods (0 where not periodic)", "1");
  write_field(file, "k", per_cell<int>(map, [](const CellResult& c) { return c.k; }, 0), map.grid, scales,
              "impacts per regime period (0 where not periodic)", "1");
}

// One stored quantity: int64 (0 where not done) or float64 (NaN where not done, and where the
// solver did not compute it, e.g. max_multiplier of a cell without a periodic orbit).
void write_quantity(Hdf5File& file, const SweepMap& map, const std::vector<Dataset>& scales, Quantity q) {
  const std::string name = to_string(q);
  if (quantity_is_integer(q)) {
    const auto values = per_cell<std::int64_t>(map, [q](const CellResult& c) { return quantity_int(c, q); }, 0);
    write_field(file, name, values, map.grid, scales, quantity_description(q), quantity_units(q));
  } else {
    const auto values = per_cell<double>(map, [q](const CellResult& c) { return c.value(q); }, kNaN);
    write_field(file, name, values, map.grid, scales, quantity_description(q), quantity_units(q));
  }
}

void write_measures(Hdf5File& file, const SweepMap& map, const std::vector<Dataset>& scales) {
  write_field(file, "wall_s", per_cell<double>(map, [](const CellResult& c) { return c.wall_s; }, kNaN), map.grid,
              scales, "wall-clock time spent on the cell", "s");
  write_field(file, "steady_residual",
              per_cell<double>(map, [](const CellResult& c) { return c.steady_residual; }, kNaN), map.grid, scales,
              "relative residual of the steady-state test", "1");
  for (const Quantity q : map.stored) write_quantity(file, map, scales, q);
}

void write_root_attributes(Hdf5File& file, const SweepMap& map) {
  const auto cells_done = std::count_if(map.done.begin(), map.done.end(), [](std::uint8_t d) { return d != 0; });
  std::string stored;
  for (const Quantity q : map.stored) stored.append(stored.empty() ? "" : " ").append(to_string(q));
  file.set_attribute("title", "vibromap regime map");
  file.set_attribute("Conventions", "CF-1.8");
  file.set_attribute("vibromap_version", VIBROMAP_VERSION);
  file.set_attribute("scene", map.scene_text);
  file.set_attribute("ranks", map.ranks);
  file.set_attribute("cells_total", map.grid.size());
  file.set_attribute("cells_done", cells_done);
  file.set_attribute("complete", static_cast<std::size_t>(cells_done) == map.grid.size() ? 1 : 0);
  file.set_attribute("stored", stored);
}

}  // namespace
}  // namespace detail

void write_map(const std::string& path, const SweepMap& map) {
  detail::check_writable(path, map);
  write_hdf5_atomically(path, [&](Hdf5File& file) {
    const std::vector<Dataset> scales = detail::write_axes(file, map.grid);
    detail::write_codes(file, map, scales);
    detail::write_measures(file, map, scales);
    detail::write_root_attributes(file, map);
  });
}

// ---- reading ----------------------------------------------------------------------------

namespace detail {
namespace {

[[noreturn]] void malformed(const Hdf5File& file, std::string_view what) {
  fail(file.path(), cat("not a valid vibromap map: ", what));
}

void require_attribute(const Hdf5Object& object, const Hdf5File& file, std::string_view name) {
  if (!object.has_attribute(name))
    malformed(file, object.name() == "/" ? cat("no root attribute '", name, "'")
                                         : cat("no attribute '", name, "' on dataset '", object.name(), "'"));
}

std::string shape_text(const Shape& shape) {
  std::string text;
  for (const std::size_t n : shape) text.append(text.empty() ? "" : "x").append(std::to_string(n));
  return text.empty() ? "scalar" : text;
}

// Opens /<name> and checks that it has the grid's shape.
Dataset open_field(const Hdf5File& file, std::string_view name, const Shape& shape) {
  if (!file.exists(name)) malformed(file, cat("no dataset '/", name, "'"));
  Dataset dataset = file.open_dataset(name);
  if (dataset.shape() != shape)
    malformed(file, cat("dataset '", dataset.name(), "' has shape ", shape_text(dataset.shape()), ", expected ",
                        shape_text(shape), " (the axes' lengths)"));
  return dataset;
}

// The integers of /<name>, each checked to lie in [lo, hi].
std::vector<std::int64_t> read_ints(const Hdf5File& file, std::string_view name, const Shape& shape,
                                    std::int64_t lo, std::int64_t hi) {
  std::vector<std::int64_t> values = open_field(file, name, shape).read_int();
  for (const std::int64_t v : values)
    if (v < lo || v > hi)
      malformed(file, cat("dataset '/", name, "' holds ", std::to_string(v), ", outside ", std::to_string(lo), "..",
                          std::to_string(hi)));
  return values;
}

// One axis from the dimension scale attached to dimension `dim` of /done.
Axis read_axis(const Hdf5File& file, const Dataset& done, std::size_t dim) {
  const std::vector<std::string> scales = done.attached_scales(dim);
  if (scales.size() != 1)
    malformed(file, cat("dimension ", std::to_string(dim), " of dataset '/done' has ", std::to_string(scales.size()),
                        " coordinates attached, expected 1"));
  const Dataset coordinate = file.open_dataset(scales.front());
  Axis axis;
  axis.name = coordinate.dimension_scale_name();
  if (coordinate.shape().size() != 1) malformed(file, cat("coordinate '", coordinate.name(), "' is not 1-D"));
  axis.values = coordinate.read_double();
  require_attribute(coordinate, file, "scale");
  try {
    axis.scale = parse_axis_scale(coordinate.read_string_attribute("scale"));
  } catch (const std::invalid_argument& e) {
    malformed(file, cat("coordinate '", coordinate.name(), "': ", e.what()));
  }
  if (const std::string err = validate_axis(axis); !err.empty())
    malformed(file, cat("coordinate '", coordinate.name(), "': ", err));
  return axis;
}

Grid read_grid(const Hdf5File& file) {
  if (!file.exists("done")) malformed(file, "no dataset '/done'");
  const Dataset done = file.open_dataset("done");
  std::vector<Axis> axes;
  for (std::size_t d = 0; d < done.shape().size(); ++d) axes.push_back(read_axis(file, done, d));
  if (axes.empty()) malformed(file, "dataset '/done' is a scalar, expected one dimension per axis");
  return Grid(std::move(axes));
}

std::vector<Quantity> read_stored(const Hdf5File& file) {
  require_attribute(file, file, "stored");
  const std::string text = file.read_string_attribute("stored");
  std::vector<Quantity> stored;
  std::size_t begin = 0;
  while (begin < text.size()) {
    const std::size_t end = std::min(text.find(' ', begin), text.size());
    if (end > begin) {
      const std::string_view name = std::string_view(text).substr(begin, end - begin);
      try {
        stored.push_back(parse_quantity(name));
      } catch (const std::invalid_argument&) {
        malformed(file, cat("root attribute 'stored' names an unknown quantity '", name, "'"));
      }
    }
    begin = end + 1;
  }
  return stored;
}

// Codes and counters of every cell (the always-kept datasets).
void read_codes(const Hdf5File& file, SweepMap& map) {
  const Shape shape = map.grid.shape();
  const auto done = read_ints(file, "done", shape, 0, 1);
  const auto status = read_ints(file, "status", shape, kNotComputed, status_code(SolveStatus::invalid_input));
  const auto regime = read_ints(file, "regime", shape, kNotComputed, regime_code(RegimeKind::failed));
  const auto stable = read_ints(file, "stable", shape, -1, 1);
  const auto n = read_ints(file, "n", shape, 0, std::numeric_limits<std::int32_t>::max());
  const auto k = read_ints(file, "k", shape, 0, std::numeric_limits<std::int32_t>::max());
  const auto wall_s = open_field(file, "wall_s", shape).read_double();
  const auto residual = open_field(file, "steady_residual", shape).read_double();
  map.done.assign(done.size(), 0);
  map.cells.assign(done.size(), CellResult{});
  for (std::size_t i = 0; i < done.size(); ++i) {
    if (done[i] == 0) continue;
    CellResult& c = map.cells[i];
    map.done[i] = 1;
    c.status = static_cast<std::int8_t>(status[i]);
    c.regime = static_cast<std::int8_t>(regime[i]);
    c.stable = static_cast<std::int8_t>(stable[i]);
    c.n = static_cast<std::int32_t>(n[i]);
    c.k = static_cast<std::int32_t>(k[i]);
    c.wall_s = wall_s[i];
    c.steady_residual = residual[i];
  }
}

// A stored quantity of every cell done, exactly as written (NaN stays NaN).
void read_quantity(const Hdf5File& file, Quantity q, SweepMap& map) {
  const std::string name = to_string(q);
  const Shape shape = map.grid.shape();
  if (!quantity_is_integer(q)) {
    const auto values = open_field(file, name, shape).read_double();
    for (std::size_t i = 0; i < values.size(); ++i)
      if (map.done[i] != 0) set_quantity(map.cells[i], q, values[i]);
    return;
  }
  const auto values = read_ints(file, name, shape, 0, quantity_max(q));
  for (std::size_t i = 0; i < values.size(); ++i)
    if (map.done[i] != 0) set_quantity_int(map.cells[i], q, values[i]);
}

// The root attributes must all be there, and their counts agree with the datasets.
void check_root_attributes(const Hdf5File& file, const SweepMap& map) {
  for (const char* name : {"title", "Conventions", "vibromap_version", "scene", "ranks", "cells_total", "cells_done",
                           "complete"})
    require_attribute(file, file, name);
  const auto done = std::count(map.done.begin(), map.done.end(), std::uint8_t{1});
  if (file.read_int_attribute("cells_total") != static_cast<std::int64_t>(map.grid.size()))
    malformed(file, cat("root attribute 'cells_total' differs from the grid's ", std::to_string(map.grid.size()),
                        " cells"));
  if (file.read_int_attribute("cells_done") != done)
    malformed(file, cat("root attribute 'cells_done' differs from the ", std::to_string(done),
                        " cells marked in dataset '/done'"));
}

}  // namespace
}  // namespace detail

SweepMap read_map(const std::string& path) {
  const Hdf5File file(path, FileMode::read_only);
  SweepMap map;
  map.stored = detail::read_stored(file);
  map.grid = detail::read_grid(file);
  detail::read_codes(file, map);
  for (const Quantity q : map.stored) detail::read_quantity(file, q, map);
  detail::check_root_attributes(file, map);
  map.scene_text = file.read_string_attribute("scene");
  map.ranks = static_cast<int>(file.read_int_attribute("ranks"));
  return map;
}

}  // namespace vibromap
