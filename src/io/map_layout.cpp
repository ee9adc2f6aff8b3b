// The map file's layout (map_file.hpp documents it): making its datasets, reading its layout
// back and checking it, and one chunk of every dataset (MapDatasets). MapWriter and the readers
// (map_file.cpp) use these.

#include "map_layout.hpp"

#include <algorithm>
#include <stdexcept>
#include <string_view>

#include "attribute_seal.hpp"
#include "index_scale.hpp"
#include "vibromap/core/text.hpp"

// CF conventions (cfconventions.org, 1.8): a coordinate variable is a 1-D variable named after
// its dimension (here an HDF5 dimension scale, which netCDF-4 reads as such);
// flag_values/flag_meanings label the integer codes of status and regime (CF section 3.5);
// _FillValue marks float cells not computed.

namespace vibromap::detail {

constexpr std::size_t kChunkCacheBytes = 4u << 20;   // per dataset: a few chunks in flight

FileOptions writer_options() {
  FileOptions o;
  o.locking = false;  // readers may open the map while it runs; the sweep holds its own lock
  o.chunk_cache_bytes = kChunkCacheBytes;
  return o;
}

[[noreturn]] void malformed(const std::string& path, std::string_view what) {
  fail(path, cat("not a valid vibromap map: ", what));
}

namespace {

std::string shape_text(const Shape& shape) {
  std::string text;
  for (const std::size_t n : shape) text.append(text.empty() ? "" : "x").append(std::to_string(n));
  return text.empty() ? "scalar" : text;
}

// ---- Making a map ------------------------------------------------------------------------

DatasetOptions chunked(const Shape& chunk, std::optional<double> fill, bool fill_attribute) {
  DatasetOptions o;
  o.chunk = chunk;
  o.fletcher32 = true;
  o.allocate_early = true;
  o.fill_value = fill;
  o.fill_attribute = fill_attribute;
  return o;
}

}  // namespace

std::vector<Dataset> write_axes(Hdf5File& file, const Grid& grid) {
  std::vector<Dataset> scales;
  for (const Axis& axis : grid.axes()) {
    DatasetOptions o;
    o.fletcher32 = true;  // one chunk: the whole axis
    Dataset coordinate = file.write_dataset(axis.name, std::span<const double>(axis.values), {}, o);
    coordinate.make_dimension_scale(axis.name);
    coordinate.set_attribute("units", axis.units);
    coordinate.set_attribute("long_name", axis.long_name);
    coordinate.set_attribute("key", axis.key);
    coordinate.set_attribute("scale", to_string(axis.scale));
    if (!axis.categories.empty()) {  // CF: the index's names, space-separated
      std::string meanings;
      std::vector<std::int8_t> codes;
      for (const std::string& c : axis.categories) {
        meanings += (meanings.empty() ? "" : " ") + c;
        codes.push_back(static_cast<std::int8_t>(codes.size()));
      }
      coordinate.set_attribute("flag_values", std::span<const std::int8_t>(codes));
      coordinate.set_attribute("flag_meanings", meanings);
    }
    scales.push_back(std::move(coordinate));
  }
  return scales;
}

// The shape of field f's dataset (per (cell, attractor): one more dimension), and its chunks:
// the cells of a chunk are those of every other dataset's chunk, so chunk spans agree.
Shape with_slots(Shape shape, const MapField& f) {
  if (f.slots > 0) shape.push_back(f.slots);
  shape.insert(shape.end(), f.inner.begin(), f.inner.end());
  return shape;
}

// `scales`: the axes' coordinates, then (with a census) /attractor, /period_start and /state.
Dataset make_field(Hdf5File& file, const MapField& f, const Shape& shape, const Shape& chunk,
                   const std::vector<Dataset>& scales) {
  Dataset d = file.create_dataset(f.name, f.file_type, with_slots(shape, f),
                                  chunked(with_slots(chunk, f), f.fill, f.fill_attribute));
  const std::size_t dims = shape.size() + (f.slots > 0 ? 1 : 0) + f.inner.size();
  for (std::size_t i = 0; i < dims; ++i) d.attach_dimension_scale(scales[i], i);
  d.set_attribute("long_name", f.long_name);
  if (!f.units.empty()) d.set_attribute("units", f.units);
  if (!f.flag_values.empty()) {
    d.set_attribute("flag_values", std::span<const std::int8_t>(f.flag_values));
    d.set_attribute("flag_meanings", f.flag_meanings);
  }
  return d;
}

void write_root_attributes(Hdf5File& file, const MapLayout& layout, int ranks) {
  std::string stored;
  for (const Quantity q : layout.stored) stored.append(stored.empty() ? "" : " ").append(to_string(q));
  file.set_attribute("title", "vibromap regime map");
  file.set_attribute("Conventions", "CF-1.8");
  file.set_attribute("vibromap_version", VIBROMAP_VERSION);
  file.set_attribute("scene", layout.scene_text);
  file.set_attribute("identity", layout.identity);
  file.set_attribute("ranks", ranks);
  file.set_attribute("cells_total", layout.grid.size());
  file.set_attribute("cells_done", 0);
  file.set_attribute("complete", 0);
  file.set_attribute("stored", stored);
  file.set_attribute("census_attractors", layout.attractors);
  file.set_attribute("steady", layout.steady);
  file.set_attribute("hertz_limit", layout.hertz_limit);
  file.set_attribute("soft_kcon", layout.soft_kcon);
  if (layout.census_shock) file.set_attribute("census_shock", 1);
  if (layout.fragility > 0.0) file.set_attribute("fragility", layout.fragility);
  std::vector<std::string> uncovered = {"cells_done", "complete", "ranks"};
  if (layout.attractors > 0) uncovered.push_back("families");  // the family table, made by each family pass
  if (layout.refine_levels > 0) {
    file.set_attribute("refine_levels", layout.refine_levels);
    file.set_attribute("refine_on", layout.refine_on);
    file.set_attribute("refine_audit_fraction", layout.refine_audit);
    file.set_attribute("refine_speckle", layout.refine_speckle ? 1 : 0);
    for (const std::string& name : refine_figure_attributes()) {
      if (name == "refine_mismatch_bound") {
        file.set_attribute(name, 1.0);
      } else if (name == "refine_solved_per_level") {
        const std::vector<double> zeros(static_cast<std::size_t>(layout.refine_levels) + 1, 0.0);
        file.set_attribute(name, std::span<const double>(zeros));
      } else {
        file.set_attribute(name, 0);
      }
      uncovered.push_back(name);
    }
  }
  // Last of the map's attributes (MapWriter::create makes every dataset first): the format
  // version, then the seal over them all but the progress attributes, which finish() rewrites
  // and no reader trusts.
  seal_attributes(file, kMapFormat, uncovered);
}

// Refuses a layout the file cannot hold, before any file is touched.
void check_layout(const std::string& path, const MapLayout& layout) {
  const auto refuse = [&](std::string_view why) { fail(path, cat("cannot write map: ", why)); };
  if (layout.grid.axes().empty()) refuse("the grid has no axes");
  const auto& axes = layout.grid.axes();
  for (std::size_t i = 0; i < axes.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (axes[i].name == axes[j].name) refuse(cat("axis '", axes[i].name, "' appears twice"));
  for (std::size_t i = 0; i < layout.stored.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (layout.stored[i] == layout.stored[j]) refuse(cat("quantity '", to_string(layout.stored[i]), "' is stored twice"));
}

// The census's attractor index 0..A-1 as a coordinate.
Dataset write_attractor_scale(Hdf5File& file, std::size_t attractors) {
  std::vector<int> index(attractors);
  for (std::size_t a = 0; a < attractors; ++a) index[a] = static_cast<int>(a);
  DatasetOptions o;
  o.fletcher32 = true;
  Dataset coordinate = file.write_dataset("attractor", std::span<const int>(index), {}, o);
  coordinate.make_dimension_scale("attractor");
  coordinate.set_attribute("long_name", "index of the attractor in the cell's census, by basin fraction");
  coordinate.set_attribute("units", "1");
  return coordinate;
}

void write_census_scales(Hdf5File& file, std::size_t attractors, std::vector<Dataset>& scales) {
  scales.push_back(write_attractor_scale(file, attractors));
  scales.push_back(write_index_scale(file, "period_start", kMapStrobePoints, "period start within the attractor's orbit"));
  scales.push_back(write_flag_scale(file, "state", {"x1", "x2", "v1", "v2"}, "state variable"));
}

// ---- Reading a map's layout ----------------------------------------------------------------

namespace {

void require_attribute(const Hdf5Object& object, const std::string& path, std::string_view name) {
  if (!object.has_attribute(name))
    malformed(path, object.name() == "/" ? cat("no root attribute '", name, "'")
                                         : cat("no attribute '", name, "' on dataset '", object.name(), "'"));
}

// One axis from the dimension scale attached to dimension `dim` of /done.
Axis read_axis(const Hdf5File& file, const Dataset& done, std::size_t dim) {
  const std::string& path = file.path();
  const std::vector<std::string> scales = done.attached_scales(dim);
  if (scales.size() != 1)
    malformed(path, cat("dimension ", std::to_string(dim), " of dataset '/done' has ", std::to_string(scales.size()),
                        " coordinates attached, expected 1"));
  const Dataset coordinate = file.open_dataset(scales.front());
  Axis axis;
  axis.name = coordinate.dimension_scale_name();
  if (coordinate.shape().size() != 1) malformed(path, cat("coordinate '", coordinate.name(), "' is not 1-D"));
  try {
    axis.values = coordinate.read_double();
  } catch (const IoError& e) {
    fail(path, cat("coordinate '", coordinate.name(), "' is damaged (", e.what(), "); the map's axes cannot be trusted: make it again with --overwrite"));
  }
  for (const char* name : {"scale", "units", "long_name", "key"}) require_attribute(coordinate, path, name);
  axis.units = coordinate.read_string_attribute("units");
  axis.long_name = coordinate.read_string_attribute("long_name");
  axis.key = coordinate.read_string_attribute("key");
  if (coordinate.has_attribute("flag_meanings")) {
    const std::string meanings = coordinate.read_string_attribute("flag_meanings");
    for (std::size_t begin = 0; begin < meanings.size();) {
      const std::size_t end = std::min(meanings.find(' ', begin), meanings.size());
      if (end > begin) axis.categories.push_back(meanings.substr(begin, end - begin));
      begin = end + 1;
    }
  }
  try {
    axis.scale = parse_axis_scale(coordinate.read_string_attribute("scale"));
  } catch (const std::invalid_argument& e) {
    malformed(path, cat("coordinate '", coordinate.name(), "': ", e.what()));
  }
  if (const std::string err = validate_axis(axis); !err.empty())
    malformed(path, cat("coordinate '", coordinate.name(), "': ", err));
  return axis;
}

std::vector<Quantity> read_stored(const Hdf5File& file) {
  require_attribute(file, file.path(), "stored");
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
        malformed(file.path(), cat("root attribute 'stored' names an unknown quantity '", clip(name), "'"));
      }
    }
    begin = end + 1;
  }
  return stored;
}

}  // namespace

