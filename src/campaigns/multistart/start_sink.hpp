#pragma once
// Internal to the multistart campaign: rank 0's sink of finished starts. Every start is kept in
// memory (a run has tens of starts) and appended to a journal (io/journal.hpp), synced as soon
// as it arrives (a start takes seconds, an fsync microseconds), so `optimise --resume` skips
// every start a killed run finished.

#include <optional>
#include <string>
#include <vector>

#include "start_codec.hpp"
#include "vibromap/io/journal.hpp"

namespace vibromap::detail {

class StartSink : public ResultSink<StartRecord> {
 public:
  // Starts of `plan` with the journal `journal`; records already in it count as done.
  StartSink(const StartCodec& codec, const std::vector<StartSpec>& plan, const OptimiseOptions& o, Journal journal,
            bool progress);

  std::uint64_t items() const override { return results_.size(); }
  std::uint64_t items_done() const override { return done_; }
  std::uint64_t pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) override;
  void store_results(const ItemRange& range, std::vector<StartRecord>& results) override;
  void checkpoint() override { journal_.sync(); }
  void finish(bool) override { journal_.sync(); }
  std::string note() const override;  // the best objective so far

  // Every start, in start order (call when every start is done).
  std::vector<StartRecord> records() const;
  const Journal& journal() const { return journal_; }

 private:
  void keep(StartRecord record);
  const StartCodec& codec_;
  const OptimiseOptions& o_;
  Journal journal_;
  bool progress_;
  std::vector<std::optional<StartRecord>> results_;
  std::uint64_t done_ = 0;
};

// One line per finished start for rank 0's stderr.
std::string start_line(const StartRecord& s, std::size_t total, const OptimiseOptions& o);

}  // namespace vibromap::detail
