// The work farm under mpiexec (-n 1, 2 and 3; tests/parallel/CMakeLists.txt): a made-up campaign
// whose result is a known function of the item, an in-memory sink that records what it got, and
// the farm's contracts: every pending item stored exactly once with its own result whatever the
// rank count, resume skips what is done, a stop signal on any rank ends the run with a final
// checkpoint (an item a stop abandoned is not stored), and a failing sink or solver ends every rank (no rank left waiting: a hang fails
// the test by ctest's timeout).

#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "vibromap/parallel/campaign.hpp"
#include "vibromap/parallel/exit_code.hpp"
#include "vibromap/parallel/signals.hpp"

namespace vibromap {
namespace {

const MpiSession* g_mpi = nullptr;

struct Value {
  std::uint64_t item = 0;
  double square_root = 0.0;  // the result: sqrt(item), exactly as std::sqrt gives it
  std::int32_t rank = -1;    // who computed it (not part of the "map")
};

class ValueCodec : public ResultCodec<Value> {
 public:
  std::uint32_t version() const override { return 7; }
  void encode(const Value& v, ByteWriter& out) const override {
    out.put(v.item);
    out.put(v.square_root);
    out.put(v.rank);
  }
  Value decode(ByteReader& in) const override {
    Value v;
    v.item = in.get<std::uint64_t>();
    v.square_root = in.get<double>();
    v.rank = in.get<std::int32_t>();
    return v;
  }
};

// An in-memory sink with a done mask: what is stored becomes done at the next checkpoint.
class MemorySink : public ResultSink<Value> {
 public:
  MemorySink(const ValueCodec& codec, std::uint64_t items, std::vector<std::uint8_t> done = {})
      : ResultSink<Value>(codec), values_(items), stored_(items, 0), done_(std::move(done)) {
    if (done_.empty()) done_.assign(items, 0);
  }
  std::uint64_t items() const override { return values_.size(); }
  std::uint64_t items_done() const override {
    std::uint64_t n = 0;
    for (const auto d : done_) n += d;
    return n;
  }
  std::uint64_t pending(std::uint64_t from, std::uint64_t max, std::vector<ItemRange>& out) override {
    return scan_pending(from, max, items(), [&](std::uint64_t i) { return done_[i] != 0; }, out);
  }
  void store_results(const ItemRange& range, std::vector<Value>& results) override {
    if (fail_after_ >= 0 && stores_++ >= fail_after_) throw std::runtime_error("disk full (made up)");
    for (std::uint64_t i = range.begin; i < range.end; ++i) {
      const Value& v = results[i - range.begin];
      EXPECT_EQ(v.item, i);
      values_[i] = v;
      ++stored_[i];
      unflushed_.push_back(i);
    }
  }
  void checkpoint() override {
    for (const auto i : unflushed_) done_[i] = 1;
    unflushed_.clear();
    ++checkpoints_;
  }
  void finish(bool complete) override {
    checkpoint();
    finished_ = true;
    complete_ = complete;
  }

