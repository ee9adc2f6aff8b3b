// The point census on MPI ranks: see point_census_run.hpp.

#include "vibromap/campaigns/census/point_census_run.hpp"

#include <algorithm>
#include <optional>
#include <string>

#include "vibromap/campaigns/census/follow_state.hpp"
#include "vibromap/campaigns/exit_status.hpp"
#include "vibromap/campaigns/stoppable.hpp"
#include "vibromap/core/analysis/census/critical_shock.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap {
namespace {

// Rank 0: every initial state's outcome (its label an index into the global list, or a census
// label) and the totals the summary reports.
class CensusSink final : public ResultSink<detail::PixelResult> {
 public:
  CensusSink(const detail::PixelCodec& codec, const Scene& scene, std::size_t K)
      : ResultSink<detail::PixelResult>(codec), scene_(scene), left_(K), done_(K, 0) {}

  std::uint64_t items() const override { return left_.size(); }
  std::uint64_t items_done() const override { return stored_; }
  std::uint64_t pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) override {
    return scan_pending(from, max, items(), [&](std::uint64_t i) { return done_[i] != 0; }, out);
  }
  void store_results(const ItemRange& range, std::vector<detail::PixelResult>& results) override {
    for (std::uint64_t i = range.begin; i < range.end; ++i) {
      const detail::PixelResult& r = results[static_cast<std::size_t>(i - range.begin)];
      left_[static_cast<std::size_t>(i)] = outcome(static_cast<std::size_t>(i), r);
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

  // The census, after the follow past the budget (on this rank, from where the ranks left the
  // states), its records made canonical from the first state that reached each.
  CensusSummary summary(const std::vector<Eigen::Vector4d>& ics, const CensusOptions& census);

 private:
  // State k's result as an outcome whose label indexes the global list.
  CensusFollower::Outcome outcome(std::size_t k, const detail::PixelResult& r) {
    CensusFollower::Outcome f;
    f.label = r.label;
    if (r.label >= 0)
      f.label = static_cast<int>(
          match_attractor(scene_.params, scene_.options, found_, first_, r.attractor, static_cast<std::int64_t>(k)));
    f.early = r.early;
    f.periods = r.periods;
    f.budget = r.budget;
    f.failed = r.failed;
    f.end_state = r.end_state;
    return f;
  }

  const Scene& scene_;
  std::vector<CensusFollower::Outcome> left_;  // per state: its last outcome
  std::vector<std::uint8_t> done_;
  std::vector<Attractor> found_;       // the global list, in the order found
  std::vector<std::int64_t> first_;    // per attractor of found_: the first initial state reaching it
  std::uint64_t stored_ = 0;
  long periods_ = 0, budget_periods_ = 0;
  int early_ = 0;
};

CensusSummary CensusSink::summary(const std::vector<Eigen::Vector4d>& ics, const CensusOptions& census) {
  const CensusOptions followers = detail::follower_census(census);
  std::optional<CensusFollower> follower;
  const PastBudget past = follow_past_budget(
      left_, ics.front(), scene_.options.analysis.max_periods, followers.max_transient_periods,
      [&](int label) { return found_[static_cast<std::size_t>(label)].periodic; },
      [&](std::size_t k, const Eigen::Vector4d& x0, long budget, bool exact) {
        if (!follower) follower.emplace(scene_.params, scene_.options, followers);
        return outcome(k, detail::follow_state(*follower, x0, budget, exact));
      });
  CensusSummary s;
  s.T = scene_.params.period();
  s.K = static_cast<int>(left_.size());
  s.periods = periods_ + past.periods;
  s.decided_early = early_;
  s.budget_states = static_cast<int>(std::count_if(left_.begin(), left_.end(), [](const auto& f) { return f.budget; }));
  s.budget_periods = budget_periods_ + past.budget_periods;
  s.transient_periods = past.transient_periods;
  s.transient_states = past.transient_states;
  for (std::size_t g = 0; g < found_.size(); ++g) {
    found_[g] = canonical_record(scene_.params, scene_.options, followers, ics[static_cast<std::size_t>(first_[g])], found_[g]);
    record_escape(found_[g], past, g);
  }
  std::vector<int> labels;
  for (const CensusFollower::Outcome& f : left_) labels.push_back(f.label);
  list_attractors(s, found_, labels, census.max_attractors);
  if (census.labels) {
    s.initial_conditions = ics;
    s.labels = labels;
  }
  add_critical_shocks(scene_.params, scene_.options, followers, s);  // rank 0 alone, after the census
  return s;
}

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
  campaign.solve = stoppable([&](std::uint64_t i) {
    if (!follower) follower.emplace(scene.params, scene.options, followers);
    return detail::follow_state(*follower, ics[static_cast<std::size_t>(i)]);
  });
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
