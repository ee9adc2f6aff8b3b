#include "attractor_set.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "vibromap/core/analysis/point/section.hpp"

namespace vibromap::census_detail {

namespace {

// T_con, v_in and impulse of the longest of the impacts [first, last) (all 0 without impacts).
template <class It>
void set_longest(Attractor& a, It first, It last) {
  const It longest = std::max_element(first, last, [](const Impact& x, const Impact& y) { return x.T_con < y.T_con; });
  if (longest == last) return;
  a.T_con = longest->T_con;
  a.v_in = longest->v_in;
  a.impulse = longest->impulse;
}

constexpr double kShorterPeriod = 100.0;   // P^d(y) = y within this many Newton tolerances
// The capture test (captured()): it applies from this scaled offset down, where the
// linearisation may describe the map, and asks the linear prediction to hold to this fraction.
constexpr double kLinearOffset = 1.0;      // largest level tried: V = c0 reaches this scaled offset
constexpr double kSmallestLevel = 1e-4;     // smallest level tried, in units of c0 (offsets 1/100 of the largest)
constexpr double kLevelMargin = 0.5;        // states are captured below this fraction of the verified level
constexpr int kLevelSamples = 16;           // sample points on a level set
constexpr double kContraction = 0.5;        // the capture test works on M^J with |M^J| <= this
constexpr int kMaxCyclePeriods = 200;       // periods J n at most (|mu| > 0.9965 per period: no capture)
constexpr double kSameRecurrent = 0.5;      // share of samples in known cells for the same attractor
constexpr std::size_t kRoomFactor = 4;      // attractors kept: this many times max_attractors
constexpr double kKnownCandidate = 1e-2;    // scaled distance of a loose Newton solution from a known orbit (discover)

// The solution S of the discrete Lyapunov equation M^T S M - S = -I (M stable), by the
// Kronecker form (M^T (x) M^T - I) vec(S) = -vec(I).
Eigen::Matrix4d lyapunov_matrix(const Eigen::Matrix4d& M) {
  Eigen::Matrix<double, 16, 16> A;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) A.block<4, 4>(4 * i, 4 * j) = M(j, i) * M.transpose();
  A -= Eigen::Matrix<double, 16, 16>::Identity();
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  const Eigen::Matrix<double, 16, 1> rhs = -Eigen::Map<const Eigen::Matrix<double, 16, 1>>(I.data());
  const Eigen::Matrix<double, 16, 1> x = A.partialPivLu().solve(rhs);
  Eigen::Matrix4d S = Eigen::Map<const Eigen::Matrix4d>(x.data());
  return 0.5 * (S + S.transpose());
}

double quadratic(const Eigen::Matrix4d& S, const Eigen::Vector4d& d) { return d.dot(S * d); }

std::uint64_t cell_hash(const Cell& c) {
  std::uint64_t h = 1469598103934665603ULL;  // FNV-1a over the four indices' bytes
  for (std::int64_t k : c)
    for (int b = 0; b < 8; ++b) {
      h ^= static_cast<std::uint64_t>(k >> (8 * b)) & 0xffU;
      h *= 1099511628211ULL;
    }
  return h;
}

}  // namespace

AttractorSet::AttractorSet(const Parameters& p, const PointOptions& options, const CensusOptions& census)
    : p_(p), options_(options), census_(census), model_(p), scale_(model_),
      unit_(scale_.length(), scale_.length(), scale_.speed(), scale_.speed()), follow_(options) {
  if (census.early_stop) follow_.integrator.rtol = std::max(census.rtol, options.integrator.rtol);
}

double AttractorSet::newton_tol() const {
  return newton_tolerance(options_);
}

bool AttractorSet::full() const {
  return records_.size() >= kRoomFactor * static_cast<std::size_t>(census_.max_attractors);
}

std::vector<double> AttractorSet::phases() const {
  std::vector<double> out;
  for (const auto& o : orbits_)
    out.push_back(o && o->capture ? o->phase : std::numeric_limits<double>::quiet_NaN());
  return out;
}

