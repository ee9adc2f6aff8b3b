#pragma once
// The typed face of the farm (farm.hpp). A campaign is four small things:
//   - a plan: how many items (its sink's items()), and which remain (its sink's pending());
//   - solve(item) -> Result: pure, calls the core, runs on every rank;
//   - a codec: Result <-> bytes, field by field, with a layout version;
//   - a sink on rank 0: stores results as they arrive and makes them durable at checkpoints.
// A new campaign is a new folder of these four things that calls run_campaign, never a copy of
// the farm.

#include <cstdint>
#include <functional>
#include <vector>

#include "vibromap/parallel/farm.hpp"

namespace vibromap {

template <class Result>
class ResultCodec {
 public:
  virtual ~ResultCodec() = default;
  virtual std::uint32_t version() const = 0;  // changes whenever the layout does
  virtual void encode(const Result& result, ByteWriter& out) const = 0;
  virtual Result decode(ByteReader& in) const = 0;  // throws WireError on truncated input
};

// A sink of typed results: FarmSink's store() decodes a range and hands it over whole.
template <class Result>
class ResultSink : public FarmSink {
 public:
  explicit ResultSink(const ResultCodec<Result>& codec) : codec_(codec) {}
  // The results of the items of `range`, in order (results.size() == range.size()).
  virtual void store_results(const ItemRange& range, std::vector<Result>& results) = 0;

  void store(const ItemRange& range, ByteReader& in) final {
    batch_.clear();
    batch_.reserve(static_cast<std::size_t>(range.size()));
    for (std::uint64_t i = range.begin; i < range.end; ++i) batch_.push_back(codec_.decode(in));
    store_results(range, batch_);
  }

 private:
  const ResultCodec<Result>& codec_;
  std::vector<Result> batch_;
};

template <class Result>
struct Campaign {
  std::function<Result(std::uint64_t item)> solve;  // every rank; an item's trouble is its result
  const ResultCodec<Result>* codec = nullptr;       // every rank
  ResultSink<Result>* sink = nullptr;               // rank 0; nullptr elsewhere
};

// Collective: runs the campaign on every rank of `mpi` (farm.hpp for distribution,
// checkpoints, signals and errors).
template <class Result>
FarmReport run_campaign(const MpiSession& mpi, FarmOptions options, const Campaign<Result>& campaign) {
  options.codec_version = campaign.codec->version();
  const ItemSolver solve = [&campaign](std::uint64_t item, ByteWriter& out) {
    campaign.codec->encode(campaign.solve(item), out);
  };
  return run_farm(mpi, options, solve, campaign.sink);
}

}  // namespace vibromap
