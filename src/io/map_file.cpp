#include "vibromap/io/map_file.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "map_fields.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"

// The layout is documented in map_file.hpp. CF conventions (cfconventions.org, 1.8): a
// coordinate variable is a 1-D variable named after its dimension (here an HDF5 dimension
// scale, which netCDF-4 reads as such); flag_values/flag_meanings label the integer codes
// of status and regime (CF section 3.5); _FillValue marks float cells not computed.

namespace vibromap {
using detail::fail;
namespace detail {
namespace {

constexpr std::size_t kChunkCacheBytes = 4u << 20;   // per dataset: a few chunks in flight
constexpr std::uint64_t kDoneWindow = 1u << 20;       // cells of /done read at a time by pending()

FileOptions writer_options() {
  FileOptions o;
  o.locking = false;  // readers may open the map while it runs; the sweep holds its own lock
  o.chunk_cache_bytes = kChunkCacheBytes;
  return o;
}

[[noreturn]] void malformed(const std::string& path, std::string_view what) {
  fail(path, cat("not a valid vibromap map: ", what));
}

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
    scales.push_back(std::move(coordinate));
  }
  return scales;
}

// The shape of field f's dataset (per (cell, attractor): one more dimension), and its chunks:
// the cells of a chunk are those of every other dataset's chunk, so chunk spans agree.
Shape with_slots(Shape shape, const MapField& f) {
  if (f.slots > 0) shape.push_back(f.slots);
  return shape;
}

// `scales`: the axes' coordinates, then (with a census) /attractor.
Dataset make_field(Hdf5File& file, const MapField& f, const Shape& shape, const Shape& chunk,
                   const std::vector<Dataset>& scales) {
  Dataset d = file.create_dataset(f.name, f.file_type, with_slots(shape, f),
                                  chunked(with_slots(chunk, f), f.fill, f.fill_attribute));
  const std::size_t dims = shape.size() + (f.slots > 0 ? 1 : 0);
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

// ---- Reading a map's layout ----------------------------------------------------------------

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

MapLayout read_layout(const Hdf5File& file) {
  const std::string& path = file.path();
  MapLayout layout;
  layout.stored = read_stored(file);
  for (const char* name : {"title", "Conventions", "vibromap_version", "scene", "identity", "ranks", "cells_total",
                           "cells_done", "complete"})
    require_attribute(file, path, name);
  if (!file.exists("done")) malformed(path, "no dataset '/done'");
  const Dataset done = file.open_dataset("done");
  std::vector<Axis> axes;
  for (std::size_t d = 0; d < done.shape().size(); ++d) axes.push_back(read_axis(file, done, d));
  if (axes.empty()) malformed(path, "dataset '/done' is a scalar, expected one dimension per axis");
  layout.grid = Grid(std::move(axes));
  layout.scene_text = file.read_string_attribute("scene");
  layout.identity = file.read_string_attribute("identity");
  if (file.has_attribute("census_attractors")) {  // maps made before the census have none
    const std::int64_t a = file.read_int_attribute("census_attractors");
    if (a < 0 || a > 64) malformed(path, "root attribute 'census_attractors' is outside 0..64");
    layout.attractors = static_cast<std::size_t>(a);
  }
  if (file.read_int_attribute("cells_total") != static_cast<std::int64_t>(layout.grid.size()))
    malformed(path, cat("root attribute 'cells_total' differs from the grid's ", std::to_string(layout.grid.size()),
                        " cells"));
  return layout;
}

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

// The datasets of an open map and a buffer per dataset for one chunk of cells.
struct MapDatasets {
  std::vector<MapField> fields;
  Dataset done;
  std::vector<Dataset> data;                     // fields[i]'s dataset
  std::vector<std::uint8_t> done_buffer;
  std::vector<std::vector<double>> reals;        // per field, float fields
  std::vector<std::vector<std::int64_t>> ints;   // per field, integer fields

  void open(const Hdf5File& file, const MapLayout& layout) {
    fields = map_fields(layout.stored, layout.attractors);
    const Shape shape = layout.grid.shape();
    done = open_field(file, "done", shape);
    for (const MapField& f : fields) data.push_back(open_field(file, f.name, with_slots(shape, f)));
    reals.resize(fields.size());
    ints.resize(fields.size());
  }

  // Reads cells `span` of dataset i (-1: done). False when HDF5 fails (a damaged chunk).
  bool read(int i, const CellSpan& span, std::string* why) {
    const std::size_t n = static_cast<std::size_t>(span.end - span.begin);
    try {
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

  std::string name(int i) const { return i < 0 ? "done" : fields[static_cast<std::size_t>(i)].name; }

  // Cell k of the chunk read last, from the buffers (integer values range-checked).
  CellResult cell(std::size_t k, const std::string& path) const {
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
        f.set_int(c, a, v);
      }
    }
    return c;
  }

  // Replaces chunk `span` of every dataset with fill values, /done with 0, without reading it.
  void fill_chunk(const CellSpan& span, const Shape& shape) {
    Shape offset(shape.size());
    std::uint64_t flat = span.begin;
    for (std::size_t d = shape.size(); d-- > 0;) {
      offset[d] = static_cast<std::size_t>(flat % shape[d]);
      flat /= shape[d];
    }
    done.reset_chunk(offset, 0.0);
    for (std::size_t i = 0; i < fields.size(); ++i)
      data[i].reset_chunk(fields[i].slots > 0 ? with_slots(offset, fields[i]) : offset, fields[i].fill.value_or(0.0));
  }
};

}  // namespace detail

// ---- MapWriter -------------------------------------------------------------------------------

struct MapWriter::Impl {
  std::string path;
  Hdf5File file;
  MapLayout layout;
  Shape chunk;
  std::vector<CellSpan> chunks;
  detail::MapDatasets ds;
  std::uint64_t done_count = 0;
  MapRepair repair;
  std::vector<CellSpan> unflushed;       // written since the last checkpoint, in arrival order
  std::uint64_t window_begin = 0;        // pending(): the cached window of /done
  std::vector<std::uint8_t> window;
  std::vector<double> reals;             // write(): one field's values
  std::vector<std::int64_t> ints;
  std::chrono::steady_clock::time_point last_writeback = std::chrono::steady_clock::now();