Eigen::Vector4d AttractorSet::offset(std::size_t i, const State& at_phase) const {
  return ((at_phase - orbits_[i]->y).array() / unit_).matrix();
}

// The capture rule. V(d) = d^T S d is the quadratic Lyapunov function of the orbit's
// linearisation M (M^T S M - S = -I, all Floquet multipliers inside the unit circle), d the
// scaled offset from the orbit's point at its section. When the orbit was found, the largest
// level c of V was looked for (verified_level) such that on sample points of the ellipsoid
// V = c the map P^n decreases V by at least half of what M alone guarantees; the region
// V <= c / 2 is then taken as inside the basin. An initial state is captured when its offset
// is in that region on two successive cycles, the second with a smaller V.
// Why this is safe: V <= c is a trapping region of P^n when V falls on all of its boundary;
// the falls are checked on sample points, not everywhere, hence the factor 2 of margin and the
// second cycle. A state passing by the orbit on a chaotic transient stays outside such a
// region. The census tests compare every label with brute-force integration that has no
// early stop.
bool AttractorSet::captured(std::size_t i, const Offsets& d) const {
  const Orbit& o = *orbits_[i];
  return !d.empty() && o.level > 0.0 && quadratic(o.S, d.back()) <= kLevelMargin * o.level;
}

double AttractorSet::level_ratio(std::size_t i, const Eigen::Vector4d& d) const {
  const Orbit& o = *orbits_[i];
  return o.level > 0.0 ? quadratic(o.S, d) / (kLevelMargin * o.level) : std::numeric_limits<double>::infinity();
}

// The largest level c = c0 / 2^k (k = 0, 1, ...; c0: the ellipsoid V = c0 reaches a scaled
// offset of kLinearOffset) at which every sample point d of V = c has V(P^n(y + d) - y) <=
// (1 - 1 / (2 lambda_max(S))) V(d): half the fall M guarantees. 0 when none down to
// kSmallestLevel c0.
double AttractorSet::verified_level(const Orbit& o, const Model& section, IntegrationCounters& counters) const {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> es(o.S);
  if (es.info() != Eigen::Success || es.eigenvalues().minCoeff() <= 0.0) return 0.0;
  const Eigen::Matrix4d to_offset = es.eigenvectors() * es.eigenvalues().cwiseSqrt().cwiseInverse().asDiagonal();
  const double fall = 1.0 - 0.5 / es.eigenvalues().maxCoeff();
  const Eigen::Matrix4d Sinv = o.S.inverse();
  const double c0 = kLinearOffset * kLinearOffset / Sinv.diagonal().maxCoeff();
  // Sample directions on the unit sphere of V: the axes of the ellipsoid both ways, then
  // fixed pseudo-random ones.
  std::vector<Eigen::Vector4d> w;
  for (int i = 0; i < 4; ++i) {
    w.push_back(Eigen::Vector4d::Unit(i));
    w.push_back(-Eigen::Vector4d::Unit(i));
  }
  SplitMix64 draws(0x5eed);
  auto uniform = [&draws] { return 2.0 * draws.uniform() - 1.0; };
  while (static_cast<int>(w.size()) < kLevelSamples) {
    const Eigen::Vector4d v(uniform(), uniform(), uniform(), uniform());
    if (v.norm() > 1e-3) w.push_back(v.normalized());
  }
  // A direction that fails at one level most likely fails at the next one down too: it moves
  // to the front, so that a failing level costs one sample's J cycles, not several. (Whether
  // all samples pass does not depend on their order: the level found is the same.)
  for (double c = c0; c >= kSmallestLevel * c0; c /= 2.0) {
    bool all = true;
    std::size_t k = 0;
    for (; k < w.size() && all; ++k) {
      const Eigen::Vector4d d = std::sqrt(c) * (to_offset * w[k]);
      State u = o.y + (d.array() * unit_).matrix();
      const auto integ = make_integrator(section, follow_.integrator);
      integ->reset(u);
      Observer none;
      for (int i = 0; i < o.n * o.cycles && all; ++i) all = integ->advance_period(u, none) == IntegrationStatus::ok;
      counters += integ->counters();
      const Eigen::Vector4d image = ((u - o.y).array() / unit_).matrix();
      all = all && quadratic(o.S, image) <= fall * quadratic(o.S, d);
    }
    if (all) return c;
    std::rotate(w.begin(), w.begin() + static_cast<std::ptrdiff_t>(k - 1), w.begin() + static_cast<std::ptrdiff_t>(k));
  }
  return 0.0;
}

