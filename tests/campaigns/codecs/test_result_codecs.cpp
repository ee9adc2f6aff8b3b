// Every campaign's result codec (parallel/campaign.hpp's ResultCodec) round-trips its record
// exactly: encode, decode, compare field by field. Doubles are compared bit for bit, so NaN
// (unset quantities), -0.0 and infinities must survive; empty vectors and strings too. The
// encoded size is the layout's sum of field widths, every proper prefix of a record is refused
// with WireError (a truncated journal or message is never read as a record), and records
// written back to back decode one after the other, as a sink reads a range.
//   sweep:          CellResult (sweep/cell_codec.hpp), with and without a census
//   census's attractor: Attractor (campaigns/census/attractor_codec.hpp), which both below carry
//   basins, census: PixelResult (campaigns/census/state_codec.hpp)
//   optimise:       StartRecord (multistart/start_codec.hpp)
//   orbit diagram:  the steps of one direction (orbit_diagram/steps_codec.hpp)
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <limits>
#include <vector>

#include "multistart/start_codec.hpp"
#include "orbit_diagram/steps_codec.hpp"
#include "sweep/cell_codec.hpp"
#include "vibromap/campaigns/census/attractor_codec.hpp"
#include "vibromap/campaigns/census/state_codec.hpp"
#include "vibromap/core/analysis/census/basins_plane.hpp"  // kOverlapLabel

using namespace vibromap;
using namespace vibromap::detail;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Bit-for-bit equality: NaN == NaN (same payload), -0.0 != 0.0.
::testing::AssertionResult same_bits(double a, double b) {
  if (std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " and " << b << " differ in their bits";
}

template <class Result>
std::vector<char> encode(const ResultCodec<Result>& codec, const Result& r) {
  ByteWriter w;
  codec.encode(r, w);
  return w.bytes();
}

// Decodes one record that must use every byte.
template <class Result>
Result decode_all(const ResultCodec<Result>& codec, const std::vector<char>& bytes) {
  ByteReader in(bytes);
  Result r = codec.decode(in);
  EXPECT_EQ(in.remaining(), 0u);
  return r;
}

// Every proper prefix of an encoded record is refused.
template <class Result>
void expect_prefixes_refused(const ResultCodec<Result>& codec, const std::vector<char>& bytes) {
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    ByteReader in(bytes.data(), n);
    EXPECT_THROW(codec.decode(in), WireError) << "prefix of " << n << " of " << bytes.size() << " bytes";
  }
}

}  // namespace

// ---- an attractor (the census map's cells and the followed states carry theirs so) ----------

