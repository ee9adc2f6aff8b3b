#include "vibromap/io/map_file.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "map_layout.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/output_file.hpp"

// MapWriter and the whole-map readers; the layout itself (making, reading, one chunk of every
// dataset) is map_layout.cpp's.

namespace vibromap {
using detail::fail;

namespace {
constexpr std::size_t kStagedCells = kMapChunkCells / 4;  // cells staged at most (MapWriter::Impl::staged)
}  // namespace

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
  // Cells written in pieces smaller than their chunk, by flat index in arrival order: set in
  // the file a chunk at a time (flush_staged), at most kStagedCells of them held: HDF5 keeps
  // memory for every small piece written into a chunk, and an adaptive map's audit scatters
  // single cells over the whole map.
  std::vector<std::pair<std::uint64_t, CellResult>> staged;
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
  for (const detail::MapField& f : detail::map_fields(layout))
    per_cell += detail::element_bytes(f.file_type) * f.width();
  for (const detail::MapField& f : detail::family_fields(layout.attractors))
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

namespace {

// The map's skeleton (axes, every dataset allocated with its fill values, the root attributes)
// written into the new file `out` and closed (not committed).
void make_skeleton(NewFile& out, const MapLayout& layout, int ranks) {
  out.close_descriptor();
  Hdf5File file(out.path(), FileMode::truncate, detail::writer_options());
  out.check_same(file.descriptor());
  const Shape shape = layout.grid.shape();
  const Shape chunk = detail::map_chunk_shape(shape);
  std::vector<Dataset> scales = detail::write_axes(file, layout.grid);
  if (layout.attractors > 0) detail::write_census_scales(file, layout.attractors, scales);
  detail::make_field(file, detail::done_field(), shape, chunk, scales);
  for (const detail::MapField& f : detail::map_fields(layout))
    detail::make_field(file, f, shape, chunk, scales);
  for (const detail::MapField& f : detail::family_fields(layout.attractors)) detail::make_field(file, f, shape, chunk, scales);
  detail::write_root_attributes(file, layout, ranks);
  scales.clear();
  file.close();
}

}  // namespace

// The map at `path` opened again to be written: a regular file, the very one named.
std::unique_ptr<MapWriter::Impl> MapWriter::open_for_writing(const std::string& path) {
  check_output(path, {.option = "map", .resume = true});
  auto impl = std::make_unique<Impl>(path, Hdf5File(path, FileMode::read_write, detail::writer_options()));
  check_opened_output(path, impl->file.descriptor());
  return impl;
}

MapWriter MapWriter::create(const std::string& path, const MapLayout& layout, int ranks) {
  detail::check_layout(path, layout);
  {
    NewFile out(path);
    make_skeleton(out, layout, ranks);
    out.commit();
  }
  return open_new(path, layout);
}

MapWriter MapWriter::create_in(NewFile& out, const MapLayout& layout, int ranks) {
  detail::check_layout(out.target(), layout);
  make_skeleton(out, layout, ranks);
  return open_new(out.path(), layout);
}

MapWriter MapWriter::open_new(const std::string& path, const MapLayout& layout) {
  auto impl = open_for_writing(path);
  impl->layout = layout;
  impl->chunk = detail::map_chunk_shape(layout.grid.shape());
  impl->chunks = detail::chunk_spans(layout.grid.shape(), impl->chunk);
  impl->ds.open(impl->file, layout);
  return MapWriter(std::move(impl));
}

MapWriter MapWriter::resume(const std::string& path, const std::function<void(std::uint64_t, const CellResult&)>& visit_done) {
  // The attributes are checked read-only first: a map refused for them is left as it was
  // (HDF5 rewrites the superblock of a file it closes after opening it for writing).
  (void)read_map_layout(path);
  auto impl = open_for_writing(path);
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
void MapWriter::verify_and_repair(const std::function<void(std::uint64_t, const CellResult&)>& visit_done) {
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
      if (visit_done) visit_done(span.begin + k, c);
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

namespace {

// The chunk (a run of cells in flat order) that holds cell `flat`.
CellSpan chunk_holding(const std::vector<CellSpan>& chunks, std::uint64_t flat, const std::string& path) {
  const auto it = std::upper_bound(chunks.begin(), chunks.end(), flat,
                                   [](std::uint64_t x, const CellSpan& s) { return x < s.begin; });
  if (it == chunks.begin() || flat >= (it - 1)->end) fail(path, "no chunk holds cell " + std::to_string(flat));
  return *(it - 1);
}

}  // namespace

// A piece that fills its chunk, or too long to stage, is written as it comes (after the cells
// staged in its chunk, so that the later values win); shorter pieces are staged.
void MapWriter::write(std::uint64_t first, std::span<const CellResult> cells) {
  Impl& m = *impl_;
  if (cells.empty()) return;
  const std::uint64_t last = first + cells.size();
  for (std::uint64_t at = first; at < last;) {
    const CellSpan chunk = chunk_holding(m.chunks, at, m.path);
    const std::uint64_t end = std::min(last, chunk.end);
    const auto piece = cells.subspan(static_cast<std::size_t>(at - first), static_cast<std::size_t>(end - at));
    if ((at == chunk.begin && end == chunk.end) || piece.size() >= kStagedCells) {
      if (std::any_of(m.staged.begin(), m.staged.end(), [&](const auto& s) { return s.first >= chunk.begin && s.first < chunk.end; }))
        flush_staged();
      write_run(at, piece);
    } else {
      for (std::size_t k = 0; k < piece.size(); ++k) m.staged.emplace_back(at + k, piece[k]);
      if (m.staged.size() > kStagedCells) flush_staged();
    }
    at = end;
  }
  // Every second or so, push what HDF5 has evicted towards the disk: checkpoints then wait
  // for the last second's data only, not for everything since the previous checkpoint.
  if (const auto now = std::chrono::steady_clock::now(); now - m.last_writeback > std::chrono::seconds(1)) {
    m.file.start_writeback();
    m.last_writeback = now;
  }
  if (!m.unflushed.empty() && m.unflushed.back().end == first) {
    m.unflushed.back().end = last;
  } else {
    m.unflushed.push_back({first, last});
  }
}

// Cells [first, first + cells.size()) into every dataset, one selection each.
void MapWriter::write_run(std::uint64_t first, std::span<const CellResult> cells) {
  Impl& m = *impl_;
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
}

// The staged cells, a chunk at a time (a cell staged twice: its last values).
void MapWriter::flush_staged() {
  Impl& m = *impl_;
  std::stable_sort(m.staged.begin(), m.staged.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < m.staged.size();) {
    const CellSpan chunk = chunk_holding(m.chunks, m.staged[i].first, m.path);
    std::size_t j = i;
    while (j < m.staged.size() && m.staged[j].first < chunk.end) ++j;
    write_staged(chunk, i, j);
    i = j;
  }
  m.staged.clear();
}

// Staged cells [from, to) (ascending, all in `chunk`) into every dataset: the chunk read
// (unless they cover it), the cells set in it, and the chunk written whole, one selection.
void MapWriter::write_staged(const CellSpan& chunk, std::size_t from, std::size_t to) {
  Impl& m = *impl_;
  const auto n = static_cast<std::size_t>(chunk.end - chunk.begin);
  std::size_t distinct = 0;
  for (std::size_t k = from; k < to; ++k) distinct += k == from || m.staged[k].first != m.staged[k - 1].first ? 1 : 0;
  const bool whole = distinct == n;
  std::string why;
  for (std::size_t i = 0; i < m.ds.fields.size(); ++i) {
    const detail::MapField& f = m.ds.fields[i];
    const std::size_t w = f.width();
    if (!whole && !m.ds.read(static_cast<int>(i), chunk, &why))
      fail(m.path, cat("dataset '/", f.name, "' fails to read (", why, ")"));
    if (f.integer) {
      std::vector<std::int64_t>& v = m.ds.ints[i];
      v.resize(n * w);
      for (std::size_t k = from; k < to; ++k)
        for (std::size_t a = 0; a < w; ++a) v[(m.staged[k].first - chunk.begin) * w + a] = f.get_int(m.staged[k].second, a);
      m.ds.data[i].write_flat(chunk.begin * w, std::span<const std::int64_t>(v));
    } else {
      std::vector<double>& v = m.ds.reals[i];
      v.resize(n * w);
      for (std::size_t k = from; k < to; ++k)
        for (std::size_t a = 0; a < w; ++a) v[(m.staged[k].first - chunk.begin) * w + a] = f.get_real(m.staged[k].second, a);
      m.ds.data[i].write_flat(chunk.begin * w, std::span<const double>(v));
    }
  }
}

CellSpan MapWriter::read_chunk(std::uint64_t flat, std::vector<CellResult>& out) {
  Impl& m = *impl_;
  const CellSpan span = chunk_holding(m.chunks, flat, m.path);
  if (std::any_of(m.staged.begin(), m.staged.end(), [&](const auto& s) { return s.first >= span.begin && s.first < span.end; }))
    flush_staged();  // the chunk as written so far
  std::string why;
  for (int i = 0; i < static_cast<int>(m.ds.fields.size()); ++i)
    if (!m.ds.read(i, span, &why)) fail(m.path, cat("dataset '/", m.ds.name(i), "' fails to read (", why, ")"));
  out.clear();
  for (std::uint64_t k = 0; k < span.end - span.begin; ++k) out.push_back(m.ds.cell(static_cast<std::size_t>(k), m.path));
  return span;
}

void MapWriter::checkpoint() {
  Impl& m = *impl_;
  if (m.unflushed.empty()) return;
  flush_staged();
  m.file.sync();  // the data first: /done never runs ahead of it
  std::sort(m.unflushed.begin(), m.unflushed.end(),
            [](const CellSpan& a, const CellSpan& b) { return a.begin < b.begin; });
  mark_done(m.unflushed);
  for (const CellSpan& span : m.unflushed) m.done_count += span.end - span.begin;
  m.unflushed.clear();
  m.window.clear();  // pending() reads /done afresh
  m.file.sync();
}

// Sets /done to 1 over `spans` (ascending), a chunk at a time: a chunk they do not cover is read
// first; each chunk is written whole, one selection.
void MapWriter::mark_done(const std::vector<CellSpan>& spans) {
  Impl& m = *impl_;
  std::vector<std::uint8_t>& done = m.ds.done_buffer;
  std::uint64_t at = 0;
  for (std::size_t s = 0; s < spans.size();) {
    at = std::max(at, spans[s].begin);
    if (at >= spans[s].end) {
      ++s;
      continue;
    }
    const CellSpan chunk = chunk_holding(m.chunks, at, m.path);
    const auto n = static_cast<std::size_t>(chunk.end - chunk.begin);
    std::string why;
    if (at == chunk.begin && spans[s].end >= chunk.end) {
      done.assign(n, 1);
    } else if (!m.ds.read(-1, chunk, &why)) {
      fail(m.path, cat("dataset '/done' fails to read (", why, ")"));
    }
    for (std::size_t t = s; t < spans.size() && spans[t].begin < chunk.end; ++t)
      for (std::uint64_t p = std::max(spans[t].begin, chunk.begin); p < std::min(spans[t].end, chunk.end); ++p)
        done[static_cast<std::size_t>(p - chunk.begin)] = 1;
    m.ds.done.write_flat(chunk.begin, std::span<const std::uint8_t>(done));
    at = chunk.end;
  }
}

std::vector<std::string> refine_figure_attributes() {
  return {"refine_solved_per_level", "refine_solved", "refine_inherited", "refine_audited", "refine_mismatches",
          "refine_mismatch_bound", "refine_whole_blocks"};
}

void MapWriter::finish(int ranks, const RefineFigures* refine) {
  Impl& m = *impl_;
  checkpoint();
  m.file.set_attribute("cells_done", m.done_count);
  m.file.set_attribute("complete", m.done_count == m.layout.grid.size() ? 1 : 0);
  m.file.set_attribute("ranks", ranks);
  if (refine != nullptr && m.layout.refine_levels > 0) {
    std::vector<double> per_level(refine->solved_per_level.begin(), refine->solved_per_level.end());  // exact below 2^53
    m.file.set_attribute("refine_solved_per_level", std::span<const double>(per_level));
    m.file.set_attribute("refine_solved", refine->solved);
    m.file.set_attribute("refine_inherited", refine->inherited);
    m.file.set_attribute("refine_audited", refine->audited);
    m.file.set_attribute("refine_mismatches", refine->mismatches);
    m.file.set_attribute("refine_mismatch_bound", refine->mismatch_bound);
    m.file.set_attribute("refine_whole_blocks", refine->whole_blocks);
  }
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
  // Written whole into a new file, renamed over `path` when finished.
  NewFile out(path);
  const MapLayout layout{map.grid, map.stored, map.scene_text, map.identity, map.attractors};
  {
    MapWriter w = MapWriter::create_in(out, layout, map.ranks);
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
  }
  out.commit();
}

}  // namespace vibromap