bool AttractorSet::recurrence_decides(std::size_t i) const {
  return census_.decide_by_recurrence && recurrent_[i] && !records_[i].transient;
}

void AttractorSet::observe_stay(std::size_t i, std::optional<std::size_t> outcome) {
  if (recurrent_[i] && outcome && *outcome != i) records_[i].transient = true;
}

Cell AttractorSet::cell(const State& u) const {
  Cell c;
  constexpr double kFar = 9e18;  // within std::int64_t
  for (int i = 0; i < 4; ++i) {
    // A state beyond the grid's range (diverging, or NaN) is one far cell, never the undefined
    // value of a cast out of range.
    const double q = std::floor(u[i] / (unit_[i] * census_.cell));
    c[static_cast<std::size_t>(i)] = std::abs(q) < kFar ? static_cast<std::int64_t>(q)
                                                        : static_cast<std::int64_t>(q > 0.0 ? kFar : -kFar);
  }
  return c;
}

// The set holds every visited cell's 80 neighbours too (Recurrent::near), so that the test a
// following state makes every period is one lookup; the neighbourhood is added once per
// sample, when a set is made or extended.
bool AttractorSet::visits(std::size_t i, const Cell& c) const {
  return recurrent_[i] && recurrent_[i]->near.count(cell_hash(c)) > 0;
}

void Recurrent::add(const Cell& c) {
  if (!visited.insert(c).second) return;
  for (int k = 0; k < 81; ++k) {
    Cell n = c;
    for (int d = 0, r = k; d < 4; ++d, r /= 3) n[static_cast<std::size_t>(d)] += r % 3 - 1;
    near.insert(cell_hash(n));
  }
}

bool AttractorSet::same_orbit(const Orbit& o, const std::vector<State>& points) const {
  return static_cast<int>(o.points.size()) == o.n && same_cycle(model_, o.points, points, same_orbit_tolerance(options_));
}

// Newton for period n at the section phase s, from u (a period start), integrated at `io` to
// the residual `tol`: the orbit's period-start point when Newton converges to a stable orbit.
std::optional<State> AttractorSet::newton(const State& u, int n, double s, const IntegratorOptions& io, double tol,
                                          IntegrationCounters& counters) const {
  const Model section = s > 0.0 ? shifted_model(model_, s) : model_;
  std::optional<State> start = u;
  if (s > 0.0) start = state_at_phase(model_, io, u, s, counters);
  if (!start) return std::nullopt;
  ShootingOptions so;
  so.n = n;
  so.tol = tol;
  so.max_iterations = options_.analysis.newton_max_iterations;
  const ShootingResult sh = shoot(section, io, *start, so, counters);
  if (!sh.converged || !sh.stable()) return std::nullopt;
  if (s == 0.0) return sh.y;
  return state_at_phase(section, io, sh.y, model_.period() - s, counters);
}

std::optional<State> AttractorSet::shoot_from(const State& u, int n, const std::deque<Impact>& impacts,
                                              const std::optional<Impact>& open, long last_period,
                                              IntegrationCounters& counters) {
  const double s = section_phase(impacts, open, 0, last_period, model_.period());
  return newton(u, n, s, options_.integrator, newton_tol(), counters);
}

