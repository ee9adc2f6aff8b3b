// bench_libraries: vibromap against the libraries a user would pick instead, on the same
// parameter point solved to steady state.
//
//   build/tests/benchmarks/bench_libraries [SCENE.toml ...] [--repeat N] [--stat min|median]
//                                          [--rtols 1e-6,1e-8,...]
//
// For every scene (default: jobs/paper/table1.toml and table2.toml) and every rtol (default
// 1e-6 .. 1e-12) it runs
//   - vibromap solve_point with the scene's options (its default method) and rtol overridden,
//   - vibromap solve_point with steady = integrate and method = dopri5 (brute force),
//   - Boost.Odeint dopri5 with dense output and located events (odeint_solver.hpp),
//   - SUNDIALS CVODE Adams and BDF with root finding and CVodeReInit (cvode_solver.hpp),
// each integrating from the rest state until the stroboscopic samples repeat to 100 * rtol
// (scaled max-norm, vibromap's SteadyStateDetector), and prints status, periods, RHS
// evaluations, the least (--stat median: the median) wall time of N repeats, the steady T_con
// and its relative error against the reference. Then, per library, the fastest run with
// relative error <= 1e-6 against vibromap's fastest such run.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "bench_common.hpp"
#include "cvode_solver.hpp"
#include "odeint_solver.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap::bench {
namespace {

constexpr double kTargetError = 1e-6;

struct Args {
  std::vector<std::string> scenes;
  int repeat = 3;
  bool median = false;  // --stat median: the median wall time of the repeats, else the least
  std::vector<double> rtols{1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
};

struct Row {
  std::string library;
  std::string method;
  double rtol = 0.0;
  RunResult result;
  double wall_s = 0.0;  // least or median of the repeats (Args::median)
  double rel_err = 0.0;
};

// The reference T_con of a scene: the README's tight vibromap runs for the paper's tables.
struct Reference {
  double T_con = NAN;  // NaN: no reference (errors are not computed)
  std::string origin;
};

std::vector<double> parse_list(const std::string& text) {
  std::vector<double> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || !(v > 0.0 && v < 1.0))
      throw std::invalid_argument("--rtols " + text + ": '" + item + "' is not a tolerance in (0, 1)");
    out.push_back(v);
  }
  return out;
}

void usage(std::ostream& os) {
  os << "usage: bench_libraries [SCENE.toml ...] [--repeat N] [--stat min|median] [--rtols 1e-6,1e-8,...]\n"
        "  default scenes: jobs/paper/table1.toml jobs/paper/table2.toml; N = 3 repeats of each run, of which\n"
        "  the least wall time is kept (--stat median: the median)\n";
}

// Returns nullopt after printing usage; rc is then the exit code (0 for --help, 2 for misuse).
std::optional<Args> parse_args(int argc, char** argv, int& rc) {
  Args a;
  rc = 2;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "-h" || arg == "--help") {
      usage(std::cout);
      rc = 0;
      return std::nullopt;
    }
    if (arg == "--repeat" && has_value) {
      a.repeat = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--stat" && has_value) {
      const std::string stat = argv[++i];
      if (stat != "min" && stat != "median") throw std::invalid_argument("--stat " + stat + ": expected min or median");
      a.median = stat == "median";
    } else if (arg == "--rtols" && has_value) {
      a.rtols = parse_list(argv[++i]);
    } else if (!arg.empty() && arg[0] == '-') {
      usage(std::cerr);
      return std::nullopt;
    } else {
      a.scenes.push_back(arg);
    }
  }
  if (a.scenes.empty())
    a.scenes = {VIBROMAP_SOURCE_DIR "/jobs/paper/table1.toml", VIBROMAP_SOURCE_DIR "/jobs/paper/table2.toml"};
  if (a.rtols.empty()) {
    usage(std::cerr);
    return std::nullopt;
  }
  return a;
}

std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0e", v);
  return buf;
}

// Runs f `repeat` times; keeps the first result and the least wall time, or the median (of an
// even count, the mean of the middle two).
std::pair<RunResult, double> timed(int repeat, bool median, const std::function<RunResult()>& f) {
  RunResult first;
  std::vector<double> walls;
  for (int i = 0; i < repeat; ++i) {
    const auto start = std::chrono::steady_clock::now();
    RunResult r = f();
    walls.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (i == 0) first = std::move(r);
  }
  std::sort(walls.begin(), walls.end());
  const std::size_t n = walls.size();
  return {first, !median ? walls.front() : n % 2 ? walls[n / 2] : 0.5 * (walls[n / 2 - 1] + walls[n / 2])};
}