  Impl(std::string p, Hdf5File f) : path(std::move(p)), file(std::move(f)) {}
};

MapWriter::MapWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
MapWriter::MapWriter(MapWriter&&) noexcept = default;
MapWriter& MapWriter::operator=(MapWriter&&) noexcept = default;
MapWriter::~MapWriter() = default;

const std::string& MapWriter::path() const { return impl_->path; }
const MapLayout& MapWriter::layout() const { return impl_->layout; }
std::uint64_t MapWriter::cells_done() const { return impl_->done_count; }
const MapRepair& MapWriter::repair() const { return impl_->repair; }

std::uint64_t MapWriter::file_bytes(const MapLayout& layout) {
  std::uint64_t per_cell = 1;  // done
  for (const detail::MapField& f : detail::map_fields(layout.stored, layout.attractors))
    per_cell += detail::element_bytes(f.file_type) * f.width();
  // HDF5 stores every chunk whole, the ones that overhang the grid's edge included.
  const Shape shape = layout.grid.shape();
  const Shape chunk = detail::map_chunk_shape(shape);
  std::uint64_t chunks = 1, chunk_cells = 1;
  for (std::size_t d = 0; d < shape.size(); ++d) {
    chunks *= (shape[d] + chunk[d] - 1) / chunk[d];
    chunk_cells *= chunk[d];
  }
  std::uint64_t axes = 0;
  for (const Axis& a : layout.grid.axes()) axes += 8 * a.values.size() + 4;
  constexpr std::uint64_t kPerChunk = 64;      // its checksum and its entry in the chunk index, about
  constexpr std::uint64_t kHeaders = 32768;    // object headers and attributes, about
  return chunks * (chunk_cells * per_cell + 10 * kPerChunk) + axes + kHeaders + layout.scene_text.size() +
         layout.identity.size();
}

MapWriter MapWriter::create(const std::string& path, const MapLayout& layout, int ranks) {
  detail::check_layout(path, layout);
  try {
    auto impl = std::make_unique<Impl>(path, Hdf5File(path, FileMode::truncate, detail::writer_options()));
    impl->layout = layout;
    const Shape shape = layout.grid.shape();
    impl->chunk = detail::map_chunk_shape(shape);
    impl->chunks = detail::chunk_spans(shape, impl->chunk);
    std::vector<Dataset> scales = detail::write_axes(impl->file, layout.grid);
    if (layout.attractors > 0) scales.push_back(detail::write_attractor_scale(impl->file, layout.attractors));
    detail::MapField done_field = detail::done_field();
    impl->ds.fields = detail::map_fields(layout.stored, layout.attractors);
    impl->ds.done = detail::make_field(impl->file, done_field, shape, impl->chunk, scales);
    for (const detail::MapField& f : impl->ds.fields)
      impl->ds.data.push_back(detail::make_field(impl->file, f, shape, impl->chunk, scales));
    impl->ds.reals.resize(impl->ds.fields.size());
    impl->ds.ints.resize(impl->ds.fields.size());
    detail::write_root_attributes(impl->file, layout, ranks);
    impl->file.sync();
    return MapWriter(std::move(impl));
  } catch (...) {
    std::remove(path.c_str());
    throw;
  }
}

MapWriter MapWriter::resume(const std::string& path, const std::function<void(const CellResult&)>& visit_done) {
  auto impl = std::make_unique<Impl>(path, Hdf5File(path, FileMode::read_write, detail::writer_options()));
  impl->layout = detail::read_layout(impl->file);
  const Shape shape = impl->layout.grid.shape();
  impl->chunk = detail::map_chunk_shape(shape);
  impl->chunks = detail::chunk_spans(shape, impl->chunk);
  impl->ds.open(impl->file, impl->layout);
  MapWriter writer(std::move(impl));
  writer.verify_and_repair(visit_done);
  return writer;
}

// Reads every chunk of every dataset: a chunk that fails to read anywhere is wiped everywhere
// (fill values, /done = 0); the others' done cells are counted and visited.
void MapWriter::verify_and_repair(const std::function<void(const CellResult&)>& visit_done) {
  Impl& m = *impl_;
  std::vector<CellSpan> damaged;
  const int n_fields = static_cast<int>(m.ds.fields.size());
  for (const CellSpan& span : m.chunks) {
    bool ok = true;
    for (int i = -1; i < n_fields; ++i) {
      if (m.ds.read(i, span, nullptr)) continue;
      ok = false;
      const std::string name = m.ds.name(i);
      if (std::find(m.repair.datasets.begin(), m.repair.datasets.end(), name) == m.repair.datasets.end())
        m.repair.datasets.push_back(name);
    }
    if (!ok) {
      damaged.push_back(span);
      continue;
    }
    for (std::size_t k = 0; k < m.ds.done_buffer.size(); ++k) {
      if (m.ds.done_buffer[k] > 1) detail::malformed(m.path, "dataset '/done' holds a value other than 0 or 1");
      if (m.ds.done_buffer[k] == 0) continue;
      const CellResult c = m.ds.cell(k, m.path);
      ++m.done_count;
      if (visit_done) visit_done(c);
    }
  }
  for (const CellSpan& span : damaged) {
    ++m.repair.chunks;
    m.repair.cells += span.end - span.begin;
    m.ds.fill_chunk(span, m.layout.grid.shape());
  }
  if (!damaged.empty()) m.file.sync();
}

std::uint64_t MapWriter::pending(std::uint64_t from, std::uint64_t max, std::vector<CellSpan>& out) {
  Impl& m = *impl_;
  const std::uint64_t cells = m.layout.grid.size();
  std::uint64_t taken = 0, i = from;
  while (i < cells && taken < max) {
    if (i < m.window_begin || i >= m.window_begin + m.window.size()) {
      m.window_begin = i;
      m.window.resize(static_cast<std::size_t>(std::min(detail::kDoneWindow, cells - i)));
      m.ds.done.read_flat(i, std::span<std::uint8_t>(m.window));
    }
    if (m.window[static_cast<std::size_t>(i - m.window_begin)] == 0) {
      if (!out.empty() && out.back().end == i) {
        ++out.back().end;
      } else {
        out.push_back({i, i + 1});
      }
      ++taken;
    }
    ++i;
  }
  return i;
}

void MapWriter::write(std::uint64_t first, std::span<const CellResult> cells) {
  Impl& m = *impl_;
  if (cells.empty()) return;
  for (std::size_t i = 0; i < m.ds.fields.size(); ++i) {
    const detail::MapField& f = m.ds.fields[i];
    const std::size_t w = f.width();
    if (f.integer) {
      m.ints.resize(cells.size() * w);
      for (std::size_t k = 0; k < cells.size(); ++k)
        for (std::size_t a = 0; a < w; ++a) m.ints[k * w + a] = f.get_int(cells[k], a);
      m.ds.data[i].write_flat(first * w, std::span<const std::int64_t>(m.ints));
    } else {
      m.reals.resize(cells.size() * w);
      for (std::size_t k = 0; k < cells.size(); ++k)
        for (std::size_t a = 0; a < w; ++a) m.reals[k * w + a] = f.get_real(cells[k], a);
      m.ds.data[i].write_flat(first * w, std::span<const double>(m.reals));
    }
  }
  // Every second or so, push what HDF5 has evicted towards the disk: checkpoints then wait
  // for the last second's data only, not for everything since the previous checkpoint.
  if (const auto now = std::chrono::steady_clock::now(); now - m.last_writeback > std::chrono::seconds(1)) {
    m.file.start_writeback();
    m.last_writeback = now;
  }
  const std::uint64_t last = first + cells.size();
  if (!m.unflushed.empty() && m.unflushed.back().end == first) {
    m.unflushed.back().end = last;
  } else {
    m.unflushed.push_back({first, last});
  }
}

void MapWriter::checkpoint() {
  Impl& m = *impl_;
  if (m.unflushed.empty()) return;
  m.file.sync();  // the data first: /done never runs ahead of it
  std::sort(m.unflushed.begin(), m.unflushed.end(),
            [](const CellSpan& a, const CellSpan& b) { return a.begin < b.begin; });
  std::vector<std::uint8_t> ones;
  for (const CellSpan& span : m.unflushed) {
    for (std::uint64_t at = span.begin; at < span.end;) {
      const std::uint64_t n = std::min<std::uint64_t>(span.end - at, detail::kDoneWindow);
      ones.assign(static_cast<std::size_t>(n), 1);
      m.ds.done.write_flat(at, std::span<const std::uint8_t>(ones));
      at += n;
    }
    m.done_count += span.end - span.begin;
  }
  m.unflushed.clear();
  m.window.clear();  // pending() reads /done afresh
  m.file.sync();
}

void MapWriter::finish(int ranks) {
  Impl& m = *impl_;
  checkpoint();
  m.file.set_attribute("cells_done", m.done_count);
  m.file.set_attribute("complete", m.done_count == m.layout.grid.size() ? 1 : 0);
  m.file.set_attribute("ranks", ranks);
  m.file.sync();
  m.ds = detail::MapDatasets{};
  m.file.close();
}

// ---- Reading ---------------------------------------------------------------------------------

MapLayout read_map_layout(const std::string& path) {
  const Hdf5File file(path, FileMode::read_only);
  return detail::read_layout(file);
}

void scan_map(const std::string& path, const std::function<void(std::uint64_t, const CellResult&)>& visit) {
  const Hdf5File file(path, FileMode::read_only);
  const MapLayout layout = detail::read_layout(file);
  const Shape shape = layout.grid.shape();
  const Shape chunk = detail::map_chunk_shape(shape);
  detail::MapDatasets ds;
  ds.open(file, layout);
  const int n_fields = static_cast<int>(ds.fields.size());
  for (const CellSpan& span : detail::chunk_spans(shape, chunk)) {
    std::string why;
    for (int i = -1; i < n_fields; ++i)
      if (!ds.read(i, span, &why))
        fail(path, cat("dataset '/", ds.name(i), "' is damaged: cells ", std::to_string(span.begin), "..",
                       std::to_string(span.end - 1), " fail to read (", why, ")"));
    for (std::size_t k = 0; k < ds.done_buffer.size(); ++k) {
      if (ds.done_buffer[k] > 1) detail::malformed(path, "dataset '/done' holds a value other than 0 or 1");
      if (ds.done_buffer[k] == 1) visit(span.begin + k, ds.cell(k, path));
    }
  }
}

SweepMap read_map(const std::string& path) {
  SweepMap map;
  {
    const Hdf5File file(path, FileMode::read_only);
    const MapLayout layout = detail::read_layout(file);
    map.grid = layout.grid;
    map.stored = layout.stored;
    map.scene_text = layout.scene_text;
    map.identity = layout.identity;
    map.attractors = layout.attractors;
    map.ranks = static_cast<int>(file.read_int_attribute("ranks"));
  }
  map.cells.assign(map.grid.size(), CellResult{});
  map.done.assign(map.grid.size(), 0);
  scan_map(path, [&](std::uint64_t i, const CellResult& c) {
    map.cells[i] = c;
    map.done[i] = 1;
  });
  return map;
}

void write_map(const std::string& path, const SweepMap& map) {
  const auto refuse = [&](std::string_view why) { fail(path, cat("cannot write map: ", why)); };
  const std::string cells = std::to_string(map.grid.size());
  if (map.cells.size() != map.grid.size()) refuse(cat(std::to_string(map.cells.size()), " cell records for ", cells, " cells"));
  if (map.done.size() != map.grid.size()) refuse(cat(std::to_string(map.done.size()), " done flags for ", cells, " cells"));
  detail::check_layout(path, {map.grid, map.stored, map.scene_text, map.identity, map.attractors});
  const std::string tmp = path + ".tmp";
  try {
    MapWriter w = MapWriter::create(tmp, {map.grid, map.stored, map.scene_text, map.identity, map.attractors}, map.ranks);
    for (std::uint64_t i = 0; i < map.cells.size();) {
      if (!map.done[i]) {
        ++i;
        continue;
      }
      std::uint64_t j = i;
      while (j < map.cells.size() && map.done[j]) ++j;
      w.write(i, std::span<const CellResult>(map.cells.data() + i, static_cast<std::size_t>(j - i)));
      i = j;
    }
    w.finish(map.ranks);
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      fail(path, cat("cannot rename file '", tmp, "' to it (", std::strerror(errno), ")"));
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

}  // namespace vibromap
