// The point census on MPI ranks: see point_census_run.hpp.

#include "vibromap/campaigns/basins/point_census_run.hpp"

#include <optional>
#include <string>

#include "pixel_codec.hpp"
#include "vibromap/campaigns/exit_status.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap {
namespace {

// Rank 0: every initial state's label (an index into the global list, or a census label) and
// the totals the summary reports.
class CensusSink final : public ResultSink<detail::PixelResult> {
 public:
  CensusSink(const detail::PixelCodec& codec, const Scene& scene, std::size_t K)
      : ResultSink<detail::PixelResult>(codec), scene_(scene), labels_(K, kUnresolvedLabel), done_(K, 0), left_(K) {}

  std::uint64_t items() const override { return labels_.size(); }
  std::uint64_t items_done() const override { return stored_; }
  std::uint64_t pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) override {
    return scan_pending(from, max, items(), [&](std::uint64_t i) { return done_[i] != 0; }, out);
  }
  void store_results(const ItemRange& range, std::vector<detail::PixelResult>& results) override {
    for (std::uint64_t i = range.begin; i < range.end; ++i) {
      const detail::PixelResult& r = results[static_cast<std::size_t>(i - range.begin)];
      int label = r.label;
      if (label >= 0) {
        label = static_cast<int>(
            match_attractor(scene_.params, scene_.options, found_, first_, r.attractor, static_cast<std::int64_t>(i)));
      }
      labels_[i] = label;
      left_[static_cast<std::size_t>(i)] = r;
      if (!done_[i]) ++stored_;
      done_[i] = 1;
      periods_ += r.periods;
      early_ += r.early ? 1 : 0;
      budget_periods_ += r.budget ? r.periods : 0;
    }
  }
  void checkpoint() override {}  // nothing is written: a stopped run prints no census
  void finish(bool /*complete*/) override {}
  std::string note() const override {
    return cat(std::to_string(found_.size()), " attractor", found_.size() == 1 ? "" : "s");
  }

  // The census, its records made canonical from the first state that reached each.
  CensusSummary summary(const std::vector<Eigen::Vector4d>& ics, const CensusOptions& census) {
    CensusSummary s;
    s.T = scene_.params.period();
    s.K = static_cast<int>(labels_.size());
    const CensusOptions followers = detail::follower_census(census);
    follow_on(followers, ics.front(), s);
    s.periods = periods_;
    s.decided_early = early_;
    s.budget_states = 0;
    for (const detail::PixelResult& r : left_) s.budget_states += r.budget ? 1 : 0;
    s.budget_periods = budget_periods_;
    std::vector<Attractor> escapes = found_;  // canonical_record keeps count and transient only
    for (std::size_t g = 0; g < found_.size(); ++g) {
      found_[g] = canonical_record(scene_.params, scene_.options, followers, ics[static_cast<std::size_t>(first_[g])], found_[g]);
      found_[g].escape_exposure = escapes[g].escape_exposure;
      found_[g].escapes = escapes[g].escapes;
      if (escapes[g].escape_exposure > 0)
        found_[g].escape_rate = static_cast<double>(escapes[g].escapes) / static_cast<double>(escapes[g].escape_exposure);
    }
    std::vector<int> labels = labels_;
    list_attractors(s, found_, labels, census.max_attractors);
    if (census.labels) {
      s.initial_conditions = ics;
      s.labels = labels;
    }
    return s;
  }

 private:
  // State k's new result r: its label in the global list, kept.
  int store_follow_on(std::size_t k, const detail::PixelResult& r) {
    int label = r.label;
    if (label >= 0)
      label = static_cast<int>(
          match_attractor(scene_.params, scene_.options, found_, first_, r.attractor, static_cast<std::int64_t>(k)));
    labels_[k] = label;
    left_[k] = r;
    return label;
  }

  // On a non-periodic set at the end of its budget; with `leaked`, one states left in the
  // rounds past the budget (census.cpp's on_set).
  bool on_set(std::size_t k, const std::vector<bool>* leaked) const {
    const int l = labels_[k];
    if (!left_[k].budget || l < 0 || found_[static_cast<std::size_t>(l)].periodic) return false;
    return leaked == nullptr || (static_cast<std::size_t>(l) < leaked->size() && (*leaked)[static_cast<std::size_t>(l)]);
  }
  bool settling(std::size_t k) const {
    return left_[k].budget && !left_[k].failed && labels_[k] == kUnresolvedLabel;
  }