  std::vector<Value> values_;
  std::vector<int> stored_;
  std::vector<std::uint8_t> done_;
  std::vector<std::uint64_t> unflushed_;
  int checkpoints_ = 0;
  bool finished_ = false, complete_ = false;
  int fail_after_ = -1, stores_ = 0;
};

Value solve_value(std::uint64_t item) {
  // A little work per item, so that chunks grow beyond one item and every rank gets some.
  volatile double x = 0.0;
  for (int k = 0; k < 2000; ++k) x = x + 1e-9 * k;
  return {item, std::sqrt(static_cast<double>(item)), g_mpi->rank()};
}

FarmOptions quiet_options() {
  FarmOptions o;
  o.progress = false;
  o.checkpoint_interval = 0.01;
  o.chunk_seconds = 0.002;
  return o;
}

TEST(Farm, StoresEveryItemOnceWithItsOwnResult) {
  constexpr std::uint64_t kItems = 5000;
  const ValueCodec codec;
  MemorySink sink(codec, kItems);
  const FarmReport report =
      run_campaign<Value>(*g_mpi, quiet_options(), {solve_value, &codec, g_mpi->rank() == 0 ? &sink : nullptr});
  if (g_mpi->rank() != 0) return;
  EXPECT_TRUE(report.complete());
  EXPECT_EQ(report.items_computed, kItems);
  EXPECT_TRUE(sink.finished_ && sink.complete_);
  std::set<int> ranks;
  for (std::uint64_t i = 0; i < kItems; ++i) {
    ASSERT_EQ(sink.stored_[i], 1) << "item " << i;
    EXPECT_EQ(sink.values_[i].square_root, std::sqrt(static_cast<double>(i)));
    EXPECT_EQ(sink.done_[i], 1);
    ranks.insert(sink.values_[i].rank);
  }
  EXPECT_EQ(static_cast<int>(ranks.size()), g_mpi->size()) << "every rank computes, rank 0 included";
  if (g_mpi->size() > 1) {
    EXPECT_GT(report.requests, 0);
  }
}

TEST(Farm, ResumeComputesOnlyWhatIsNotDone) {
  constexpr std::uint64_t kItems = 3000;
  std::vector<std::uint8_t> done(kItems, 0);
  for (std::uint64_t i = 0; i < kItems; ++i) done[i] = (i % 3 == 0 || (i > 1000 && i < 2000)) ? 1 : 0;
  const ValueCodec codec;
  MemorySink sink(codec, kItems, done);
  const std::uint64_t before = sink.items_done();
  const FarmReport report =
      run_campaign<Value>(*g_mpi, quiet_options(), {solve_value, &codec, g_mpi->rank() == 0 ? &sink : nullptr});
  if (g_mpi->rank() != 0) return;
  EXPECT_EQ(report.items_resumed, before);
  EXPECT_EQ(report.items_computed, kItems - before);
  EXPECT_TRUE(report.complete());
  for (std::uint64_t i = 0; i < kItems; ++i) EXPECT_EQ(sink.stored_[i], done[i] ? 0 : 1) << "item " << i;
}

// A stop signal that reaches only the last rank, mid-run: every rank stops, what was computed is
// stored and checkpointed, and the report names the signal.
TEST(Farm, StopSignalOnAnyRankStopsEveryRankAfterAFinalCheckpoint) {
  constexpr std::uint64_t kItems = 200000;
  const int signalled_rank = g_mpi->size() - 1;
  const ValueCodec codec;
  MemorySink sink(codec, kItems);
  std::uint64_t solved = 0;
  const auto solve = [&](std::uint64_t item) {
    if (g_mpi->rank() == signalled_rank && ++solved == 500) request_stop(SIGUSR1);
    return solve_value(item);
  };
  const FarmReport report = run_campaign<Value>(*g_mpi, quiet_options(), {solve, &codec, g_mpi->rank() == 0 ? &sink : nullptr});
  if (g_mpi->rank() != 0) return;
  EXPECT_EQ(report.stop_signal, SIGUSR1);
  EXPECT_FALSE(report.complete());
  EXPECT_TRUE(sink.finished_);
  EXPECT_FALSE(sink.complete_);
  std::uint64_t stored = 0;
  for (std::uint64_t i = 0; i < kItems; ++i) {
    stored += static_cast<std::uint64_t>(sink.stored_[i]);
    EXPECT_EQ(sink.done_[i], sink.stored_[i]) << "whatever was stored is checkpointed";
  }
  EXPECT_EQ(stored, report.items_computed);
  EXPECT_GE(stored, 500u);
  EXPECT_LT(stored, kItems / 2) << "the farm stopped long before the end";
}

// A solver that abandons its item for a stop, as an integration polling the stop flag does
// (campaigns/stoppable.hpp): that item is not stored, the items solved before it are, every
// rank stops, and what was stored is checkpointed.
TEST(Farm, AnItemAbandonedForAStopIsNotStored) {
  constexpr std::uint64_t kItems = 200000;
  constexpr std::uint64_t kAbandoned = 777;
  const ValueCodec codec;
  MemorySink sink(codec, kItems);
  const auto solve = [&](std::uint64_t item) {
    if (item == kAbandoned) {
      request_stop(SIGTERM);
      throw ItemStopped{};
    }
    return solve_value(item);
  };
  const FarmReport report = run_campaign<Value>(*g_mpi, quiet_options(), {solve, &codec, g_mpi->rank() == 0 ? &sink : nullptr});
  if (g_mpi->rank() != 0) return;
  EXPECT_EQ(report.stop_signal, SIGTERM);
  EXPECT_FALSE(report.complete());
  EXPECT_TRUE(sink.finished_);
  EXPECT_EQ(sink.stored_[kAbandoned], 0);
  std::uint64_t stored = 0;
  for (std::uint64_t i = 0; i < kItems; ++i) {
    stored += static_cast<std::uint64_t>(sink.stored_[i]);
    EXPECT_EQ(sink.done_[i], sink.stored_[i]) << "whatever was stored is checkpointed";
  }
  EXPECT_EQ(stored, report.items_computed);
  EXPECT_LT(stored, kItems / 2) << "the farm stopped long before the end";
  if (g_mpi->size() == 1) {  // one rank solves in order: everything before the abandoned item, nothing after
    EXPECT_EQ(stored, kAbandoned);
    for (std::uint64_t i = 0; i < kAbandoned; ++i) EXPECT_EQ(sink.stored_[i], 1) << "item " << i;
  }
}

// The sink fails on its third store: rank 0 throws the sink's error, every other rank ends
// with the classified exit code, and nobody waits forever.
TEST(Farm, FailingSinkEndsEveryRankWithTheClassifiedCode) {
  constexpr std::uint64_t kItems = 100000;
  const ValueCodec codec;
  MemorySink sink(codec, kItems);
  sink.fail_after_ = 2;
  FarmOptions o = quiet_options();
  o.exit_code_of = [](std::exception_ptr) { return code(ExitCode::io); };
  try {
    run_campaign<Value>(*g_mpi, o, {solve_value, &codec, g_mpi->rank() == 0 ? &sink : nullptr});
    ADD_FAILURE() << "rank " << g_mpi->rank() << " returned normally";
  } catch (const QuietExit& e) {
    EXPECT_NE(g_mpi->rank(), 0);
    EXPECT_EQ(e.code, code(ExitCode::io));
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(g_mpi->rank(), 0);
    EXPECT_STREQ(e.what(), "disk full (made up)");
  }
  if (g_mpi->rank() == 0) {
    EXPECT_FALSE(sink.finished_) << "a failing sink is not asked to finish";
  }
}

// A solver that throws on the last rank: rank 0 reports it, writes a final checkpoint of what
// it holds, and every rank ends.
TEST(Farm, ThrowingSolverOnAWorkerStopsEveryRank) {
  constexpr std::uint64_t kItems = 100000;
  const ValueCodec codec;
  MemorySink sink(codec, kItems);
  const int bad_rank = g_mpi->size() - 1;
  std::uint64_t solved = 0;
  const auto solve = [&](std::uint64_t item) {
    if (g_mpi->rank() == bad_rank && ++solved == 300) throw std::runtime_error("solver bug (made up)");
    return solve_value(item);
  };
  try {
    run_campaign<Value>(*g_mpi, quiet_options(), {solve, &codec, g_mpi->rank() == 0 ? &sink : nullptr});
    ADD_FAILURE() << "rank " << g_mpi->rank() << " returned normally";
  } catch (const QuietExit& e) {
    EXPECT_NE(g_mpi->rank(), 0);
    EXPECT_EQ(e.code, code(ExitCode::internal));
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(g_mpi->rank(), 0);
    const std::string what = e.what();
    if (bad_rank == 0) {
      EXPECT_EQ(what, "solver bug (made up)");
    } else {
      EXPECT_EQ(what, "rank " + std::to_string(bad_rank) + ": solver bug (made up)");
    }
  }
  if (g_mpi->rank() == 0) {
    EXPECT_TRUE(sink.finished_) << "what was stored gets its final checkpoint";
  }
}

}  // namespace
}  // namespace vibromap

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  vibromap::MpiSession mpi;
  vibromap::g_mpi = &mpi;
  return RUN_ALL_TESTS();
}