namespace {

// Every field of an Attractor away from its default; i varies the regime, flags and strobe.
Attractor full_attractor(int i) {
  Attractor a;
  a.periodic = i % 2 == 0;
  a.regime = i % 2 == 0 ? Regime{RegimeKind::periodic, 2 + i, 5 * i} : Regime{RegimeKind::chaotic, 0, 0};
  a.T_con = 0.011 * (i + 1);
  a.k_con = 79.0 / (i + 1);
  a.F_max = 2.5e6;
  a.z_ratio = 1e-5;
  a.z_max = -0.0;
  a.v_in = 0.31;
  a.impulse = 40.0;
  a.hertz_valid = i % 2 == 0;
  a.max_floquet = i == 1 ? kNaN : 0.93;
  a.stable = i % 3 - 1;
  a.count = 17 + i;
  a.fraction = 0.25 * (i + 1);
  a.fraction_stderr = -kInf;
  a.from_rest = i == 0;
  a.strobe = {Eigen::Vector4d(0.1, 0.2, 0.3, 0.4), Eigen::Vector4d(kNaN, -0.0, 1e300, -1e-300)};
  a.strobe.resize(static_cast<std::size_t>(2 - i % 3));  // 2, 1, 0 states
  a.soft = i % 2 == 1;
  a.escape_rate = i == 1 ? 0.125 : kNaN;
  a.escape_exposure = 4000000000L + i;
  a.escapes = 3 * i;
  a.transient = i == 1;
  if (i != 2) {
    a.shock.status = i == 0 ? ShockStatus::found : ShockStatus::none;
    a.shock.size = 0.125 + i;
    a.shock.random_size = 1.0 / 3.0;
    a.shock.wall_s = 2.5;
    a.shock.dx = Eigen::Vector4d(1e-3, -0.0, kNaN, 7.0);
    a.shock.x_star = Eigen::Vector4d(-1.0, 2.0, 3e-300, kInf);
    a.shock.strobe_index = 2;
    a.shock.to = kShockToUnlisted;
    a.shock.to_regime = Regime{RegimeKind::periodic, 3, 3};
    a.shock.unresolved = 5;
    a.shock.verified = true;
    a.shock.follows = 5000000000L;
  }
  return a;
}

void expect_same_attractor(const Attractor& x, const Attractor& y) {
  EXPECT_EQ(x.periodic, y.periodic);
  EXPECT_EQ(x.regime, y.regime);
  for (const double Attractor::*m : {&Attractor::T_con, &Attractor::k_con, &Attractor::F_max, &Attractor::z_ratio,
                                     &Attractor::z_max, &Attractor::v_in, &Attractor::impulse, &Attractor::max_floquet,
                                     &Attractor::fraction, &Attractor::fraction_stderr, &Attractor::escape_rate})
    EXPECT_TRUE(same_bits(x.*m, y.*m));
  for (const bool Attractor::*m : {&Attractor::hertz_valid, &Attractor::from_rest, &Attractor::soft, &Attractor::transient})
    EXPECT_EQ(x.*m, y.*m);
  EXPECT_EQ(x.stable, y.stable);
  EXPECT_EQ(x.count, y.count);
  EXPECT_EQ(x.escape_exposure, y.escape_exposure);
  EXPECT_EQ(x.escapes, y.escapes);
  ASSERT_EQ(x.strobe.size(), y.strobe.size());
  for (std::size_t k = 0; k < x.strobe.size(); ++k)
    for (int i = 0; i < 4; ++i) EXPECT_TRUE(same_bits(x.strobe[k][i], y.strobe[k][i]));
  const CriticalShock &a = x.shock, &b = y.shock;
  EXPECT_EQ(a.status, b.status);
  for (const double CriticalShock::*m : {&CriticalShock::size, &CriticalShock::random_size, &CriticalShock::wall_s})
    EXPECT_TRUE(same_bits(a.*m, b.*m));
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(same_bits(a.dx[i], b.dx[i]) && same_bits(a.x_star[i], b.x_star[i]));
  EXPECT_EQ(a.strobe_index, b.strobe_index);
  EXPECT_EQ(a.to, b.to);
  EXPECT_EQ(a.to_regime, b.to_regime);
  EXPECT_EQ(a.unresolved, b.unresolved);
  EXPECT_EQ(a.verified, b.verified);
  EXPECT_EQ(a.follows, b.follows);
}

// Layout (attractor_codec.hpp): periodic, kind, n, k (int32), 11 doubles, 4 flags, stable and
// count (int32), escape_exposure (int64), escapes (int32), the count of states (uint64), states,
// the shock: status (int32), 3 doubles, dx and x_star (8 doubles), 6 int32, verified, follows (int64).
constexpr std::size_t kShockBytes = 4 + 3 * 8 + 8 * 8 + 6 * 4 + 1 + 8;
constexpr std::size_t kAttractorBytes = 1 + 3 * 4 + 11 * 8 + 4 + 2 * 4 + 8 + 4 + 8 + kShockBytes;
constexpr std::size_t kStateBytes = 4 * 8;

}  // namespace

