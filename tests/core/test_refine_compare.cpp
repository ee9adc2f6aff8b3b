// What "differs" means for adaptive refinement: classes exactly, continuous quantities by a
// relative threshold, NaN against a number always.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "vibromap/core/refine/refine_compare.hpp"

using namespace vibromap;

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

TEST(RefineCompare, ClassesCompareExactly) {
  EXPECT_FALSE(values_differ(3.0, 3.0, true, 0.0));
  EXPECT_TRUE(values_differ(3.0, 4.0, true, 0.0));
  EXPECT_TRUE(values_differ(1e6, 1e6 + 1, true, 0.5));  // a threshold never applies to a class
  EXPECT_TRUE(values_differ(kNaN, 0.0, true, 0.0));
  EXPECT_TRUE(values_differ(0.0, kNaN, true, 0.0));
  EXPECT_FALSE(values_differ(kNaN, kNaN, true, 0.0));
}

TEST(RefineCompare, ContinuousQuantitiesCompareByRelativeThreshold) {
  EXPECT_FALSE(values_differ(1.0, 1.04, false, 0.05));
  EXPECT_TRUE(values_differ(1.0, 1.06, false, 0.05));
  EXPECT_FALSE(values_differ(-2.0, -2.1, false, 0.05));   // 0.1 <= 0.05 * 2.1
  EXPECT_TRUE(values_differ(-2.0, -2.2, false, 0.05));
  EXPECT_TRUE(values_differ(1.0, 1.0 + 1e-15, false, 0.0));  // rel 0: any difference
  EXPECT_FALSE(values_differ(0.0, -0.0, false, 0.0));
  EXPECT_TRUE(values_differ(0.0, 1e-300, false, 0.5));     // against zero only rel >= 1 is lenient
  EXPECT_FALSE(values_differ(0.0, 1e-300, false, 1.0));
  EXPECT_TRUE(values_differ(kNaN, 1.0, false, 10.0));
  EXPECT_FALSE(values_differ(kNaN, kNaN, false, 0.1));
  EXPECT_FALSE(values_differ(kInf, kInf, false, 0.1));
  EXPECT_TRUE(values_differ(kInf, 1e300, false, 0.9));
  EXPECT_TRUE(values_differ(-kInf, kInf, false, 0.9));
}

TEST(RefineCompare, CellsDifferInAnyQuantityOfTheList) {
  CellResult a;
  a.regime = 0;
  a.n = 1;
  a.k = 1;
  a.soft = 0;
  a.k_con = 20.0;
  a.T_con = 1e-3;
  CellResult b = a;
  const auto& on = default_refine_on();
  EXPECT_FALSE(cells_differ(a, b, on));
  b.T_con = 2e-3;  // not in the default list
  EXPECT_FALSE(cells_differ(a, b, on));
  EXPECT_TRUE(cells_differ(a, b, {{RefineField::T_con, 0.1}}));
  EXPECT_FALSE(cells_differ(a, b, {{RefineField::T_con, 0.6}}));
  b = a;
  b.k = 2;
  EXPECT_TRUE(cells_differ(a, b, on));
  b = a;
  b.soft = 1;
  EXPECT_TRUE(cells_differ(a, b, on));
  EXPECT_FALSE(cells_differ(a, b, {{RefineField::regime, 0.0}}));
  b = a;
  b.census.resize(2);
  EXPECT_EQ(refine_value(b, RefineField::attractors), 2.0);
  EXPECT_TRUE(cells_differ(a, b, {{RefineField::attractors, 0.0}}));
  b = a;
  b.soft_fraction = 0.5;  // NaN in a (no census) against a number
  EXPECT_TRUE(cells_differ(a, b, {{RefineField::soft_fraction, 0.5}}));
}

TEST(RefineCompare, NamesParseAndThresholdsAreChecked) {
  ASSERT_EQ(all_refine_fields().size(), 11u);
  for (RefineField f : all_refine_fields()) EXPECT_EQ(parse_refine_field(to_string(f)), f);
  EXPECT_TRUE(refine_field_is_class(RefineField::hertz_valid));
  EXPECT_FALSE(refine_field_is_class(RefineField::z_ratio));
  try {
    parse_refine_field("colour");
    ADD_FAILURE() << "an unknown name parsed";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'colour'"), std::string::npos) << m;
    EXPECT_NE(m.find("regime, n, k, soft, hertz_valid, attractors, k_con, T_con, F_max, z_ratio, soft_fraction"),
              std::string::npos)
        << m;
  }
  EXPECT_EQ(validate_refine_on({RefineField::k_con, 0.05}), "");
  EXPECT_EQ(validate_refine_on({RefineField::n, 0.0}), "");
  EXPECT_EQ(validate_refine_on({RefineField::n, 0.1}), "n is a class and takes no threshold");
  EXPECT_NE(validate_refine_on({RefineField::F_max, -0.1}), "");
  EXPECT_NE(validate_refine_on({RefineField::F_max, kNaN}), "");
}