  // The follow past the budget (census.cpp, transient chaos), on rank 0 once every rank is
  // done: the states left on a leaking set or still settling go on from where their rank left
  // them, in rounds of analysis.max_periods, by the rule of states_to_follow_on.
  void follow_on(const CensusOptions& followers, const Eigen::Vector4d& rest, CensusSummary& s) {
    const long round = scene_.options.analysis.max_periods;
    std::optional<CensusFollower> follower;
    if (!labels_.empty() && (on_set(0, nullptr) || settling(0)) && followers.max_transient_periods > left_[0].periods) {
      // Rest again, at the scene's tolerance, to the cap in one go (census.cpp's rest_to_the_cap).
      follower.emplace(scene_.params, scene_.options, followers);
      const detail::PixelResult r = detail::follow_state(*follower, rest, followers.max_transient_periods, true);
      store_follow_on(0, r);
      periods_ += r.periods;  // the work done: rest's first periods again, at the scene's tolerance
      s.transient_periods += std::max(0L, r.periods - round);
      budget_periods_ += r.budget ? r.periods : 0;
    }
    std::vector<long> spent(labels_.size());
    for (std::size_t k = 0; k < spent.size(); ++k) spent[k] = left_[k].periods;
    if (!spent.empty()) spent[0] = std::max(spent[0], followers.max_transient_periods);  // rest: done above
    std::vector<bool> leaked;
    for (bool first = true;; first = false) {
      std::vector<std::size_t> pending;
      for (std::size_t k = 0; k < labels_.size(); ++k)
        if ((on_set(k, first ? nullptr : &leaked) || settling(k)) && spent[k] + round <= followers.max_transient_periods)
          pending.push_back(k);
      pending = states_to_follow_on(std::move(pending), labels_.size());
      if (pending.empty()) break;
      if (!follower) follower.emplace(scene_.params, scene_.options, followers);
      for (const std::size_t k : pending) {
        const int from = labels_[k];
        const detail::PixelResult r = detail::follow_state(*follower, left_[k].end_state, round);
        const int label = store_follow_on(k, r);
        if (leaked.size() < found_.size()) leaked.resize(found_.size(), false);
        if (from >= 0) {
          found_[static_cast<std::size_t>(from)].escape_exposure += r.periods;
          found_[static_cast<std::size_t>(from)].escapes += label != from ? 1 : 0;
          if (label != from) leaked[static_cast<std::size_t>(from)] = found_[static_cast<std::size_t>(from)].transient = true;
        }
        spent[k] += r.periods;
        periods_ += r.periods;
        s.transient_periods += r.periods;
        budget_periods_ += r.budget ? r.periods : 0;
      }
    }
    for (std::size_t k = 0; k < labels_.size(); ++k) s.transient_states += on_set(k, &leaked) || settling(k) ? 1 : 0;
  }

  const Scene& scene_;
  std::vector<int> labels_;
  std::vector<std::uint8_t> done_;
  std::vector<detail::PixelResult> left_;  // per state: its last result (budget, failed, where it was left)
  std::vector<Attractor> found_;       // the global list, in the order found
  std::vector<std::int64_t> first_;    // per attractor of found_: the first initial state reaching it
  std::uint64_t stored_ = 0;
  long periods_ = 0, budget_periods_ = 0;
  int early_ = 0;
};

}  // namespace

PointCensusReport run_point_census(const MpiSession& mpi, const Scene& scene, const CensusOptions& census,
                                   bool progress) {
  const CensusOptions followers = detail::follower_census(census);
  const std::vector<Eigen::Vector4d> ics = census_initial_conditions(scene.params, census);  // the same on every rank
  mpi.agree(
      [&] {
        if (const std::string err = census_input_error(scene.params, scene.options, followers); !err.empty())
          throw SceneError(cat(scene.path, ": ", err));
        if (static_cast<int>(ics.size()) != census.initial_conditions)
          throw SceneError(cat(scene.path, ": [census] ", kCensusBoxOverlaps));
      },
      exit_status_of);

  const detail::PixelCodec codec;
  std::optional<CensusSink> sink;
  if (mpi.rank() == 0) sink.emplace(codec, scene, ics.size());
  std::optional<CensusFollower> follower;  // one per rank for the whole run, made at its first state
  Campaign<detail::PixelResult> campaign;
  campaign.solve = [&](std::uint64_t i) {
    if (!follower) follower.emplace(scene.params, scene.options, followers);
    return detail::follow_state(*follower, ics[static_cast<std::size_t>(i)]);
  };
  campaign.codec = &codec;
  campaign.sink = sink ? &*sink : nullptr;
  FarmOptions o;
  o.label = "census";
  o.noun = "initial states";
  o.checkpoint_interval = 1e9;  // nothing to make durable
  o.progress = progress;
  o.exit_code_of = exit_status_of;
  PointCensusReport report;
  report.farm = run_campaign(mpi, o, campaign);
  if (sink && report.farm.complete()) {
    report.summary = sink->summary(ics, census);
    report.summary.wall_s = report.farm.wall_s;
  }
  return report;
}

}  // namespace vibromap