MapLayout read_layout(const Hdf5File& file) {
  const std::string& path = file.path();
  verify_file(file, kMapFormat);
  MapLayout layout;
  layout.stored = read_stored(file);
  for (const char* name : {"title", "Conventions", "vibromap_version", "scene", "identity", "ranks", "cells_total",
                           "cells_done", "complete", "census_attractors", "steady", "hertz_limit", "soft_kcon"})
    require_attribute(file, path, name);
  if (!file.exists("done")) malformed(path, "no dataset '/done'");
  const Dataset done = file.open_dataset("done");
  std::vector<Axis> axes;
  for (std::size_t d = 0; d < done.shape().size(); ++d) axes.push_back(read_axis(file, done, d));
  if (axes.empty()) malformed(path, "dataset '/done' is a scalar, expected one dimension per axis");
  layout.grid = Grid(std::move(axes));
  layout.scene_text = file.read_string_attribute("scene");
  layout.identity = file.read_string_attribute("identity");
  layout.steady = file.read_string_attribute("steady");
  layout.hertz_limit = file.read_double_attribute("hertz_limit");
  layout.soft_kcon = file.read_double_attribute("soft_kcon");
  if (file.has_attribute("fragility")) layout.fragility = file.read_double_attribute("fragility");
  const std::int64_t a = file.read_int_attribute("census_attractors");
  if (a < 0 || a > 64) malformed(path, "root attribute 'census_attractors' is outside 0..64");
  layout.attractors = static_cast<std::size_t>(a);
  layout.census_shock = file.has_attribute("census_shock") && file.read_int_attribute("census_shock") != 0;
  if (file.has_attribute("refine_levels")) {  // an adaptive map
    const std::int64_t l = file.read_int_attribute("refine_levels");
    if (l < 1 || l > 20) malformed(path, "root attribute 'refine_levels' is outside 1..20");
    layout.refine_levels = static_cast<int>(l);
    for (const char* name : {"refine_on", "refine_audit_fraction", "refine_speckle"}) require_attribute(file, path, name);
    layout.refine_on = file.read_string_attribute("refine_on");
    layout.refine_audit = file.read_double_attribute("refine_audit_fraction");
    layout.refine_speckle = file.read_int_attribute("refine_speckle") != 0;
  }
  if (file.read_int_attribute("cells_total") != static_cast<std::int64_t>(layout.grid.size()))
    malformed(path, cat("root attribute 'cells_total' differs from the grid's ", std::to_string(layout.grid.size()),
                        " cells"));
  return layout;
}