TEST(ResultCodecs, AttractorWithEveryField) {
  const AttractorCodec codec;
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE("attractor " + std::to_string(i));
    const Attractor a = full_attractor(i);
    const std::vector<char> bytes = encode(codec, a);
    EXPECT_EQ(bytes.size(), kAttractorBytes + a.strobe.size() * kStateBytes);
    expect_same_attractor(a, decode_all(codec, bytes));
    expect_prefixes_refused(codec, bytes);
  }
}

TEST(ResultCodecs, AttractorOfAnUnknownRegimeKindIsRefused) {
  const AttractorCodec codec;
  std::vector<char> bytes = encode(codec, full_attractor(0));
  const auto failed = static_cast<std::int32_t>(RegimeKind::failed);
  for (const std::int32_t kind : {failed + 1, std::int32_t{-1}}) {
    std::memcpy(bytes.data() + 1, &kind, sizeof kind);  // after the periodic byte
    ByteReader in(bytes);
    EXPECT_THROW(codec.decode(in), WireError) << "kind " << kind;
  }
  std::memcpy(bytes.data() + 1, &failed, sizeof failed);
  ByteReader in(bytes);
  EXPECT_EQ(codec.decode(in).regime.kind, RegimeKind::failed);
}

// ---- sweep ----------------------------------------------------------------------------------

namespace {

// Every quantity a value of its own from its place j in the table (1 for hertz_valid, whose
// largest is 1), none its default: a quantity the codec drops or swaps shows.
CellResult distinct_quantities() {
  CellResult c;
  const std::vector<Quantity>& all = all_quantities();
  for (std::size_t j = 0; j < all.size(); ++j) {
    if (quantity_is_integer(all[j]))
      set_quantity_int(c, all[j], std::min<std::int64_t>(quantity_max(all[j]), static_cast<std::int64_t>(j) + 2));
    else
      set_quantity(c, all[j], 0.25 + static_cast<double>(j));
  }
  return c;
}

// Extreme values where the wire must not round: the quantities the table gives a value of
// their own, then the named ones below.
CellResult sample_cell() {
  CellResult c = distinct_quantities();
  c.status = 2;
  c.regime = -1;
  c.hertz_valid = 1;
  c.stable = 0;
  c.soft = -1;
  c.fragile = 1;
  c.n = 3;
  c.k = -7;
  c.periods = std::numeric_limits<std::int64_t>::max();
  c.rhs_evals = 123456789012345;
  c.clipped_impacts = -1;
  c.wall_s = 0.125;
  c.steady_residual = 3.5e-300;  // subnormal-adjacent: no rounding on the way
  c.T_con = 1e-3 / 3.0;
  c.k_con = kInf;
  c.F_max = -0.0;
  c.z_max = 4.2e-5;
  c.z_ratio = -kInf;
  c.v_in = 0.3;
  c.impulse = std::numeric_limits<double>::denorm_min();
  c.max_multiplier = kNaN;
  c.lyapunov = -kNaN;
  c.e_effective = 0.7;
  c.energy_dissipated = 12.5;
  return c;
}

void expect_same_cell(const CellResult& a, const CellResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.regime, b.regime);
  EXPECT_EQ(a.hertz_valid, b.hertz_valid);
  EXPECT_EQ(a.stable, b.stable);
  EXPECT_EQ(a.soft, b.soft);
  EXPECT_EQ(a.fragile, b.fragile);
  EXPECT_EQ(a.n, b.n);
  EXPECT_EQ(a.k, b.k);
  for (const Quantity q : all_quantities()) {
    if (quantity_is_integer(q))
      EXPECT_EQ(quantity_int(a, q), quantity_int(b, q)) << to_string(q);
    else
      EXPECT_TRUE(same_bits(a.value(q), b.value(q))) << to_string(q);
  }
  for (const double CellResult::*m :
       {&CellResult::wall_s, &CellResult::steady_residual, &CellResult::soft_fraction,
        &CellResult::unresolved_fraction, &CellResult::unlisted_fraction, &CellResult::budget_fraction,
        &CellResult::basin_entropy})
    EXPECT_TRUE(same_bits(a.*m, b.*m));
  ASSERT_EQ(a.census.size(), b.census.size());
  for (std::size_t i = 0; i < a.census.size(); ++i) expect_same_attractor(a.census[i], b.census[i]);
}

