// The MPI side of `vibromap optimise`: see multistart_runner.hpp for the design.

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <type_traits>

#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/map_file.hpp"
#include "vibromap/io/optimise_file.hpp"
#include "vibromap/io/scene/keys.hpp"
#include "vibromap/io/trajectory_file.hpp"
#include "vibromap/parallel/multistart_runner.hpp"
#include "mpi_messages.hpp"
#include "vibromap/core/optimise/point_objective.hpp"
#include "vibromap/parallel/sweep_runner.hpp"

namespace vibromap {
namespace {

using detail::broadcast_status;
using detail::mpi_check;
using detail::recv_bytes;
using detail::send_bytes;
using Clock = std::chrono::steady_clock;

constexpr int kTagRequest = 11;  // worker -> 0: the last start's result (none at first), and a request
constexpr int kTagStart = 12;    // 0 -> worker: the next start's index; -1 means stop
constexpr auto kPollPause = std::chrono::milliseconds(1);  // starts take seconds: a 1 ms answer is prompt
constexpr int kVerifyTrajectoryPeriods = 2;  // periods of the best point's trajectory when the scene keeps none
constexpr double kDistinct = 0.01;  // best points closer than this in every scaled variable are one point

// Set-up outcomes rank 0 broadcasts (0: go on; otherwise the other ranks exit with it).
constexpr int kStatusOk = 0;
constexpr int kStatusIo = 1;
constexpr int kStatusScene = 2;
constexpr int kStatusInterrupted = 3;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// --- Bytes: a start's result travels as a flat buffer ---------------------------------------

class ByteWriter {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const char*>(&v);
    buf_.insert(buf_.end(), p, p + sizeof(T));
  }
  void put(const std::string& s) {
    put(static_cast<std::uint64_t>(s.size()));
    buf_.insert(buf_.end(), s.begin(), s.end());
  }
  void put(const std::vector<double>& v) {
    put(static_cast<std::uint64_t>(v.size()));
    for (const double x : v) put(x);
  }
  std::vector<char>& bytes() { return buf_; }

