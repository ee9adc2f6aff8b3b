// The family pass of a census map: see map_families.hpp.

#include "vibromap/io/map_families.hpp"

#include <chrono>
#include <cmath>
#include <span>

#include "attribute_seal.hpp"
#include "map_layout.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"

namespace vibromap {
namespace {

constexpr const char* kTable = "families";

// One chunk of the census datasets the matching reads.
struct CensusChunk {
  std::size_t A = 0;
  std::vector<std::uint8_t> done;
  std::vector<std::int32_t> listed, n, k;
  std::vector<std::int8_t> regime, soft;
  std::vector<double> fraction, strobe;

  void read(const Hdf5File& file, const CellSpan& span) {
    const auto cells = static_cast<std::size_t>(span.end - span.begin);
    const auto get = [&](const char* name, auto& buffer, std::size_t width) {
      buffer.resize(cells * width);
      file.open_dataset(name).read_flat(span.begin * width, std::span(buffer));
    };
    get("done", done, 1);
    get("attractors", listed, 1);
    get("attractor_regime", regime, A);
    get("attractor_n", n, A);
    get("attractor_k", k, A);
    get("attractor_soft", soft, A);
    get("attractor_fraction", fraction, A);
    get("attractor_strobe", strobe, A * detail::kMapStrobePoints * 4);
  }

  // Cell i's attractors as the matching sees them, in motion scales `s`.
  std::vector<FamilyNode> nodes(std::size_t i, const MotionScale& s) const {
    std::vector<FamilyNode> out(std::min<std::size_t>(static_cast<std::size_t>(std::max(listed[i], 0)), A));
    for (std::size_t a = 0; a < out.size(); ++a) {
      const std::size_t at = i * A + a;
      FamilyNode& node = out[a];
      node.regime = Regime{static_cast<RegimeKind>(std::max<int>(regime[at], 0)), n[at], k[at]};
      const double* x = &strobe[at * detail::kMapStrobePoints * 4];
      node.periodic = !std::isnan(x[0]);  // an orbit (periodic, or a periodic no-contact motion) has its states
      node.soft = soft[at] == 1;
      node.fraction = fraction[at];
      for (std::size_t p = 0; node.periodic && p < detail::kMapStrobePoints; ++p, x += 4) {
        if (std::isnan(x[0])) break;
        node.points.emplace_back(x[0] / s.length, x[1] / s.length, x[2] / s.speed, x[3] / s.speed);
      }
    }
    return out;
  }
};

// The labeller's output, a chunk at a time: /family (provisional labels) and /family_flags.
class LabelWriter {
 public:
  LabelWriter(Hdf5File& file, std::vector<CellSpan> spans, std::size_t A)
      : family_(file.open_dataset("family")), flags_(file.open_dataset("family_flags")), spans_(std::move(spans)), A_(A) {}

  void put(std::uint64_t cell, std::span<const std::int64_t> labels, std::span<const std::int8_t> flags) {
    while (cell >= spans_[at_].end) flush();
    if (labels_.empty()) {
      const auto width = static_cast<std::size_t>(spans_[at_].end - spans_[at_].begin) * A_;
      labels_.assign(width, -1);
      bits_.assign(width, -1);
    }
    const auto base = static_cast<std::size_t>(cell - spans_[at_].begin) * A_;
    for (std::size_t a = 0; a < labels.size() && a < A_; ++a) {
      labels_[base + a] = static_cast<std::int32_t>(labels[a]);
      bits_[base + a] = flags[a];
    }
  }
  // Writes the chunk being filled (every cell of it emitted) and moves to the next.
  void flush() {
    if (!labels_.empty()) {
      family_.write_flat(spans_[at_].begin * A_, std::span<const std::int32_t>(labels_));
      flags_.write_flat(spans_[at_].begin * A_, std::span<const std::int8_t>(bits_));
    }
    labels_.clear();
    bits_.clear();
    ++at_;
  }