// Layout: 6 int8 flags (hertz_valid and fragile among them), n and k (int32), an int64 per other integer
// quantity, wall_s, steady_residual and a double per float quantity, the census byte.
std::size_t cell_bytes() {
  const auto& all = all_quantities();
  const auto integers = static_cast<std::size_t>(std::count_if(all.begin(), all.end(), quantity_is_integer));
  return 6 + 2 * 4 + (integers - 1) * 8 + (2 + all.size() - integers) * 8 + 1;
}
const std::size_t kCellBytes = cell_bytes();
// The census: 4 fractions and the basin entropy, a uint32 count, then each attractor (attractor_codec.hpp).
constexpr std::size_t kCensusBytes = 5 * 8 + 4;

}  // namespace

TEST(ResultCodecs, SweepCellWithoutCensus) {
  const CellCodec codec(false);
  const CellResult c = sample_cell();
  const std::vector<char> bytes = encode(codec, c);
  EXPECT_EQ(bytes.size(), kCellBytes);
  const CellResult back = decode_all(codec, bytes);
  expect_same_cell(c, back);  // census empty, its fractions NaN: the defaults on both sides
  expect_prefixes_refused(codec, bytes);
}

// Every quantity of the table crosses the wire, with the value it had: none of them is left at
// its default on the other side, nor takes another's value.
TEST(ResultCodecs, SweepCellCarriesEveryQuantityOfTheTable) {
  const CellResult fresh;
  const CellResult c = distinct_quantities();
  for (const bool census : {false, true}) {
    const CellCodec codec(census);
    const CellResult back = decode_all(codec, encode(codec, c));
    for (const Quantity q : all_quantities()) {
      EXPECT_EQ(back.value(q), c.value(q)) << to_string(q);
      EXPECT_NE(back.value(q), fresh.value(q)) << to_string(q);
    }
  }
}

// The layout's version: 10 and 13 for the 15 quantities the generations were set for (the head
// with the fragile flag; the census's with its basin entropy), another number for a quantity
// more or fewer, or two swapped.
TEST(ResultCodecs, SweepCellVersionFollowsTheQuantities) {
  const std::vector<Quantity>& all = all_quantities();
  ASSERT_GE(all.size(), 15u);
  const std::vector<Quantity> generation(all.begin(), all.begin() + 15);
  EXPECT_EQ(cell_layout_version(false, generation), 10u);
  EXPECT_EQ(cell_layout_version(true, generation), 13u);
  const std::vector<Quantity> fewer(all.begin(), all.begin() + 14);
  std::vector<Quantity> more = generation, moved = generation;
  more.push_back(Quantity::T_con);
  std::swap(moved[0], moved[1]);
  for (const auto& other : {fewer, more, moved})
    for (const bool census : {false, true}) {
      EXPECT_NE(cell_layout_version(census, other), 10u);
      EXPECT_NE(cell_layout_version(census, other), 13u);
    }
  EXPECT_EQ(CellCodec(false).version(), cell_layout_version(false, all));
  EXPECT_EQ(CellCodec(true).version(), cell_layout_version(true, all));
  EXPECT_NE(CellCodec(false).version(), CellCodec(true).version());
}