// Most searches from states not yet decided land on an orbit already known, so Newton runs
// first at the follow tolerance, where a period costs several times less than at the scene's.
// A landing point
// within kKnownCandidate of a known orbit's point is that orbit: the loose solution is
// within its residual / (1 - |mu|) of the orbit (1e-3 scaled at |mu| = 0.99), distinct orbits
// lie farther apart (one point of the paper's box has two (1,1) orbits 3 % apart in T_con). A wrong match could only
// defer a new orbit's discovery to a later search or to the state's settling, never change a
// label: labels come from capture (a verified region of the orbit itself) or settling.
std::optional<std::size_t> AttractorSet::discover(const State& u, int n, const std::deque<Impact>& impacts,
                                                  const std::optional<Impact>& open, long last_period,
                                                  IntegrationCounters& counters) {
  const double s = section_phase(impacts, open, 0, last_period, model_.period());
  const std::optional<State> y = newton(u, n, s, follow_.integrator, newton_tolerance(follow_), counters);
  if (!y) return std::nullopt;
  for (std::size_t i = 0; i < orbits_.size(); ++i)
    if (orbits_[i])
      for (const State& point : orbits_[i]->points)
        if (scale_.distance(point, *y) <= kKnownCandidate) return i;
  const std::optional<State> refined = newton(*y, n, s, options_.integrator, newton_tol(), counters);
  if (!refined) return std::nullopt;
  return add_periodic(*refined, n, counters);
}

// The section and the linearisation the capture test needs: the middle of the orbit's
// longest contact-free stretch, and Newton there (one or two iterations from the orbit).
void AttractorSet::prepare_capture(Orbit& o, const std::deque<Impact>& cycle_impacts,
                                   IntegrationCounters& counters) const {
  o.phase = section_phase(cycle_impacts, std::nullopt, 0, o.n - 1, model_.period());
  const Model section = o.phase > 0.0 ? shifted_model(model_, o.phase) : model_;
  std::optional<State> start = o.points.front();
  if (o.phase > 0.0) start = state_at_phase(model_, options_.integrator, *start, o.phase, counters);
  if (!start) return;
  ShootingOptions so;
  so.n = o.n;
  so.tol = newton_tol();
  so.max_iterations = options_.analysis.newton_max_iterations;
  const ShootingResult sh = shoot(section, options_.integrator, *start, so, counters);
  if (!sh.converged) return;
  o.y = sh.y;
  const Eigen::Matrix4d D = unit_.matrix().asDiagonal();
  const Eigen::Matrix4d Dinv = unit_.inverse().matrix().asDiagonal();
  o.M = Dinv * sh.monodromy * D;
  o.linearised = true;
  if (!sh.stable()) return;
  // J cycles, so that M^J contracts offsets by half at least: its largest singular value is at
  // most 1/2 (V then falls by a good part of itself per J cycles, far beyond the integration's
  // noise and the map's nonlinearity: S = sum_k (M^J)^Tk M^Jk has lambda_max(S) <= 4/3). The
  // Frobenius norm, used before, asked up to 2x the singular value and so more cycles for the
  // same guarantee; each cycle is paid by every sample of verified_level.
  Eigen::Matrix4d power = o.M;
  o.cycles = 1;
  while (power.operatorNorm() > kContraction && o.cycles * o.n < kMaxCyclePeriods) {
    power = o.M * power;
    ++o.cycles;
  }
  if (power.operatorNorm() > kContraction) return;
  o.S = lyapunov_matrix(power);
  if (!o.S.allFinite()) return;
  o.level = verified_level(o, section, counters);
  o.capture = o.level > 0.0;
}