 private:
  std::vector<char> buf_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::vector<char>& buf) : buf_(buf) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    if (pos_ + sizeof(T) > buf_.size()) throw std::runtime_error("optimise: truncated message from a rank");
    T v;
    std::memcpy(&v, buf_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  std::string get_string() {
    const auto n = static_cast<std::size_t>(get<std::uint64_t>());
    if (pos_ + n > buf_.size()) throw std::runtime_error("optimise: truncated message from a rank");
    std::string s(buf_.data() + pos_, n);
    pos_ += n;
    return s;
  }
  std::vector<double> get_doubles() {
    std::vector<double> v(static_cast<std::size_t>(get<std::uint64_t>()));
    for (double& x : v) x = get<double>();
    return v;
  }

 private:
  const std::vector<char>& buf_;
  std::size_t pos_ = 0;
};

void put_evaluation(ByteWriter& w, const EvaluationRecord& e) {
  w.put(e.x);
  w.put(e.result.value);
  w.put(e.result.violation);
  w.put(static_cast<std::uint8_t>(e.result.feasible));
  w.put(static_cast<std::int32_t>(e.result.regime.kind));
  w.put(static_cast<std::int32_t>(e.result.regime.n));
  w.put(static_cast<std::int32_t>(e.result.regime.k));
  w.put(static_cast<std::int32_t>(e.result.stable));
  w.put(e.result.measures);
  w.put(e.result.message);
  w.put(e.wall_s);
}

EvaluationRecord get_evaluation(ByteReader& r) {
  EvaluationRecord e;
  e.x = r.get_doubles();
  e.result.value = r.get<double>();
  e.result.violation = r.get<double>();
  e.result.feasible = r.get<std::uint8_t>() != 0;
  e.result.regime.kind = static_cast<RegimeKind>(r.get<std::int32_t>());
  e.result.regime.n = r.get<std::int32_t>();
  e.result.regime.k = r.get<std::int32_t>();
  e.result.stable = r.get<std::int32_t>();
  e.result.measures = r.get_doubles();
  e.result.message = r.get_string();
  e.wall_s = r.get<double>();
  return e;
}

std::vector<char> pack(const StartRecord& s) {
  ByteWriter w;
  const LocalResult& r = s.result;
  w.put(static_cast<std::int32_t>(s.spec.index));
  w.put(static_cast<std::int32_t>(s.rank));
  w.put(static_cast<std::uint64_t>(r.evaluations.size()));
  for (const EvaluationRecord& e : r.evaluations) put_evaluation(w, e);
  w.put(static_cast<std::int64_t>(r.best ? static_cast<std::int64_t>(*r.best) : -1));
  w.put(r.stop);
  w.put(static_cast<std::int32_t>(r.nlopt_code));
  w.put(static_cast<std::int64_t>(r.calls));
  w.put(static_cast<std::int64_t>(r.cache_hits));
  w.put(r.wall_s);
  return std::move(w.bytes());
}

StartRecord unpack(const std::vector<char>& buf, const std::vector<StartSpec>& plan) {
  ByteReader r(buf);
  StartRecord s;
  const auto index = static_cast<std::size_t>(r.get<std::int32_t>());
  if (index >= plan.size()) throw std::runtime_error("optimise: a rank answered for an unknown start");
  s.spec = plan[index];
  s.rank = r.get<std::int32_t>();
  s.result.evaluations.resize(static_cast<std::size_t>(r.get<std::uint64_t>()));
  for (EvaluationRecord& e : s.result.evaluations) e = get_evaluation(r);
  if (const auto best = r.get<std::int64_t>(); best >= 0) s.result.best = static_cast<std::size_t>(best);
  s.result.stop = r.get_string();
  s.result.nlopt_code = r.get<std::int32_t>();
  s.result.calls = static_cast<long>(r.get<std::int64_t>());
  s.result.cache_hits = static_cast<long>(r.get<std::int64_t>());
  s.result.wall_s = r.get<double>();
  return s;
}




// Rank 0 runs `step`, tells every rank whether it worked, and rethrows its error; the other
// ranks wait for the verdict and leave quietly with the error's exit code.
template <class Step>
void agreed(int rank, Step step) {
  if (rank != 0) {
    if (const int code = broadcast_status(kStatusOk); code != kStatusOk) throw QuietExit{code};
    return;
  }
  try {
    step();
  } catch (const SceneError&) {
    broadcast_status(kStatusScene);
    throw;
  } catch (...) {
    broadcast_status(kStatusIo);
    throw;
  }
  broadcast_status(kStatusOk);
}

// --- One start, on whichever rank --------------------------------------------------------------

StartRecord run_one(const Scene& scene, const std::vector<Seed>& seeds, const StartSpec& spec, int rank) {
  StartRecord rec{spec, {}, rank};
  try {
    rec.result = run_start(scene.params, scene.options, *scene.optimise,
                           seeds.at(static_cast<std::size_t>(spec.seed)), spec.algorithm);
  } catch (const std::exception& e) {  // a start's trouble is its result, never the run's
    rec.result.stop = std::string("FAILURE (") + e.what() + ")";
  }
  return rec;
}

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

// Rank 0's queue of starts and the results gathered so far.
class StartQueue {
 public:
  StartQueue(const std::vector<StartSpec>& plan, const OptimiseOptions& o, bool progress)
      : plan_(plan), o_(o), progress_(progress), results_(plan.size()) {}

  std::optional<StartSpec> take() {
    std::lock_guard lock(mu_);
    if (next_ >= plan_.size()) return std::nullopt;
    return plan_[next_++];
  }

  void store(StartRecord r) {
    std::lock_guard lock(mu_);
    if (progress_) std::cerr << start_line(r, plan_.size(), o_) << std::flush;
    const auto i = static_cast<std::size_t>(r.spec.index);
    results_.at(i) = std::move(r);
  }

  std::vector<StartRecord> results() {
    std::lock_guard lock(mu_);
    return results_;
  }

  const std::vector<StartSpec>& plan() const { return plan_; }

 private:
  const std::vector<StartSpec>& plan_;
  const OptimiseOptions& o_;
  bool progress_;
  std::mutex mu_;
  std::size_t next_ = 0;
  std::vector<StartRecord> results_;
};

// Rank 0's coordinator thread: answers the other ranks until each has been told to stop.
void serve(StartQueue& queue, int workers) {
  int active = workers;
  while (active > 0) {
    int flag = 0;
    MPI_Status st;
    mpi_check(MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &flag, &st), "MPI_Iprobe");
    if (!flag) {
      std::this_thread::sleep_for(kPollPause);
      continue;
    }
    int from = 0;
    const std::vector<char> buf = recv_bytes(st.MPI_SOURCE, kTagRequest, &from);
    if (!buf.empty()) queue.store(unpack(buf, queue.plan()));
    const std::optional<StartSpec> next = queue.take();
    int index = next ? next->index : -1;
    mpi_check(MPI_Send(&index, 1, MPI_INT, from, kTagStart, MPI_COMM_WORLD), "MPI_Send");
    if (index < 0) --active;
  }
}

