// The accuracy study: see accuracy_run.hpp.

#include "vibromap/campaigns/accuracy/accuracy_run.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include "vibromap/core/text.hpp"

namespace vibromap {
namespace {

// The shortest text that reads back to the same double; "nan" and "inf" for the others.
std::string exact(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  std::array<char, 64> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), x);
  return std::string(buf.data(), res.ptr);
}

// A CSV field, quoted when it holds a comma, a quote or a line break (RFC 4180).
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

constexpr const char* kCsvHeader =
    "method,setting,integrator,steady,rtol,atol,rk4_steps,status,regime,regime_matches,steady_used,"
    "newton_iterations,wall_s,rhs_evals,steps,periods,T_con,F_max,k_con,rel_err_T_con,rel_err_F_max,"
    "rel_err_k_con,note";

std::string csv_line(const AccuracyRow& r) {
  const std::vector<std::string> fields = {
      r.label, r.setting, to_string(r.method), to_string(r.steady), exact(r.rtol), exact(r.atol),
      std::to_string(r.rk4_steps), to_string(r.status), r.regime, r.regime_matches ? "1" : "0",
      to_string(r.steady_used), std::to_string(r.newton_iterations), exact(r.wall_s), std::to_string(r.rhs_evals),
      std::to_string(r.steps), std::to_string(r.periods), exact(r.T_con), exact(r.F_max), exact(r.k_con),
      exact(r.rel_err_T_con), exact(r.rel_err_F_max), exact(r.rel_err_k_con), r.note};
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) line += ',';
    line += csv_field(fields[i]);
  }
  return line;
}

}  // namespace

std::string accuracy_csv(const AccuracyReport& report) {
  std::string text = cat(kCsvHeader, "\n", csv_line(report.reference), "\n");
  for (const AccuracyRow& r : report.rows) text += csv_line(r) + "\n";
  return text;
}

namespace {

// The cases' options must be valid (what solve_point would reject as invalid_input; the
// scene's parameters passed validate() when it was read), checked before hours of solving.
void check_cases(const Scene& scene, const std::vector<AccuracyCase>& cases) {
  for (const AccuracyCase& c : cases) {
    for (const std::string& err : {validate(c.options.integrator), validate(c.options.analysis)}) {
      if (err.empty()) continue;
      std::string msg = scene.path;
      msg += ": accuracy case ";
      msg += c.method_label;
      msg += " ";
      msg += setting_label(c.options.integrator);
      msg += ": ";
      msg += err;
      throw SceneError(msg);
    }
  }
}

}  // namespace

AccuracyStudy::AccuracyStudy(const Scene& scene, const std::string& csv, bool overwrite)
    : scene_(scene),
      cases_(default_accuracy_cases(scene.options)),
      reference_(default_accuracy_reference(scene.options)) {
  if (!csv.empty()) {
    check_output(csv, {.option = "--csv", .overwrite = overwrite});
    csv_.emplace(csv);
  }
  check_cases(scene, cases_);
  check_cases(scene, {reference_});
}

AccuracyReport AccuracyStudy::run(const AccuracyProgress& progress) const {
  return run_accuracy(scene_.params, cases_, reference_, progress);
}

void AccuracyStudy::write_csv(const AccuracyReport& report) {
  if (!csv_) return;
  csv_->write(accuracy_csv(report));
  csv_->commit();
}

}  // namespace vibromap