std::optional<std::size_t> AttractorSet::add_periodic(const State& y0_in, int n_in, IntegrationCounters& counters) {
  const int n = least_period(model_, options_.integrator, y0_in, n_in, kShorterPeriod * newton_tol(), counters);
  // The cycle's points at period starts.
  std::vector<State> points{y0_in};
  {
    const auto integ = make_integrator(model_, options_.integrator);
    State u = y0_in;
    integ->reset(u);
    Observer none;
    for (int i = 1; i < n && integ->advance_period(u, none) == IntegrationStatus::ok; ++i) points.push_back(u);
    counters += integ->counters();
    if (static_cast<int>(points.size()) != n) return std::nullopt;
  }
  for (std::size_t i = 0; i < orbits_.size(); ++i)
    if (orbits_[i] && same_orbit(*orbits_[i], points)) return i;
  if (full()) return std::nullopt;

  const PointSummary m = measure_orbit(p_, options_, Model::to_physical(y0_in), n);
  counters += m.counters;
  Attractor a;
  a.periodic = true;
  a.regime = m.status == SolveStatus::ok ? m.regime : Regime{RegimeKind::failed, 0, 0};
  a.T_con = m.T_con;
  a.k_con = m.k_con;
  a.F_max = m.F_max;
  a.z_ratio = m.z_ratio;
  a.z_max = m.z_max;
  a.hertz_valid = m.hertz_valid;
  set_longest(a, m.impacts.begin(), m.impacts.end());
  for (const State& y : points) a.strobe.push_back(Model::to_physical(y));

  Orbit o;
  o.n = n;
  o.points = points;
  std::deque<Impact> cycle;
  for (const Impact& im : m.impacts) cycle.push_back(im);
  prepare_capture(o, cycle, counters);
  // Stability: the monodromy at the section (the multipliers do not depend on the section).
  a.max_floquet = std::numeric_limits<double>::quiet_NaN();
  if (o.linearised) {
    const Eigen::EigenSolver<Eigen::Matrix4d> es(o.M, false);
    a.max_floquet = es.eigenvalues().cwiseAbs().maxCoeff();
    a.stable = a.max_floquet < 1.0 ? 1 : 0;
  }
  a.soft = is_soft(a.regime, a.stable, a.hertz_valid, a.k_con, options_.analysis.soft_kcon);
  records_.push_back(a);
  orbits_.push_back(std::move(o));
  recurrent_.emplace_back();
  return records_.size() - 1;
}

std::optional<std::size_t> AttractorSet::add_recurrent(const std::vector<State>& samples,
                                                       const std::deque<Impact>& impacts, long first_period,
                                                       long last_period) {
  std::vector<Cell> cells;
  for (const State& u : samples) cells.push_back(cell(u));
  for (std::size_t i = 0; i < recurrent_.size(); ++i) {
    if (!recurrent_[i]) continue;
    const auto hits = std::count_if(cells.begin(), cells.end(), [&](const Cell& c) { return visits(i, c); });
    if (static_cast<double>(hits) >= kSameRecurrent * static_cast<double>(cells.size())) {
      for (const Cell& c : cells) recurrent_[i]->add(c);
      return i;
    }
  }
  if (full()) return std::nullopt;
  Attractor a;
  a.periodic = false;
  a.max_floquet = std::numeric_limits<double>::quiet_NaN();
  std::vector<Impact> seen;
  for (const Impact& im : impacts) {
    if (im.period_in < first_period || im.period_in > last_period) continue;
    seen.push_back(im);
    a.F_max = std::max(a.F_max, im.F_max);
    a.z_ratio = std::max(a.z_ratio, im.z_ratio);
    a.z_max = std::max(a.z_max, im.z_max);
  }
  set_longest(a, seen.begin(), seen.end());
  const auto count = static_cast<long>(seen.size());
  a.k_con = a.T_con > 0.0 ? model_.period() / a.T_con : 0.0;
  a.hertz_valid = a.z_ratio <= options_.analysis.hertz_limit;
  const long window = last_period - first_period + 1;
  const bool chatter = count >= options_.analysis.chatter_impacts * window;
  a.regime = {chatter ? RegimeKind::chatter : RegimeKind::non_periodic, 0, 0};
  records_.push_back(a);
  orbits_.emplace_back();
  Recurrent r;
  for (const Cell& c : cells) r.add(c);
  recurrent_.push_back(std::move(r));
  return records_.size() - 1;
}

}  // namespace vibromap::census_detail