void worker_loop(const Scene& scene, const std::vector<Seed>& seeds, const std::vector<StartSpec>& plan, int rank) {
  std::vector<char> result;
  for (;;) {
    send_bytes(result, 0, kTagRequest);
    int index = -1;
    mpi_check(MPI_Recv(&index, 1, MPI_INT, 0, kTagStart, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
    if (index < 0) return;
    result = pack(run_one(scene, seeds, plan.at(static_cast<std::size_t>(index)), rank));
  }
}

// Rank 0: computes starts itself while the coordinator thread serves the other ranks.
std::vector<StartRecord> coordinate(const Scene& scene, const std::vector<Seed>& seeds,
                                    const std::vector<StartSpec>& plan, int ranks, bool progress) {
  StartQueue queue(plan, *scene.optimise, progress);
  std::exception_ptr error;
  std::thread coordinator([&] {
    try {
      serve(queue, ranks - 1);
    } catch (...) {
      error = std::current_exception();
    }
  });
  for (auto spec = queue.take(); spec; spec = queue.take()) queue.store(run_one(scene, seeds, *spec, 0));
  coordinator.join();
  if (error) std::rethrow_exception(error);
  return queue.results();
}

// --- Seeds ----------------------------------------------------------------------------------

// The scene without its [optimise] section: what the seeding sweep's map records, so that
// changing an [optimise] setting does not make the map "another scene" for --resume.
Scene sweep_scene(const Scene& scene) {
  Scene s = scene;
  s.optimise.reset();
  const auto at = s.text.find("\n[optimise]\n");
  if (at != std::string::npos) {
    const auto next = s.text.find("\n[", at + 1);
    s.text.erase(at, next == std::string::npos ? std::string::npos : next - at);
  }
  return s;
}

// Rank 0: the best cells of a map file as seeds.
std::vector<Seed> seeds_from_map(const Scene& scene, const std::string& path) {
  const SweepMap map = read_map(path);
  try {
    return select_seeds(map.grid, map.cells, map.done, map.stored, scene.params, *scene.optimise,
                        scene.options.analysis.hertz_limit);
  } catch (const std::invalid_argument& e) {
    throw SceneError(scene.path + ": [optimise] seeds from " + path + ": " + e.what());
  }
}

void check_output(const OptimiseRunConfig& config) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(config.output, ec) && !config.overwrite)
    throw SceneError(config.output + ": already exists; use --overwrite to replace it");
  const fs::path dir = fs::path(config.output).parent_path();
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw IoError(config.output + ": cannot write the optimisation: directory '" + dir.string() + "' does not exist");
}

// Runs the scene's [sweep] into config.map_output on every rank. Returns false (on every
// rank) when a signal stopped it.
bool run_seeding_sweep(const Scene& scene, const OptimiseRunConfig& config, int rank, OptimiseReport& report) {
  SweepRunConfig sc;
  sc.output = config.map_output;
  sc.overwrite = config.overwrite;
  sc.resume = !config.overwrite;  // an existing map of this scene is finished or reused
  sc.progress = config.progress;
  const SweepReport sweep = run_sweep(sweep_scene(scene), sc);
  for (const int sig : {SIGINT, SIGTERM, SIGUSR1}) std::signal(sig, SIG_DFL);  // run_sweep's handlers end with it
  report.sweep_wall_s = sweep.wall_s;
  const int status = broadcast_status(rank == 0 && sweep.interrupted ? kStatusInterrupted : kStatusOk);
  return status == kStatusOk;
}

// Every rank gets rank 0's seeds (only their x: the rest stays on rank 0 for the report).
void broadcast_seeds(std::vector<Seed>& seeds, std::size_t variables) {
  std::uint64_t n = seeds.size();
  mpi_check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
  std::vector<double> x(static_cast<std::size_t>(n) * variables);
  for (std::size_t i = 0; i < seeds.size(); ++i) std::copy(seeds[i].x.begin(), seeds[i].x.end(), x.begin() + static_cast<long>(i * variables));
  mpi_check(MPI_Bcast(x.data(), static_cast<int>(x.size()), MPI_DOUBLE, 0, MPI_COMM_WORLD), "MPI_Bcast");
  seeds.resize(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < seeds.size(); ++i)
    seeds[i].x.assign(x.begin() + static_cast<long>(i * variables), x.begin() + static_cast<long>((i + 1) * variables));
}

