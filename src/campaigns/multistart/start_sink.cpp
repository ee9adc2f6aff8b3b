#include "start_sink.hpp"

#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

#include "vibromap/core/optimise/point_objective.hpp"
#include "vibromap/io/hdf5_file.hpp"

namespace vibromap::detail {

std::string start_line(const StartRecord& s, std::size_t total, const OptimiseOptions& o) {
  std::ostringstream os;
  const LocalResult& r = s.result;
  os << "optimise: start " << s.spec.index + 1 << "/" << total << " (seed " << s.spec.seed << ", "
     << to_string(s.spec.algorithm) << ", rank " << s.rank << "): ";
  if (r.best) {
    os << objective_quantity(o.objective) << " " << std::setprecision(6)
       << objective_sense(o.objective) * r.evaluations[*r.best].result.value;
  } else {
    os << "no feasible point";
  }
  os << " after " << r.evaluations.size() << " evaluations (" << r.cache_hits << " cache hits), " << r.stop << ", "
     << std::setprecision(3) << r.wall_s << " s\n";
  return os.str();
}

StartSink::StartSink(const StartCodec& codec, const std::vector<StartSpec>& plan, const OptimiseOptions& o,
                     Journal journal, bool progress)
    : ResultSink<StartRecord>(codec), codec_(codec), o_(o), journal_(std::move(journal)), progress_(progress),
      results_(plan.size()) {
  for (const Journal::Record& rec : journal_.records()) {
    ByteReader in(rec.bytes);
    StartRecord s;
    try {
      s = codec_.decode(in);
    } catch (const WireError& e) {
      throw IoError(journal_.path() + ": a damaged start record (" + e.what() + ")");
    }
    if (rec.item >= results_.size() || static_cast<std::uint64_t>(s.spec.index) != rec.item)
      throw IoError(journal_.path() + ": a start record that does not belong to this plan");
    keep(std::move(s));
  }
}

void StartSink::keep(StartRecord record) {
  auto& slot = results_.at(static_cast<std::size_t>(record.spec.index));
  if (!slot) ++done_;
  slot = std::move(record);
}

std::uint64_t StartSink::pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) {
  return scan_pending(from, max, items(), [&](std::uint64_t i) { return results_[static_cast<std::size_t>(i)].has_value(); },
                      out);
}

void StartSink::store_results(const ItemRange& range, std::vector<StartRecord>& results) {
  ByteWriter bytes;
  for (StartRecord& s : results) {
    if (progress_) std::cerr << start_line(s, results_.size(), o_) << std::flush;
    bytes.clear();
    codec_.encode(s, bytes);
    journal_.append(static_cast<std::uint64_t>(s.spec.index), bytes.bytes().data(), bytes.size());
    keep(std::move(s));
  }
  journal_.sync();  // a start takes seconds: one fsync each keeps every finished start
  (void)range;
}

std::string StartSink::note() const {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& s : results_)
    if (s && s->result.best) best = std::min(best, s->result.evaluations[*s->result.best].result.value);
  if (best == std::numeric_limits<double>::infinity()) return {};
  std::ostringstream os;
  os << "best " << objective_quantity(o_.objective) << " " << std::setprecision(6) << objective_sense(o_.objective) * best;
  return os.str();
}

std::vector<StartRecord> StartSink::records() const {
  std::vector<StartRecord> out;
  for (const auto& s : results_)
    if (s) out.push_back(*s);
  return out;
}

}  // namespace vibromap::detail
