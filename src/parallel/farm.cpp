// The work farm: see farm.hpp for the design.

#include "vibromap/parallel/farm.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <mutex>
#include <thread>

#include "mpi_check.hpp"
#include "progress.hpp"
#include "vibromap/parallel/exit_code.hpp"
#include "vibromap/parallel/signals.hpp"

namespace vibromap {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// ---- Wire format ---------------------------------------------------------------------------
// Request, worker -> 0: header, kind, the worker's stop signal (0: none), compute seconds of the
// chunk, the ranges solved (the chunk, or its items before one a stop abandoned), then their
// results (kind results) or an error message (kind failed).
// Reply, 0 -> worker: header, kind, exit code (abort), ranges (work).

constexpr int kTagRequest = 101;
constexpr int kTagReply = 102;
constexpr std::uint32_t kMagic = 0x57464d56;  // "VMFW"
constexpr std::uint32_t kWireVersion = 1;

enum class RequestKind : std::uint8_t { results = 0, failed = 1 };
enum class ReplyKind : std::uint8_t { work = 0, stop = 1, abort = 2 };

void put_header(ByteWriter& w, std::uint32_t codec_version) {
  w.put(kMagic);
  w.put(kWireVersion);
  w.put(codec_version);
}

void check_header(ByteReader& r, std::uint32_t codec_version) {
  if (r.get<std::uint32_t>() != kMagic || r.get<std::uint32_t>() != kWireVersion)
    throw WireError("a rank sent a message of another wire format (mixed vibromap builds?)");
  if (r.get<std::uint32_t>() != codec_version)
    throw WireError("a rank encodes results in another layout (mixed vibromap builds?)");
}

void put_ranges(ByteWriter& w, const std::vector<ItemRange>& ranges) {
  w.put(static_cast<std::uint64_t>(ranges.size()));
  for (const ItemRange& r : ranges) {
    w.put(r.begin);
    w.put(r.end);
  }
}

std::vector<ItemRange> get_ranges(ByteReader& r) {
  const auto n = r.get<std::uint64_t>();
  if (n > r.remaining() / 16) throw WireError("malformed list of item ranges");
  std::vector<ItemRange> ranges(static_cast<std::size_t>(n));
  for (ItemRange& x : ranges) {
    x.begin = r.get<std::uint64_t>();
    x.end = r.get<std::uint64_t>();
    if (x.end < x.begin) throw WireError("malformed item range");
  }
  return ranges;
}

std::uint64_t count_items(const std::vector<ItemRange>& ranges) {
  std::uint64_t n = 0;
  for (const ItemRange& r : ranges) n += r.size();
  return n;
}

// What a rank made of a chunk: the items it solved (all of the chunk, or those before the one a
// stop abandoned), and their compute time.
struct Solved {
  std::vector<ItemRange> done;
  double seconds = 0.0;  // s
};

// Solves the items of `ranges` in order into `out`, until a solver abandons its item for a stop
// signal (ItemStopped): that item's bytes are dropped, the items before it are kept.
Solved solve_ranges(const ItemSolver& solve, const std::vector<ItemRange>& ranges, ByteWriter& out) {
  const auto t0 = Clock::now();
  Solved s;
  for (const ItemRange& r : ranges) {
    for (std::uint64_t i = r.begin; i < r.end; ++i) {
      const std::size_t mark = out.size();
      try {
        solve(i, out);
      } catch (const ItemStopped&) {
        out.bytes().resize(mark);
        s.seconds = seconds_since(t0);
        return s;
      }
      if (!s.done.empty() && s.done.back().end == i) {
        ++s.done.back().end;
      } else {
        s.done.push_back({i, i + 1});
      }
    }
  }
  s.seconds = seconds_since(t0);
  return s;
}

// VIBROMAP_MAX_CHUNK=n caps a chunk at n items (a benchmark knob: one item per request measures
// rank 0's dispatch rate).
std::uint64_t max_chunk(const FarmOptions& o) {
  if (const char* v = std::getenv("VIBROMAP_MAX_CHUNK")) return std::strtoull(v, nullptr, 10);
  return o.max_chunk;
}

// ---- A worker (rank > 0) -------------------------------------------------------------------

void worker_loop(const FarmOptions& o, const ItemSolver& solve, FarmReport& report) {
  ByteWriter request;
  put_header(request, o.codec_version);
  request.put(static_cast<std::uint8_t>(RequestKind::results));
  request.put(static_cast<std::int32_t>(stop_signal()));
  request.put(0.0);
  put_ranges(request, {});
  std::vector<char> reply;
  for (;;) {
    detail::send_bytes(request.bytes(), 0, kTagRequest);
    detail::recv_bytes(0, kTagReply, reply);
    ByteReader r(reply);
    check_header(r, o.codec_version);
    const auto kind = static_cast<ReplyKind>(r.get<std::uint8_t>());
    const auto code = r.get<std::int32_t>();
    if (kind == ReplyKind::abort) throw QuietExit{code};
    if (kind == ReplyKind::stop) return;
    const std::vector<ItemRange> chunk = get_ranges(r);
    request.clear();
    put_header(request, o.codec_version);
    ByteWriter results;
    Solved solved;
    RequestKind outcome = RequestKind::results;
    try {
      solved = solve_ranges(solve, chunk, results);
      report.items_computed += count_items(solved.done);
    } catch (const std::exception& e) {
      outcome = RequestKind::failed;
      results.clear();
      results.put(std::string_view(e.what()));
    }
    request.put(static_cast<std::uint8_t>(outcome));
    request.put(static_cast<std::int32_t>(stop_signal()));
    request.put(solved.seconds);
    put_ranges(request, outcome == RequestKind::results ? solved.done : std::vector<ItemRange>{});
    request.put_bytes(results.bytes().data(), results.size());
  }
}

// ---- Rank 0 --------------------------------------------------------------------------------

class Coordinator {
 public:
  Coordinator(const MpiSession& mpi, const FarmOptions& o, const ItemSolver& solve, FarmSink& sink)
      : o_(o), solve_(solve), sink_(sink), workers_(mpi.size() - 1), ranks_(mpi.size()), max_chunk_(max_chunk(o)),
        resumed_(sink.items_done()), scope_done_(sink.scope_done()), left_(sink.items_pending()),
        progress_(std::cerr, o.progress, isatty(STDERR_FILENO) != 0, o.progress_interval, o.label, o.noun,
                  sink.scope_items(), scope_done_) {}

