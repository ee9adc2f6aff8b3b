// The source paper's Tables 1 and 2 (docs/model.md), solved from the shipped scenes
// jobs/paper/table{1,2}.toml: regime (1,1) and T_con within 3 % of the paper; the default
// tolerance within 1e-6 of a tight run; the paper's RK4 agrees on the soft contact.
#include <gtest/gtest.h>

#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/io/scene/scene.hpp"

using namespace vibromap;

namespace {
struct Table {
  const char* name;
  double paper_T_con, paper_k_con;  // the paper's values (docs/model.md)
};
const Table kTable1{"table1", 7.81e-4, 1113.3};
const Table kTable2{"table2", 0.098, 8.868};
constexpr double kPaperAgreement = 0.03;

std::ostream& operator<<(std::ostream& os, const Table& t) { return os << t.name; }

Parameters point(const Table& t) {
  return load_scene(std::string(VIBROMAP_SOURCE_DIR) + "/jobs/paper/" + t.name + ".toml").params;
}

class PaperTable : public ::testing::TestWithParam<Table> {};
}  // namespace

TEST_P(PaperTable, OneOneRegimeAndContactTimeWithinThreePercent) {
  const Table& t = GetParam();
  const PointSummary s = solve_point(point(t), PointOptions{});
  ASSERT_EQ(s.status, SolveStatus::ok) << s.message;
  EXPECT_EQ(s.regime.label(), "(1,1)");
  EXPECT_NEAR(s.T_con / t.paper_T_con, 1.0, kPaperAgreement);
  EXPECT_NEAR(s.k_con / t.paper_k_con, 1.0, kPaperAgreement);
  ASSERT_EQ(s.impacts.size(), 1u);
  EXPECT_GT(s.impacts[0].v_in, 0.0);
  EXPECT_DOUBLE_EQ(s.F_max, s.impacts[0].F_max);
}

TEST_P(PaperTable, DefaultToleranceAgreesWithTightRun) {
  const Table& t = GetParam();
  PointOptions tight;
  tight.integrator.rtol = 1e-13;
  const PointSummary ref = solve_point(point(t), tight);
  const PointSummary s = solve_point(point(t), PointOptions{});
  ASSERT_EQ(ref.regime, s.regime);
  EXPECT_NEAR(s.T_con / ref.T_con, 1.0, 1e-6);
  EXPECT_NEAR(s.F_max / ref.F_max, 1.0, 1e-6);
}

TEST(PaperTable2, ReferenceRk4AgreesWithAdaptive) {
  // On the soft contact the paper's fixed-step RK4 converges; it is an independent check.
  PointOptions rk4;
  rk4.integrator.method = Method::rk4;
  rk4.integrator.rk4_steps = 8192;
  const PointSummary a = solve_point(point(kTable2), rk4);
  const PointSummary b = solve_point(point(kTable2), PointOptions{});
  ASSERT_EQ(a.status, SolveStatus::ok) << a.message;
  EXPECT_EQ(a.regime, b.regime);
  EXPECT_NEAR(a.T_con / b.T_con, 1.0, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Paper, PaperTable, ::testing::Values(kTable1, kTable2),
                         [](const ::testing::TestParamInfo<Table>& param_info) { return std::string(param_info.param.name); });