 private:
  Dataset family_, flags_;
  std::vector<CellSpan> spans_;
  std::size_t A_, at_ = 0;
  std::vector<std::int32_t> labels_;
  std::vector<std::int8_t> bits_;
};

// Pass 2: the provisional labels in /family replaced by the families' ids, chunk by chunk.
void write_ids(Hdf5File& file, const std::vector<CellSpan>& spans, std::size_t A, const FamilyLabeller& labeller) {
  Dataset family = file.open_dataset("family");
  std::vector<std::int32_t> v;
  for (const CellSpan& s : spans) {
    v.resize(static_cast<std::size_t>(s.end - s.begin) * A);
    family.read_flat(s.begin * A, std::span<std::int32_t>(v));
    for (std::int32_t& x : v) x = labeller.id(x);
    family.write_flat(s.begin * A, std::span<const std::int32_t>(v));
  }
}

// /families, made again.
void write_table(Hdf5File& file, const std::vector<FamilyRecord>& families, double distance) {
  if (file.exists(kTable)) file.remove(kTable);
  Group g = file.create_group(kTable);
  g.set_attribute("count", static_cast<std::int64_t>(families.size()));
  g.set_attribute("distance", distance);
  g.set_attribute("long_name", "the families of attractors across the map, by id (io/map_families.hpp)");
  if (families.empty()) return;
  DatasetOptions o;
  o.fletcher32 = true;
  std::vector<int> ids(families.size());  // the table's coordinate (netCDF readers need one per axis)
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<int>(i);
  Dataset id = g.write_dataset("id", std::span<const int>(ids), {}, o);
  id.make_dimension_scale("family");
  const auto column = [&](const char* name, auto value) {
    using T = decltype(value(families.front()));
    std::vector<T> v;
    for (const FamilyRecord& r : families) v.push_back(value(r));
    g.write_dataset(name, std::span<const T>(v), {}, o).attach_dimension_scale(id, 0);
  };
  std::vector<std::string> regimes;
  for (const FamilyRecord& r : families) regimes.push_back(family_regimes_text(r));
  g.write_strings("regimes", regimes).attach_dimension_scale(id, 0);
  column("cells", [](const FamilyRecord& r) { return std::int64_t{r.cells}; });
  column("soft_cells", [](const FamilyRecord& r) { return std::int64_t{r.soft_cells}; });
  column("edge_cells", [](const FamilyRecord& r) { return std::int64_t{r.edge_cells}; });
  column("label_changes", [](const FamilyRecord& r) { return std::int64_t{r.label_changes}; });
  column("fraction_min", [](const FamilyRecord& r) { return r.fraction_min; });
  column("fraction_max", [](const FamilyRecord& r) { return r.fraction_max; });
  column("first_cell", [](const FamilyRecord& r) { return static_cast<std::int64_t>(r.first_cell); });
  column("last_cell", [](const FamilyRecord& r) { return static_cast<std::int64_t>(r.last_cell); });
  column("first_attractor", [](const FamilyRecord& r) { return r.first_attractor; });
}

}  // namespace

std::string family_regimes_text(const FamilyRecord& f) {
  std::string out;
  for (const Regime& g : f.regimes) out.append(out.empty() ? "" : " ").append(g.label());
  return out;
}

FamilyPassReport write_map_families(const std::string& path, const std::function<MotionScale(std::uint64_t)>& scale_of,
                                    double distance) {
  const auto t0 = std::chrono::steady_clock::now();
  const MapLayout layout = read_map_layout(path);
  if (layout.attractors == 0) detail::fail(path, "not a census map (no attractors): it has no families");
  Hdf5File file(path, FileMode::read_write, detail::writer_options());
  detail::verify_file(file, kMapFormat);
  const Shape shape = layout.grid.shape();
  const std::vector<CellSpan> spans = detail::chunk_spans(shape, detail::map_chunk_shape(shape));
  const std::size_t A = layout.attractors;

  FamilyPassReport report;
  report.distance = distance;
  report.cells = layout.grid.size();
  LabelWriter out(file, spans, A);
  FamilyLabeller labeller(std::vector<std::size_t>(shape.begin(), shape.end()), distance,
                          [&](std::uint64_t cell, std::span<const std::int64_t> labels,
                              std::span<const std::int8_t> flags) { out.put(cell, labels, flags); });
  CensusChunk chunk;
  chunk.A = A;
  for (const CellSpan& s : spans) {
    chunk.read(file, s);
    for (std::uint64_t c = s.begin; c < s.end; ++c) {
      const auto i = static_cast<std::size_t>(c - s.begin);
      const bool done = chunk.done[i] != 0;
      std::vector<FamilyNode> nodes = done ? chunk.nodes(i, scale_of(c)) : std::vector<FamilyNode>{};
      report.nodes += nodes.size();
      labeller.add(c, std::move(nodes), done);
    }
  }
  labeller.finish();
  if (!spans.empty()) out.flush();
  write_ids(file, spans, A, labeller);
  write_table(file, labeller.families(), distance);
  file.flush();
  file.sync();
  file.close();
  report.families = labeller.families();
  report.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

}  // namespace vibromap