TEST(ResultCodecs, SweepCellWithACensus) {
  const CellCodec codec(true);
  CellResult c = sample_cell();
  c.soft_fraction = 0.5;
  c.unresolved_fraction = 0.0;
  c.unlisted_fraction = kNaN;
  c.budget_fraction = 1.0 / 7.0;
  c.basin_entropy = std::log(3.0);
  c.census = {full_attractor(0), full_attractor(1), full_attractor(2)};  // 2, 1 and 0 stroboscopic states
  const std::vector<char> bytes = encode(codec, c);
  EXPECT_EQ(bytes.size(), kCellBytes + kCensusBytes + 3 * kAttractorBytes + 3 * kStateBytes);
  expect_same_cell(c, decode_all(codec, bytes));
  expect_prefixes_refused(codec, bytes);
}

TEST(ResultCodecs, SweepCellWithAnEmptyCensus) {
  const CellCodec codec(true);
  CellResult c = sample_cell();
  c.soft_fraction = 0.0;
  const std::vector<char> bytes = encode(codec, c);
  EXPECT_EQ(bytes.size(), kCellBytes + kCensusBytes);
  const CellResult back = decode_all(codec, bytes);
  EXPECT_TRUE(back.census.empty());
  expect_same_cell(c, back);
}

TEST(ResultCodecs, SweepCellsBackToBackAsARange) {
  const CellCodec codec(true);
  std::vector<CellResult> cells(3, sample_cell());
  cells[1].census = {full_attractor(1)};
  cells[2].n = 9;
  ByteWriter w;
  for (const CellResult& c : cells) codec.encode(c, w);
  ByteReader in(w.bytes());
  for (const CellResult& c : cells) expect_same_cell(c, codec.decode(in));
  EXPECT_EQ(in.remaining(), 0u);
}

TEST(ResultCodecs, SweepCellListingMoreAttractorsThanACensusKeepsIsRefused) {
  const CellCodec codec(true);
  CellResult c = sample_cell();
  c.census.assign(kMaxCensusAttractors + 1, full_attractor(0));
  const std::vector<char> bytes = encode(codec, c);
  ByteReader in(bytes);
  EXPECT_THROW(codec.decode(in), WireError);
}

// ---- basins and the point census ------------------------------------------------------------

namespace {

PixelResult sample_pixel() {
  PixelResult r;
  r.label = 4;
  r.periods = 1234567;
  r.early = true;
  r.budget = false;
  r.failed = true;
  r.end_state = Eigen::Vector4d(0.01, 0.05, -kInf, kNaN);
  r.attractor = full_attractor(1);
  r.attractor.strobe = full_attractor(0).strobe;
  return r;
}

void expect_same_pixel(const PixelResult& a, const PixelResult& b) {
  EXPECT_EQ(a.label, b.label);
  EXPECT_EQ(a.periods, b.periods);
  EXPECT_EQ(a.early, b.early);
  EXPECT_EQ(a.budget, b.budget);
  EXPECT_EQ(a.failed, b.failed);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(same_bits(a.end_state[i], b.end_state[i]));
  expect_same_attractor(a.attractor, b.attractor);
}

// Layout: label (int32), periods (int64), 3 flags, the end state; for a label >= 0, the attractor.
constexpr std::size_t kPixelBytes = 4 + 8 + 3 + 4 * 8;

}  // namespace

TEST(ResultCodecs, BasinsPixelWithItsAttractor) {
  const PixelCodec codec;
  const PixelResult r = sample_pixel();
  const std::vector<char> bytes = encode(codec, r);
  EXPECT_EQ(bytes.size(), kPixelBytes + kAttractorBytes + 2 * kStateBytes);
  expect_same_pixel(r, decode_all(codec, bytes));
  expect_prefixes_refused(codec, bytes);
}

TEST(ResultCodecs, BasinsPixelOfAPeriodicAttractorWithoutStrobe) {
  const PixelCodec codec;
  PixelResult r = sample_pixel();
  r.label = 0;
  r.attractor = full_attractor(2);
  r.attractor.periodic = true;
  r.attractor.regime = Regime{RegimeKind::periodic, 3, 3};
  ASSERT_TRUE(r.attractor.strobe.empty());
  const std::vector<char> bytes = encode(codec, r);
  EXPECT_EQ(bytes.size(), kPixelBytes + kAttractorBytes);
  expect_same_pixel(r, decode_all(codec, bytes));
}