  FarmReport run() {
    const auto t0 = Clock::now();
    last_checkpoint_ = t0;
    std::thread coordinator([this] { coordinate(); });
    try {
      compute_locally();
    } catch (...) {  // a solver that throws despite its contract: stop every rank
      std::lock_guard lock(mu_);
      fail(std::current_exception(), false);
    }
    local_done_ = true;
    coordinator.join();
    finish();
    report_.wall_s = seconds_since(t0);
    return report_;
  }

 private:
  // The main thread: takes chunks and computes them like any other rank.
  void compute_locally() {
    ByteWriter results;
    for (std::vector<ItemRange> chunk = take_chunk(); !chunk.empty(); chunk = take_chunk()) {
      results.clear();
      const Solved solved = solve_ranges(solve_, chunk, results);  // a stop: the next take_chunk() sees it
      ByteReader r(results.bytes());
      if (!store(solved.done, r, solved.seconds)) return;
    }
  }

  // The next chunk, or none when the items are exhausted, a stop was asked or an error seen.
  std::vector<ItemRange> take_chunk() {
    std::lock_guard lock(mu_);
    std::vector<ItemRange> chunk;
    if (const int s = stop_signal(); s != 0 && report_.stop_signal == 0) report_.stop_signal = s;
    if (stopping() || left_ == 0) return chunk;
    try {
      const std::uint64_t ranks = static_cast<std::uint64_t>(ranks_);
      std::uint64_t n = mean_item_s_ > 0.0 ? static_cast<std::uint64_t>(o_.chunk_seconds / mean_item_s_) : 1;
      n = std::clamp<std::uint64_t>(n, 1, std::max<std::uint64_t>(1, left_ / (2 * ranks)));
      if (max_chunk_ > 0) n = std::min(n, max_chunk_);
      if (o_.block > 1) n = std::max(o_.block, n / o_.block * o_.block);
      fill_buffer(n);
      std::uint64_t taken = 0;
      while (taken < n && !buffer_.empty()) {
        ItemRange& front = buffer_.front();
        const std::uint64_t k = std::min(n - taken, front.size());
        chunk.push_back({front.begin, front.begin + k});
        front.begin += k;
        taken += k;
        if (front.size() == 0) buffer_.erase(buffer_.begin());
      }
      left_ -= std::min(left_, taken);
      if (taken == 0) left_ = 0;
    } catch (...) {
      fail(std::current_exception(), true);
      chunk.clear();
    }
    return chunk;
  }