// ---- vibromap's own solver --------------------------------------------------------------

std::string steady_label(SteadyMethod m) { return to_string(m); }
std::string vibromap_label(const PointOptions& o) {
  return to_string(o.integrator.method) + "+" + steady_label(o.analysis.steady);
}

RunResult solve_vibromap(const Scene& scene, const PointOptions& options) {
  const PointSummary s = solve_point(scene.params, options);
  RunResult r;
  r.status = to_string(s.status);
  r.message = s.message;
  if (s.status == SolveStatus::ok && s.steady_method != options.analysis.steady)
    r.message = "fell back to " + steady_label(s.steady_method);
  r.regime = s.regime.label();
  r.periods = s.periods;
  r.rhs_evals = s.counters.rhs_evals;
  r.T_con = s.T_con;
  return r;
}

PointOptions brute_force(PointOptions o) {
  o.analysis.steady = SteadyMethod::integrate;
  o.integrator.method = Method::dopri5;
  return o;
}

// ---- one scene ----------------------------------------------------------------------------

Reference reference_for(const Scene& scene) {
  const std::string stem = std::filesystem::path(scene.path).stem().string();
  if (stem == "table1") return {7.820654471924428e-4, "Table 1, tight vibromap run"};
  if (stem == "table2") return {0.09696184953685727, "Table 2, tight vibromap run"};
  PointOptions o = brute_force(scene.options);
  o.integrator.rtol = 1e-13;
  o.analysis.max_periods = std::max(o.analysis.max_periods, 20'000L);
  const PointSummary s = solve_point(scene.params, o);
  if (s.status != SolveStatus::ok || !(s.T_con > 0.0))
    return {NAN, "none: vibromap dopri5+integrate at rtol 1e-13 gave " + to_string(s.status) + ", " + s.regime.label()};
  return {s.T_con, "vibromap dopri5+integrate at rtol 1e-13, this run"};
}

// Every (library, method) of the comparison as a function of rtol.
struct Contender {
  std::string library;
  std::string method;
  std::function<RunResult(double rtol)> run;
};

std::vector<Contender> contenders(const Scene& scene) {
  const Scene* sc = &scene;
  auto with_rtol = [sc](PointOptions o, double rtol) {
    o.integrator.rtol = rtol;
    return solve_vibromap(*sc, o);
  };
  auto library = [sc](double rtol, auto solve) {
    const Model model(sc->params);
    return solve(model, library_options(*sc, rtol));
  };
  const PointOptions def = scene.options, brute = brute_force(scene.options);
  return {
      {"vibromap", vibromap_label(def), [=](double r) { return with_rtol(def, r); }},
      {"vibromap", vibromap_label(brute), [=](double r) { return with_rtol(brute, r); }},
      {"odeint", "dopri5", [=](double r) { return library(r, solve_odeint); }},
      {"cvode", "adams", [=](double r) {
         return library(r, [](const Model& m, const LibraryOptions& o) { return solve_cvode(m, o, CvodeMethod::adams); });
       }},
      {"cvode", "bdf", [=](double r) {
         return library(r, [](const Model& m, const LibraryOptions& o) { return solve_cvode(m, o, CvodeMethod::bdf); });
       }},
  };
}

std::vector<Row> run_scene(const Scene& scene, const Reference& ref, const Args& args, const std::string& name) {
  std::vector<Row> rows;
  for (const Contender& c : contenders(scene)) {
    for (double rtol : args.rtols) {
      Row row{c.library, c.method, rtol, {}, 0.0, 0.0};
      std::tie(row.result, row.wall_s) = timed(args.repeat, args.median, [&] { return c.run(rtol); });
      // Only a steady result has a T_con to compare; NaN prints as "-".
      row.rel_err = row.result.status == "ok" ? std::abs(row.result.T_con - ref.T_con) / ref.T_con : NAN;
      std::fprintf(stderr, "%s: %s %s rtol %.0e: %s, %.4f s\n", name.c_str(), c.library.c_str(), c.method.c_str(),
                   rtol, row.result.status.c_str(), row.wall_s);
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

// ---- output -------------------------------------------------------------------------------

void print_table(const std::string& name, const Scene& scene, const Reference& ref, const std::vector<Row>& rows) {
  std::printf("\n== %s (%s): T = %.6f s, T_con reference %.16g s (%s)\n", name.c_str(), scene.path.c_str(),
              scene.params.period(), ref.T_con, ref.origin.c_str());
  std::printf("%-9s %-18s %6s %-17s %-11s %8s %11s %9s %-22s %8s\n", "library", "method", "rtol", "status", "regime",
              "periods", "rhs evals", "wall s", "T_con s", "rel err");
  std::vector<std::string> notes;
  for (const Row& r : rows) {
    std::string status = r.result.status;
    if (!r.result.message.empty()) {
      notes.push_back(r.library + " " + r.method + " rtol " + sci(r.rtol) + ": " + r.result.message);
      status += " [" + std::to_string(notes.size()) + "]";
    }
    char err[16] = "-";
    if (std::isfinite(r.rel_err)) std::snprintf(err, sizeof err, "%.1e", r.rel_err);
    std::printf("%-9s %-18s %6.0e %-17s %-11s %8ld %11ld %9.4f %-22.16g %8s\n", r.library.c_str(), r.method.c_str(),
                r.rtol, status.c_str(), r.result.regime.c_str(), r.result.periods, r.result.rhs_evals, r.wall_s,
                r.result.T_con, err);
  }
  for (std::size_t i = 0; i < notes.size(); ++i) std::printf("  [%zu] %s\n", i + 1, notes[i].c_str());
}

// The fastest row of (library, method) with status ok and rel err <= kTargetError.
const Row* fastest_accurate(const std::vector<Row>& rows, const std::string& library, const std::string& method) {
  const Row* best = nullptr;
  for (const Row& r : rows) {
    if (r.library != library || r.method != method) continue;
    if (r.result.status != "ok" || !(r.rel_err <= kTargetError)) continue;
    if (!best || r.wall_s < best->wall_s) best = &r;
  }
  return best;
}

// The smallest error (ok rows) a (library, method) reached, for the "never reached" line.
const Row* most_accurate(const std::vector<Row>& rows, const std::string& library, const std::string& method) {
  const Row* best = nullptr;
  for (const Row& r : rows)
    if (r.library == library && r.method == method && r.result.status == "ok" && (!best || r.rel_err < best->rel_err))
      best = &r;
  return best;
}

void print_ratios(const std::string& name, const Reference& ref, const std::vector<Row>& rows, bool median) {
  const std::string base_method = rows.front().method;  // vibromap with the scene's options
  const Row* base = fastest_accurate(rows, "vibromap", base_method);
  std::printf("\n");
  if (!std::isfinite(ref.T_con)) {
    std::printf("%s: no reference T_con: no ratios\n", name.c_str());
    return;
  }
  if (!base) {
    std::printf("%s: vibromap %s never reached rel err <= %.0e: no ratios\n", name.c_str(), base_method.c_str(), kTargetError);
    return;
  }
  std::printf("%s: time ratio = library's fastest / vibromap's fastest run with rel err <= %.0e (> 1: vibromap faster; "
              "each run's %s wall time of its repeats)\n",
              name.c_str(), kTargetError, median ? "median" : "least");
  std::vector<std::pair<std::string, std::string>> seen;
  for (const Row& r : rows) {
    const std::pair<std::string, std::string> key{r.library, r.method};
    if (r.method == base_method || std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
    seen.push_back(key);
    const Row* other = fastest_accurate(rows, r.library, r.method);
    if (!other) {
      const Row* closest = most_accurate(rows, r.library, r.method);
      std::printf("%s: %s %s never reached rel err <= %.0e", name.c_str(), r.library.c_str(), r.method.c_str(), kTargetError);
      if (closest) std::printf(" (best %.1e at rtol %.0e)", closest->rel_err, closest->rtol);
      std::printf("\n");
      continue;
    }
    std::printf("%s: vibromap %s %.4g s (rtol %.0e) vs %s %s %.4g s (rtol %.0e) at rel err <= %.0e: %.1fx\n", name.c_str(),
                base_method.c_str(), base->wall_s, base->rtol, r.library.c_str(), r.method.c_str(), other->wall_s,
                other->rtol, kTargetError, other->wall_s / base->wall_s);
  }
}

int run(const Args& args) {
  for (const std::string& path : args.scenes) {
    const Scene scene = load_scene(path);
    const std::string name = std::filesystem::path(path).stem().string();
    const Reference ref = reference_for(scene);
    const std::vector<Row> rows = run_scene(scene, ref, args, name);
    print_table(name, scene, ref, rows);
    print_ratios(name, ref, rows, args.median);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace
}  // namespace vibromap::bench

int main(int argc, char** argv) {
  try {
    int rc = 0;
    const auto args = vibromap::bench::parse_args(argc, argv, rc);
    return args ? vibromap::bench::run(*args) : rc;
  } catch (const vibromap::SceneError& e) {
    std::cerr << "bench_libraries: error: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {  // a malformed --rtols or --stat value
    std::cerr << "bench_libraries: error: " << e.what() << "\n";
    return 2;
  }
}
