#pragma once
// The accuracy study (`vibromap accuracy`): the scene's base point solved by every case of the
// default study (core/analysis/point/accuracy.hpp) against its reference, one process, and the CSV of
// its rows for vibromap.plot (postprocess/vibromap). The report (table or JSON) and the progress
// lines are printed by io/accuracy_output.hpp.

#include <optional>
#include <string>
#include <vector>

#include "vibromap/core/analysis/point/accuracy.hpp"
#include "vibromap/io/output_file.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {

class AccuracyStudy {
 public:
  // Checks the cases' options (SceneError naming the case) and, when `csv` is set, makes its new
  // file before the (long) study, so that a bad --csv is known at once (SceneError, IoError).
  AccuracyStudy(const Scene& scene, const std::string& csv, bool overwrite);

  AccuracyReport run(const AccuracyProgress& progress) const;
  // Replaces the CSV file named at construction by the report's rows (nothing without one).
  void write_csv(const AccuracyReport& report);

 private:
  const Scene& scene_;
  std::optional<NewFile> csv_;
  std::vector<AccuracyCase> cases_;
  AccuracyCase reference_;
};

// The CSV text: header, the reference row (method "reference"), then the cases; every double
// as the shortest text that reads back to it.
std::string accuracy_csv(const AccuracyReport& report);

}  // namespace vibromap