  // Keeps at least `n` pending items in the buffer while the sink has more.
  void fill_buffer(std::uint64_t n) {
    std::uint64_t have = count_items(buffer_);
    while (have < n && cursor_ < sink_.items()) {
      const std::size_t before = buffer_.size();
      cursor_ = sink_.pending(cursor_, std::max<std::uint64_t>(n - have, 4096), buffer_);
      for (std::size_t i = before; i < buffer_.size(); ++i) have += buffer_[i].size();
    }
  }

  // Stores a chunk's results (either thread). False when the farm is failing.
  bool store(const std::vector<ItemRange>& chunk, ByteReader& results, double compute_s) {
    std::lock_guard lock(mu_);
    if (error_) return false;
    try {
      for (const ItemRange& r : chunk) sink_.store(r, results);
    } catch (...) {
      fail(std::current_exception(), true);
      return false;
    }
    const std::uint64_t n = count_items(chunk);
    report_.items_computed += n;
    if (n > 0) {
      const double per_item = compute_s / static_cast<double>(n);
      mean_item_s_ = mean_item_s_ == 0.0 ? per_item : 0.8 * mean_item_s_ + 0.2 * per_item;
    }
    return true;
  }

  // Records the first error; from the sink (`sink_error`) the workers get the classified code.
  void fail(std::exception_ptr e, bool sink_error) {
    if (error_) return;
    error_ = e;
    sink_error_ = sink_error;
    abort_code_ = sink_error ? (o_.exit_code_of ? o_.exit_code_of(e) : code(ExitCode::io)) : code(ExitCode::internal);
  }

  bool stopping() const { return error_ != nullptr || report_.stop_signal != 0; }

  // The coordinator thread: signals, the other ranks' requests, checkpoints, progress.
  void coordinate() {
    auto pause = std::chrono::microseconds(20);
    int active = workers_;
    while (active > 0 || !local_done_) {
      if (const int s = stop_signal(); s != 0) {
        std::lock_guard lock(mu_);
        if (report_.stop_signal == 0) report_.stop_signal = s;
      }
      bool served = false;
      try {
        served = active > 0 && detail::message_waiting(kTagRequest);
        if (served) serve_one(active);
      } catch (...) {  // MPI itself failed, or a rank spoke another format: end every rank
        std::cerr << "vibromap: error: " << describe_exception(std::current_exception()) << "\n";
        MPI_Abort(MPI_COMM_WORLD, code(ExitCode::internal));
        std::_Exit(code(ExitCode::internal));
      }
      maybe_checkpoint();
      report_progress();
      if (served) {
        pause = std::chrono::microseconds(20);
      } else {
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::microseconds(2000));
      }
    }
  }

  static std::string describe_exception(std::exception_ptr e) {
    try {
      std::rethrow_exception(e);
    } catch (const std::exception& x) {
      return x.what();
    } catch (...) {
      return "unknown error";
    }
  }