TEST(ResultCodecs, BasinsPixelWithoutAnAttractorCarriesNoRecord) {
  // A negative label (unresolved, overlap) sends no attractor: the decoded one is the default.
  const PixelCodec codec;
  for (int label : {kUnresolvedLabel, kOverlapLabel}) {
    PixelResult r = sample_pixel();
    r.label = label;
    const std::vector<char> bytes = encode(codec, r);
    EXPECT_EQ(bytes.size(), kPixelBytes);
    const PixelResult back = decode_all(codec, bytes);
    r.attractor = Attractor{};
    expect_same_pixel(r, back);
    expect_prefixes_refused(codec, bytes);
  }
}

// ---- optimise -------------------------------------------------------------------------------

namespace {

std::vector<StartSpec> sample_plan() {
  return {StartSpec{0, 0, Algorithm::bobyqa, std::nullopt}, StartSpec{1, 0, Algorithm::cobyla, ContactLawKind::hertz},
          StartSpec{2, 1, Algorithm::sbplx, std::nullopt}};
}

StartRecord sample_start(const std::vector<StartSpec>& plan) {
  StartRecord s;
  s.spec = plan[1];
  s.rank = 3;
  EvaluationRecord seed;
  seed.x = {2.099e11, 0.05};
  seed.result.value = kNaN;
  seed.result.violation = 1.0;
  seed.result.feasible = false;
  seed.result.regime = Regime{RegimeKind::failed, 0, 0};
  seed.result.stable = -1;
  seed.result.message = std::string("integration failed:\tstep size underflow\n\0after a NUL", 52);
  seed.wall_s = 0.5;
  EvaluationRecord best;
  best.x = {};
  best.result.value = -86.9;
  best.result.violation = -0.0;
  best.result.feasible = true;
  best.result.regime = Regime{RegimeKind::periodic, 1, 1};
  best.result.stable = 1;
  best.result.measures = {0.011, kNaN, -kInf};
  best.wall_s = 0.25;
  s.result.evaluations = {seed, best};
  s.result.best = 1;
  s.result.stop = "XTOL_REACHED";
  s.result.nlopt_code = 4;
  s.result.calls = 17;
  s.result.cache_hits = 2;
  s.result.wall_s = 1.75;
  return s;
}

void expect_same_start(const StartRecord& a, const StartRecord& b) {
  EXPECT_EQ(a.spec.index, b.spec.index);
  EXPECT_EQ(a.spec.seed, b.spec.seed);
  EXPECT_EQ(a.spec.algorithm, b.spec.algorithm);
  EXPECT_EQ(a.spec.law, b.spec.law);
  EXPECT_EQ(a.rank, b.rank);
  ASSERT_EQ(a.result.evaluations.size(), b.result.evaluations.size());
  for (std::size_t i = 0; i < a.result.evaluations.size(); ++i) {
    const EvaluationRecord &x = a.result.evaluations[i], &y = b.result.evaluations[i];
    ASSERT_EQ(x.x.size(), y.x.size());
    for (std::size_t j = 0; j < x.x.size(); ++j) EXPECT_TRUE(same_bits(x.x[j], y.x[j]));
    EXPECT_TRUE(same_bits(x.result.value, y.result.value));
    EXPECT_TRUE(same_bits(x.result.violation, y.result.violation));
    EXPECT_EQ(x.result.feasible, y.result.feasible);
    EXPECT_EQ(x.result.regime, y.result.regime);
    EXPECT_EQ(x.result.stable, y.result.stable);
    ASSERT_EQ(x.result.measures.size(), y.result.measures.size());
    for (std::size_t j = 0; j < x.result.measures.size(); ++j)
      EXPECT_TRUE(same_bits(x.result.measures[j], y.result.measures[j]));
    EXPECT_EQ(x.result.message, y.result.message);
    EXPECT_TRUE(same_bits(x.wall_s, y.wall_s));
  }
  EXPECT_EQ(a.result.best, b.result.best);
  EXPECT_EQ(a.result.stop, b.result.stop);
  EXPECT_EQ(a.result.nlopt_code, b.result.nlopt_code);
  EXPECT_EQ(a.result.calls, b.result.calls);
  EXPECT_EQ(a.result.cache_hits, b.result.cache_hits);
  EXPECT_TRUE(same_bits(a.result.wall_s, b.result.wall_s));
}

}  // namespace