namespace {

// Opens /<name> and checks that it has the grid's shape.
Dataset open_field(const Hdf5File& file, std::string_view name, const Shape& shape) {
  if (!file.exists(name)) malformed(file.path(), cat("no dataset '/", name, "'"));
  Dataset dataset = file.open_dataset(name);
  if (dataset.shape() != shape)
    malformed(file.path(), cat("dataset '", dataset.name(), "' has shape ", shape_text(dataset.shape()), ", expected ",
                               shape_text(shape), " (the axes' lengths)"));
  return dataset;
}


}  // namespace

// ---- One chunk of every dataset ----------------------------------------------------------------

void MapDatasets::open(const Hdf5File& file, const MapLayout& layout) {
  fields = map_fields(layout);
  const Shape shape = layout.grid.shape();
  done = open_field(file, "done", shape);
  for (const MapField& f : fields) data.push_back(open_field(file, f.name, with_slots(shape, f)));
  reals.resize(fields.size());
  ints.resize(fields.size());
}


namespace {

// The offset of the chunk whose first cell is `flat`, per dimension of the grid.
Shape cell_offset(std::uint64_t flat, const Shape& shape) {
  Shape offset(shape.size());
  for (std::size_t d = shape.size(); d-- > 0;) {
    offset[d] = static_cast<std::size_t>(flat % shape[d]);
    flat /= shape[d];
  }
  return offset;
}

// The same chunk's offset in field f's dataset: a per-attractor field has one more dimension,
// held whole in each chunk.
Shape field_offset(Shape offset, const MapField& f) {
  if (f.slots > 0) offset.push_back(0);
  offset.insert(offset.end(), f.inner.size(), 0);
  return offset;
}

}  // namespace

