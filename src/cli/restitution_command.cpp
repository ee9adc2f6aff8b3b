// `vibromap restitution`: the effective restitution each contact law gives for a target e, from
// one tightly integrated free two-body impact per (law, e) (core/analysis/point/restitution.hpp).
// The impact is scale-free, so the answer needs no scene. The output is io/restitution_output.hpp.

#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/core/analysis/point/restitution.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/restitution_output.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap::cli {

// `vibromap restitution [--law L]... [--e E]... [--format table|json]`: the effective restitution
// of a free two-body impact for each law (default: every dissipative law) and target e
// (default 0.1, 0.2, ..., 1). Throws SceneError for an unknown law or an e outside (0, 1].
struct RestitutionArgs {
  std::vector<std::string> laws;  // contact law names
  std::vector<double> e;          // target restitutions
  std::string format = "table";   // "table" or "json" (a list of {law, e, chi, e_effective})
};
int restitution_command(const RestitutionArgs& args, std::ostream& out);


namespace {

std::vector<ContactLawKind> laws_of(const RestitutionArgs& args) {
  std::vector<ContactLawKind> laws;
  for (const std::string& name : args.laws) {
    try {
      laws.push_back(parse_contact_law(name));
    } catch (const std::invalid_argument& e) {
      throw SceneError(cat("--law: ", e.what()));
    }
  }
  if (laws.empty())
    for (const ContactLawKind k : all_contact_laws())
      if (k != ContactLawKind::hertz) laws.push_back(k);
  return laws;
}

std::vector<double> targets_of(const RestitutionArgs& args) {
  std::vector<double> e = args.e;
  if (e.empty())
    for (int i = 1; i <= 10; ++i) e.push_back(0.1 * i);
  for (const double x : e)
    if (!(x > 0.0 && x <= 1.0)) throw SceneError(cat("--e ", number(x, 12), ": a restitution must be in (0, 1]"));
  return e;
}

// Every (law, e) within the law's lower limit (min_restitution), checked before any impact.
void check_limits(const std::vector<ContactLawKind>& laws, const std::vector<double>& targets) {
  for (const ContactLawKind law : laws)
    for (const double e : targets)
      if (const double least = min_restitution(law); e < least)
        throw SceneError(cat("--e ", number(e, 12), ": below the lower limit of ", to_string(law), ", e >= ",
                             number(least, 12), " (its damping chi(e) = ", printf_number(contact_law(law).chi(e), "%.3g"),
                             " must be <= ", printf_number(kMaxImpactDamping, "%.3g"), ", the most a free impact is integrated for)"));
}

}  // namespace

int restitution_command(const RestitutionArgs& args, std::ostream& out) {
  const std::vector<ContactLawKind> laws = laws_of(args);
  const std::vector<double> targets = targets_of(args);
  check_limits(laws, targets);
  std::vector<RestitutionResult> rows;
  for (const ContactLawKind law : laws)
    for (const double e : targets) {
      rows.push_back(free_impact_restitution(law, e));
      if (rows.back().status != IntegrationStatus::ok)
        throw std::runtime_error(cat("the free impact of ", to_string(law), " at e = ", number(e, 12),
                                     " failed: ", to_string(rows.back().status)));
    }
  if (args.format == "json")
    write_restitution_json(out, rows);
  else
    write_restitution_table(out, rows);
  return code(ExitCode::ok);
}

namespace {

// The footer, with the lower limits of e (restitution.hpp).
std::string restitution_footer() {
  std::ostringstream os;
  os << "Each law's force is K z^1.5 (1 + chi w / v_in), chi calibrated from e (docs/model.md, 'Dissipative\n"
        "contact laws'). For two free bodies one impact depends on chi alone, so the effective\n"
        "restitution |v_out / v_in| is a property of the law and e: this command integrates that\n"
        "impact at rtol 1e-12, until the bodies part. postprocess/vibromap-post plot_restitution\n"
        "draws the JSON output.\n\n"
        "Lower limit: the slow separation of a heavily damped impact lasts about chi^0.6 contact\n"
        "times, so chi(e) must be at most "
     << kMaxImpactDamping << ": e >= " << min_restitution(ContactLawKind::flores) << " for flores, e >= "
     << min_restitution(ContactLawKind::gonthier) << " for gonthier,\nany e > 0 for hunt-crossley and "
        "lankarani-nikravesh (chi <= 1.5). A smaller e is refused.";
  return os.str();
}

}  // namespace

Command declare_restitution(CLI::App& app) {
  auto args = std::make_shared<RestitutionArgs>();
  CLI::App* r = app.add_subcommand("restitution", "Effective restitution of each contact law for a target e");
  r->add_option("--law", args->laws, "Contact law (repeatable; default: every dissipative law)")
      ->allow_extra_args(false)
      ->type_name("hunt-crossley|lankarani-nikravesh|flores|gonthier|hertz");
  r->add_option("--e", args->e,
                 "Target restitution in (0, 1] (repeatable; default 0.1, 0.2, ..., 1; flores and gonthier have a lower "
                 "limit, below)")
      ->check(kNumber)
      ->allow_extra_args(false)
      ->type_name("E");
  add_format_option(*r, args->format, "Output on stdout: a table, or JSON (a list of {law, e, chi, e_effective})");
  return {.app = r, .footer = restitution_footer(), .topic = "the contact laws' effective restitution", .campaign = {},
          .run = [args](std::ostream& out) { return restitution_command(*args, out); }};
}

}  // namespace vibromap::cli