  // Receives one request: stores its results, answers with the next chunk, a stop or an abort.
  void serve_one(int& active) {
    const auto t0 = Clock::now();
    std::vector<char> buf;
    const int from = detail::recv_bytes(MPI_ANY_SOURCE, kTagRequest, buf);
    ByteReader r(buf);
    check_header(r, o_.codec_version);
    const auto kind = static_cast<RequestKind>(r.get<std::uint8_t>());
    const auto signal = r.get<std::int32_t>();
    const auto compute_s = r.get<double>();
    const std::vector<ItemRange> done = get_ranges(r);
    if (signal != 0) request_stop(signal);
    if (kind == RequestKind::failed) {
      std::lock_guard lock(mu_);
      fail(std::make_exception_ptr(std::runtime_error("rank " + std::to_string(from) + ": " + r.get_string())), false);
    } else {
      store(done, r, compute_s);
    }
    ByteWriter reply;
    put_header(reply, o_.codec_version);
    std::vector<ItemRange> chunk = take_chunk();
    {
      std::lock_guard lock(mu_);
      const ReplyKind answer = error_ ? ReplyKind::abort : chunk.empty() ? ReplyKind::stop : ReplyKind::work;
      reply.put(static_cast<std::uint8_t>(answer));
      reply.put(static_cast<std::int32_t>(error_ ? abort_code_ : 0));
      if (answer != ReplyKind::work) chunk.clear();
      if (answer != ReplyKind::work) --active;
    }
    put_ranges(reply, chunk);
    detail::send_bytes(reply.bytes(), from, kTagReply);
    ++report_.requests;
    report_.request_s += seconds_since(t0);
  }

  void maybe_checkpoint() {
    if (seconds_since(last_checkpoint_) < o_.checkpoint_interval) return;
    std::lock_guard lock(mu_);
    if (!error_) {
      const auto t0 = Clock::now();
      try {
        sink_.checkpoint();
      } catch (...) {
        fail(std::current_exception(), true);
      }
      const double s = seconds_since(t0);
      report_.checkpoint_s += s;
      report_.checkpoint_max_s = std::max(report_.checkpoint_max_s, s);
      ++report_.checkpoints;
    }
    last_checkpoint_ = Clock::now();
  }

  void report_progress() {
    std::lock_guard lock(mu_);
    progress_.update(scope_done_ + report_.items_computed, sink_.note());
  }

  // After every rank has been answered: the final checkpoint, or the error.
  void finish() {
    report_.items = sink_.items();
    report_.items_resumed = resumed_;
    report_.ranks = ranks_;
    if (error_ && sink_error_) std::rethrow_exception(error_);
    const auto t0 = Clock::now();
    try {
      sink_.finish(!error_ && report_.stop_signal == 0 && resumed_ + report_.items_computed == report_.items);
    } catch (...) {
      if (!error_) throw;  // a sink that fails only now: its error is the run's
    }
    report_.final_checkpoint_s = seconds_since(t0);
    report_.checkpoint_max_s = std::max(report_.checkpoint_max_s, report_.final_checkpoint_s);
    progress_.finish(scope_done_ + report_.items_computed, sink_.note());
    if (error_) std::rethrow_exception(error_);
  }

  const FarmOptions& o_;
  const ItemSolver& solve_;
  FarmSink& sink_;
  const int workers_, ranks_;
  const std::uint64_t max_chunk_;
  const std::uint64_t resumed_;
  const std::uint64_t scope_done_;      // what progress lines count as done before this run
  std::uint64_t left_;                  // pending items not yet handed out (an upper bound)
  std::uint64_t cursor_ = 0;            // where the next sink_.pending() scan starts
  std::vector<ItemRange> buffer_;       // pending items fetched from the sink, not handed out
  double mean_item_s_ = 0.0;            // running mean compute time of an item, s
  detail::ProgressReporter progress_;
  std::mutex mu_;                       // guards everything above and the sink
  std::exception_ptr error_;
  bool sink_error_ = false;
  int abort_code_ = 0;
  std::atomic<bool> local_done_{false};
  Clock::time_point last_checkpoint_;
  FarmReport report_;
};

}  // namespace

FarmReport run_farm(const MpiSession& mpi, const FarmOptions& options, const ItemSolver& solve, FarmSink* sink) {
  if (mpi.rank() != 0) {
    FarmReport report;
    report.ranks = mpi.size();
    const auto t0 = Clock::now();
    worker_loop(options, solve, report);
    report.wall_s = seconds_since(t0);
    return report;
  }
  if (sink == nullptr) throw std::logic_error("run_farm: rank 0 needs a sink");
  return Coordinator(mpi, options, solve, *sink).run();
}

}  // namespace vibromap