bool MapDatasets::chunk_missing(int i, const CellSpan& span) {
  if (grid_shape.empty()) grid_shape = done.shape();
  const Shape offset = cell_offset(span.begin, grid_shape);
  if (i < 0) return !done.chunk_allocated(offset);
  const auto u = static_cast<std::size_t>(i);
  return !data[u].chunk_allocated(field_offset(offset, fields[u]));
}

bool MapDatasets::read(int i, const CellSpan& span, std::string* why) {
  const std::size_t n = static_cast<std::size_t>(span.end - span.begin);
  try {
    if (chunk_missing(i, span)) {
      if (why) *why = "its chunk is missing from the dataset's chunk index";
      return false;
    }
    if (i < 0) {
      done_buffer.resize(n);
      done.read_flat(span.begin, std::span<std::uint8_t>(done_buffer));
      return true;
    }
    const auto u = static_cast<std::size_t>(i);
    const std::size_t w = fields[u].width();
    if (fields[u].integer) {
      ints[u].resize(n * w);
      data[u].read_flat(span.begin * w, std::span<std::int64_t>(ints[u]));
    } else {
      reals[u].resize(n * w);
      data[u].read_flat(span.begin * w, std::span<double>(reals[u]));
    }
  } catch (const IoError& e) {
    if (why) *why = e.what();
    return false;
  }
  return true;
}


CellResult MapDatasets::cell(std::size_t k, const std::string& path) const {
  CellResult c;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const MapField& f = fields[i];
    const std::size_t w = f.width();
    for (std::size_t a = 0; a < w; ++a) {
      if (!f.integer) {
        f.set_real(c, a, reals[i][k * w + a]);
        continue;
      }
      const std::int64_t v = ints[i][k * w + a];
      if (v < f.lo || v > f.hi)
        malformed(path, cat("dataset '/", f.name, "' holds ", std::to_string(v), ", outside ", std::to_string(f.lo),
                            "..", std::to_string(f.hi)));
      try {
        f.set_int(c, a, v);
      } catch (const std::invalid_argument& e) {  // a code the field's slot cannot hold (map_fields.cpp)
        malformed(path, cat("dataset '/", f.name, "' ", e.what()));
      }
    }
  }
  return c;
}


void MapDatasets::fill_chunk(const CellSpan& span, const Shape& shape) {
  const Shape offset = cell_offset(span.begin, shape);
  done.reset_chunk(offset, 0.0);
  for (std::size_t i = 0; i < fields.size(); ++i)
    data[i].reset_chunk(field_offset(offset, fields[i]), fields[i].fill.value_or(0.0));
}

}  // namespace vibromap::detail