// Step 1 of multistart_runner.hpp: the seeds on every rank. Returns false when the seeding
// sweep was interrupted.
bool make_seeds(const Scene& scene, const OptimiseRunConfig& config, int rank, OptimiseReport& report,
                std::vector<Seed>& seeds) {
  const OptimiseOptions& o = *scene.optimise;
  if (o.map.empty() && scene.sweep && !run_seeding_sweep(scene, config, rank, report)) return false;
  report.seeds_from = !o.map.empty() ? o.map : scene.sweep ? config.map_output : "scene";
  agreed(rank, [&] {
    seeds = !o.map.empty() ? seeds_from_map(scene, o.map)
            : scene.sweep  ? seeds_from_map(scene, config.map_output)
                           : std::vector<Seed>{scene_seed(scene.params, o)};
  });
  broadcast_seeds(seeds, o.variables.size());
  return true;
}

// --- Best points ---------------------------------------------------------------------------

// The scene text of a best point: the scene, and the --set overrides that give the point.
std::string point_scene_text(const Scene& scene, const VerifiedPoint& v) {
  std::string text = scene.text;
  text += "\n# best point of vibromap optimise; vibromap run SCENE with:";
  for (const FreeVariable& f : scene.optimise->variables) text += " --set " + parameter_override(f.name, get_parameter(v.params, f.name));
  return text + "\n";
}

// Step 3 on rank 0: re-solves the best points and writes the best one's trajectory.
void verify_best(const Scene& scene, const OptimiseRunConfig& config, OptimiseReport& report) {
  const OptimiseOptions& o = *scene.optimise;
  const auto t0 = Clock::now();
  const Box box(o.variables);
  const auto points = best_points(report.starts, box, o.best, std::max(kDistinct, 10.0 * o.local.xtol_rel));
  const int periods = std::max(scene.options.analysis.trajectory_periods, kVerifyTrajectoryPeriods);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& [start, evaluation] = points[i];
    const int keep = i == 0 && !config.trajectory.empty() ? periods : 0;
    report.best.push_back(verify_point(scene.params, scene.options, o, report.starts[start], evaluation, keep));
  }
  if (!report.best.empty() && !report.best.front().integrate.trajectory.empty()) {
    write_trajectory(config.trajectory, report.best.front().integrate, point_scene_text(scene, report.best.front()));
    report.trajectory_file = std::filesystem::path(config.trajectory).filename().string();
  }
  report.verify_wall_s = seconds_since(t0);
}

}  // namespace

OptimiseReport run_optimise(const Scene& scene, const OptimiseRunConfig& config) {
  if (!scene.optimise) throw SceneError(scene.path + ": no [optimise] section: nothing to optimise (see 'vibromap keys')");
  const auto t0 = Clock::now();
  int rank = 0, size = 1;
  mpi_check(MPI_Comm_rank(MPI_COMM_WORLD, &rank), "MPI_Comm_rank");
  mpi_check(MPI_Comm_size(MPI_COMM_WORLD, &size), "MPI_Comm_size");
  OptimiseReport report;
  report.ranks = size;
  agreed(rank, [&] { check_output(config); });
  std::vector<Seed> seeds;
  if (!make_seeds(scene, config, rank, report, seeds)) {
    if (rank != 0) throw QuietExit{kStatusInterrupted};
    report.interrupted = true;
    return report;
  }
  const std::vector<StartSpec> plan = plan_starts(seeds.size(), scene.optimise->algorithms);
  if (rank != 0) {
    worker_loop(scene, seeds, plan, rank);
    return OptimiseReport{};
  }
  if (config.progress)
    std::cerr << "optimise: " << plan.size() << " starts (" << seeds.size() << " seeds x "
              << scene.optimise->algorithms.size() << " algorithms) on " << size << " rank" << (size > 1 ? "s" : "")
              << ", seeds from " << report.seeds_from << "\n";
  const auto t_starts = Clock::now();
  report.variables.clear();
  for (const FreeVariable& v : scene.optimise->variables) report.variables.push_back(v.name);
  report.measures = PointObjective(scene.params, scene.options, *scene.optimise).measure_names();
  report.seeds = seeds;
  report.starts = coordinate(scene, seeds, plan, size, config.progress);
  report.optimise_wall_s = seconds_since(t_starts);
  verify_best(scene, config, report);
  report.wall_s = seconds_since(t0);
  write_optimise_file(config.output, report, *scene.optimise, scene.text);
  return report;
}

}  // namespace vibromap
