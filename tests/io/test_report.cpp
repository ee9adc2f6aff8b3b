// The reporter's shared pieces (io/report.hpp) and a renderer built on them
// (io/branch_output.hpp), against the text they must print.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "vibromap/io/branch_output.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/report.hpp"

using namespace vibromap;

namespace {

// `write` inside one object, on one line (indent 0).
template <class Write>
std::string in_object(Write write) {
  std::ostringstream os;
  JsonWriter w(os, 0);
  w.begin_object();
  write(w);
  w.end_object();
  return os.str();
}

BranchPoint point_at(double param) {
  BranchPoint p;
  p.param = param;
  return p;
}

}  // namespace

TEST(Report, MultipliersAreReImPairs) {
  const std::vector<std::complex<double>> mu = {{0.5, -0.25}, {-1.0, 0.0}};
  EXPECT_EQ(in_object([&](JsonWriter& w) { write_multipliers_json(w, mu); }),
            R"({"multipliers":[[0.5,-0.25],[-1,0]]})");
  EXPECT_EQ(in_object([](JsonWriter& w) { write_multipliers_json(w, {}); }), R"({"multipliers":[]})");
}

TEST(Report, StrobeX1IsEachStatesFirstCoordinate) {
  const std::vector<Eigen::Vector4d> strobe = {Eigen::Vector4d(0.125, 2, 3, 4), Eigen::Vector4d(-0.5, 6, 7, 8)};
  EXPECT_EQ(in_object([&](JsonWriter& w) { write_strobe_x1_json(w, strobe); }), R"({"strobe_x1":[0.125,-0.5]})");
}

TEST(Report, StoppedNoteNamesTheSignalOnlyWhenOneStoppedTheRun) {
  FarmFigures farm;
  EXPECT_EQ(stopped_note(farm), "");
  farm.stopped_by = "SIGUSR1";
  EXPECT_EQ(stopped_note(farm), "  (stopped by SIGUSR1: go on with --resume)");
}

TEST(BranchOutput, TableListsTheBranchItsBifurcationsAndASummaryLine) {
  ContinuationReport report;
  report.start_regime = "(1,1)";
  Branch b;
  b.points = {point_at(7.23), point_at(8.3)};
  Bifurcation fold;
  fold.at = point_at(7.5);
  fold.at.multipliers = {{1.0, 0.0}, {0.25, 0.0}};
  b.bifurcations = {fold};
  b.stop = "reached the end of the interval";
  report.branches = {b};
  report.measured = {{}};
  std::ostringstream os;
  write_branch_table(os, report, {.key = "omega", .from = 7.23, .to = 8.3, .file = "", .points = false});
  EXPECT_EQ(os.str(),
            "branch         omega from 7.23 to 8.3, period 1 T ((1,1) at the start)\n"
            "points         2; reached the end of the interval\n"
            "bifurcations   1\n"
            "              fold  omega = 7.5  max|mu| 1\n"
            "\n"
            "  branch  period              from                to  points  stopped"
            "   (every point: --points, or --format json)\n"
            "       0     1 T              7.23               8.3       2  reached the end of the interval\n");
}
