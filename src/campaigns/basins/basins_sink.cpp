#include "basins_sink.hpp"

#include <algorithm>
#include <numeric>

namespace vibromap::detail {

BasinsSink::BasinsSink(const PixelCodec& codec, const Scene& scene, CensusOptions census, BasinEntropyOptions entropy,
                       std::string path, BasinsContent start)
    : ResultSink<PixelResult>(codec), scene_(scene), census_(std::move(census)), entropy_(entropy), path_(std::move(path)),
      content_(std::move(start)) {
  done_ = static_cast<std::uint64_t>(std::count(content_.done.begin(), content_.done.end(), 1));
}

std::uint64_t BasinsSink::pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) {
  return scan_pending(from, max, items(), [&](std::uint64_t i) { return content_.done[i] != 0; }, out);
}

// The index of `a` in the global list (discovery order), added when no attractor matches.
int BasinsSink::global_label(const Attractor& a, std::uint64_t pixel) {
  return static_cast<int>(match_attractor(scene_.params, scene_.options, content_.attractors, content_.first_pixel, a,
                                          static_cast<std::int64_t>(pixel)));
}

void BasinsSink::store_results(const ItemRange& range, std::vector<PixelResult>& results) {
  for (std::uint64_t i = range.begin; i < range.end; ++i) {
    const PixelResult& r = results[static_cast<std::size_t>(i - range.begin)];
    int label = r.label;
    if (label >= 0) {
      label = global_label(r.attractor, i);
      ++content_.attractors[static_cast<std::size_t>(label)].count;
    }
    content_.labels[i] = label;
    if (!content_.done[i]) ++done_;
    content_.done[i] = 1;
  }
  dirty_ = true;
}

// Each attractor's record as a fresh follower finds it from the attractor's first pixel: the
// record a rank kept depends on which of its pixels found the orbit first (the orbit's refined
// digits, the cyclic shift of its stroboscopic states), this one only on the labels.
void BasinsSink::canonicalise() {
  for (std::size_t g = 0; g < content_.attractors.size(); ++g)
    content_.attractors[g] =
        canonical_record(scene_.params, scene_.options, census_,
                         content_.plane.state(static_cast<std::uint64_t>(content_.first_pixel[g])), content_.attractors[g]);
}

BasinsContent BasinsSink::numbered(bool complete) const {
  BasinsContent c = content_;
  c.complete = complete;
  const std::size_t A = c.attractors.size();
  std::vector<std::size_t> order(A);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const int ca = content_.attractors[a].count, cb = content_.attractors[b].count;
    return ca != cb ? ca > cb : content_.first_pixel[a] < content_.first_pixel[b];
  });
  std::vector<int> new_index(A);
  long followed = 0;
  for (std::size_t i = 0; i < c.labels.size(); ++i)
    if (c.done[i] && c.labels[i] != kOverlapLabel) ++followed;
  for (std::size_t k = 0; k < A; ++k) {
    new_index[order[k]] = static_cast<int>(k);
    c.attractors[k] = content_.attractors[order[k]];
    c.first_pixel[k] = content_.first_pixel[order[k]];
    Attractor& a = c.attractors[k];
    a.fraction = followed > 0 ? static_cast<double>(a.count) / static_cast<double>(followed) : 0.0;
    a.fraction_stderr = 0.0;  // a plane is no random sample
  }
  for (std::size_t i = 0; i < c.labels.size(); ++i) {
    if (!c.done[i]) c.labels[i] = kNotComputedLabel;
    else if (c.labels[i] >= 0) c.labels[i] = new_index[static_cast<std::size_t>(c.labels[i])];
  }
  c.entropy = basin_entropy(c.labels, static_cast<int>(c.plane.axes[0].size()), static_cast<int>(c.plane.axes[1].size()),
                            entropy_);
  return c;
}

void BasinsSink::write(bool complete) {
  written_ = numbered(complete);
  write_basins_file(path_, written_);
  dirty_ = false;
}

void BasinsSink::checkpoint() {
  if (dirty_) write(false);
}

void BasinsSink::finish(bool complete) {
  if (complete) canonicalise();
  if (dirty_ || complete || written_.labels.empty()) write(complete);
}

std::string BasinsSink::note() const {
  return std::to_string(content_.attractors.size()) + " attractor" + (content_.attractors.size() == 1 ? "" : "s");
}

}  // namespace vibromap::detail