TEST(ResultCodecs, OptimiseStartWithEvaluations) {
  const std::vector<StartSpec> plan = sample_plan();
  const StartCodec codec(plan);
  const StartRecord s = sample_start(plan);
  const std::vector<char> bytes = encode(codec, s);
  expect_same_start(s, decode_all(codec, bytes));
  expect_prefixes_refused(codec, bytes);
}

TEST(ResultCodecs, OptimiseStartWithoutEvaluationsOrBest) {
  const std::vector<StartSpec> plan = sample_plan();
  const StartCodec codec(plan);
  StartRecord s;
  s.spec = plan[2];
  s.result.stop = "";
  const std::vector<char> bytes = encode(codec, s);
  // index, rank, count, best (-1), the empty stop, nlopt code, calls, cache hits, wall time.
  EXPECT_EQ(bytes.size(), 4u + 4 + 8 + 8 + 8 + 4 + 8 + 8 + 8);
  const StartRecord back = decode_all(codec, bytes);
  EXPECT_FALSE(back.result.best.has_value());
  expect_same_start(s, back);
}

TEST(ResultCodecs, OptimiseStartOfAnUnknownIndexIsRefused) {
  const std::vector<StartSpec> plan = sample_plan();
  StartRecord s = sample_start(plan);
  s.spec.index = 3;  // the plan has starts 0..2
  const std::vector<char> bytes = encode(StartCodec(plan), s);
  ByteReader in(bytes);
  EXPECT_THROW(StartCodec(plan).decode(in), WireError);
}

// ---- orbit diagram --------------------------------------------------------------------------

namespace {

void expect_same_steps(const Steps& a, const Steps& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].status, b[k].status);
    ASSERT_EQ(a[k].strobe.size(), b[k].strobe.size());
    for (std::size_t j = 0; j < a[k].strobe.size(); ++j)
      for (int i = 0; i < 4; ++i) EXPECT_TRUE(same_bits(a[k].strobe[j][i], b[k].strobe[j][i]));
  }
}

}  // namespace

TEST(ResultCodecs, OrbitDiagramSteps) {
  const StepsCodec codec;
  Steps steps(3);
  steps[0].strobe = {Eigen::Vector4d(0.01, 0.06, 0.2, -0.1), Eigen::Vector4d(-0.01, 0.04, -0.2, 0.1)};
  steps[1].status = SolveStatus::failed;  // no states kept
  steps[2].status = SolveStatus::budget;
  steps[2].strobe = {Eigen::Vector4d(kNaN, -0.0, kInf, 5e-324)};
  const std::vector<char> bytes = encode(codec, steps);
  // count, then per step its status byte, its state count and 4 doubles per state.
  EXPECT_EQ(bytes.size(), 8u + 3 * (1 + 8) + 3 * 4 * 8);
  expect_same_steps(steps, decode_all(codec, bytes));
  expect_prefixes_refused(codec, bytes);
}

TEST(ResultCodecs, OrbitDiagramWithoutSteps) {
  const StepsCodec codec;
  const std::vector<char> bytes = encode(codec, Steps{});
  EXPECT_EQ(bytes.size(), 8u);
  EXPECT_TRUE(decode_all(codec, bytes).empty());
}
