// The basins campaign: see basins_run.hpp.

#include "vibromap/campaigns/basins/basins_run.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>

#include "basins_sink.hpp"
#include "vibromap/campaigns/census/follow_state.hpp"
#include "vibromap/campaigns/exit_status.hpp"
#include "vibromap/campaigns/output_target.hpp"
#include "vibromap/campaigns/stoppable.hpp"
#include "vibromap/core/grid.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/scene/identity.hpp"
#include "vibromap/parallel/campaign.hpp"

namespace vibromap {
namespace {

CensusOptions follower_census(const Scene& scene) {
  return detail::follower_census(scene.census.value_or(CensusOptions{}));
}

// What a resume must match: the point's canonical values (its [census] keys included; a
// [sweep] or [optimise] section plays no part in a plane), the plane, its axes and the fixed
// state, one sorted "key = value" line each.
std::string run_identity(const Scene& scene, const BasinsPlane& plane) {
  Scene point = scene;
  point.sweep.reset();
  point.optimise.reset();
  std::vector<std::string> lines;
  std::istringstream in(canonical_text(point, IdentityScope::sweep));
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  lines.push_back("basins.plane = " + plane.name());
  for (std::size_t d = 0; d < 2; ++d) {
    const auto& a = plane.axes[d];
    lines.push_back(cat("basins.axis.", std::to_string(d), " = [", number(a.front(), 17), ", ", number(a.back(), 17), "] n ",
                        std::to_string(a.size())));
  }
  lines.push_back(cat("basins.fixed = ", number(plane.fixed[0], 17), " ", number(plane.fixed[1], 17), " ", number(plane.fixed[2], 17),
                      " ", number(plane.fixed[3], 17)));
  std::sort(lines.begin(), lines.end());
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

BasinsContent new_content(const Scene& scene, const BasinsPlane& plane) {
  BasinsContent c;
  c.scene_text = scene.text;
  c.identity = run_identity(scene, plane);
  c.plane = plane;
  c.soft_kcon = scene.options.analysis.soft_kcon;
  c.labels.assign(static_cast<std::size_t>(plane.pixels()), kNotComputedLabel);
  c.done.assign(c.labels.size(), 0);
  return c;
}

// A file being resumed must be this run's; the error names the values that differ.
BasinsContent resumed_content(const Scene& scene, const BasinsPlane& plane, const OutputTarget& target) {
  BasinsContent have = target.read(read_basins_file);
  const BasinsContent want = new_content(scene, plane);
  target.check_identity(have.identity, want.identity, scene.path,
                        have.labels.size() == want.labels.size() ? "" : "the grid");
  have.scene_text = scene.text;
  return have;
}

// Rank 0: the output (checked and locked), and the sink over a new plane or the file resumed.
std::unique_ptr<detail::BasinsSink> prepare_sink(const Scene& scene, const BasinsPlane& plane,
                                                 const BasinsRunConfig& config, const detail::PixelCodec& codec,
                                                 std::optional<OutputTarget>& target) {
  target.emplace(config.output,
                 OutputPolicy{.overwrite = config.overwrite, .resumable = true, .resume = config.resume});
  return std::make_unique<detail::BasinsSink>(
      codec, scene, follower_census(scene), config.entropy, config.output,
      target->resuming() ? resumed_content(scene, plane, *target) : new_content(scene, plane));
}

// One pixel, on the rank's follower.
detail::PixelResult solve_pixel(CensusFollower& follower, const BasinsPlane& plane, std::uint64_t pixel) {
  if (!plane.overlapping(pixel)) return detail::follow_state(follower, plane.state(pixel));
  detail::PixelResult r;
  r.label = kOverlapLabel;
  return r;
}

FarmOptions farm_options(const BasinsRunConfig& config) {
  FarmOptions o;
  o.label = "basins";
  o.noun = "pixels";
  o.checkpoint_interval = config.checkpoint_interval;
  o.progress = config.progress;
  o.exit_code_of = exit_status_of;
  return o;
}

}  // namespace

BasinsPlane make_basins_plane(const Scene& scene, const BasinsSpec& spec) {
  const auto box = census_box(scene.params, scene.census.value_or(CensusOptions{}));
  Parameters at_rest = scene.params;
  at_rest.initial.reset();
  BasinsPlane plane;
  plane.vars = spec.vars;
  plane.fixed = at_rest.initial_state();
  for (const auto& [var, value] : spec.at) plane.fixed[var] = value;
  for (std::size_t d = 0; d < 2; ++d) {
    const auto& side = box[static_cast<std::size_t>(spec.vars[d])];
    plane.axes[d] = axis_points(side[0], side[1], spec.n[d], AxisScale::lin);
  }
  return plane;
}

BasinsReport run_basins(const MpiSession& mpi, const Scene& scene, const BasinsPlane& plane,
                        const BasinsRunConfig& config) {
  const detail::PixelCodec codec;
  std::optional<OutputTarget> target;
  std::unique_ptr<detail::BasinsSink> sink;
  mpi.agree([&] { sink = prepare_sink(scene, plane, config, codec, target); }, exit_status_of);
  // One follower per rank for the whole run, made at its first pixel.
  std::optional<CensusFollower> follower;
  Campaign<detail::PixelResult> campaign;
  campaign.solve = stoppable([&](std::uint64_t pixel) {
    if (!follower) follower.emplace(scene.params, scene.options, follower_census(scene));
    return solve_pixel(*follower, plane, pixel);
  });
  campaign.codec = &codec;
  campaign.sink = sink.get();
  BasinsReport report;
  report.farm = run_campaign(mpi, farm_options(config), campaign);
  if (!sink) return report;
  report.content = sink->written();
  for (std::uint64_t i = 0; i < plane.pixels() && report.content.done.size() == plane.pixels(); ++i) {
    if (plane.overlapping(i)) continue;
    ++report.coverage.pixels_to_follow;
    if (report.content.done[static_cast<std::size_t>(i)]) ++report.coverage.pixels_followed;
  }
  return report;
}

}  // namespace vibromap
