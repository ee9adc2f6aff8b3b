#include "vibromap/io/trajectory_file.hpp"

#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include "attribute_seal.hpp"
#include "vibromap/io/hdf5_file.hpp"

namespace vibromap {

namespace {

// The memory the system can give without swapping (MemAvailable), bytes; 0 when unknown.
std::uint64_t available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return 0;
}

std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g GB", bytes / 1e9);
  return text;
}

constexpr std::array<TrajectoryColumn, 7> kTrajectoryColumns = {{
    {"t", "s", "time since the start of the kept window", &TrajectorySample::t},
    {"x1", "m", "displacement of the main body", &TrajectorySample::x1},
    {"x2", "m", "displacement of the attached body", &TrajectorySample::x2},
    {"v1", "m/s", "velocity of the main body", &TrajectorySample::v1},
    {"v2", "m/s", "velocity of the attached body", &TrajectorySample::v2},
    {"Fc", "N", "Hertz contact force K z^(3/2), z = x1 - x2", &TrajectorySample::Fc},
    {"F", "N", "external force lambda F0 cos(omega t + phi0)", &TrajectorySample::F},
}};

// The first column, /t, is the dimension scale "t" of every other column (netCDF-4 and xarray
// read it as the time coordinate).
void write_columns(Hdf5File& file, const std::vector<TrajectorySample>& samples) {
  std::vector<double> values(samples.size());
  Dataset time;
  for (std::size_t c = 0; c < kTrajectoryColumns.size(); ++c) {
    const TrajectoryColumn& column = kTrajectoryColumns[c];
    for (std::size_t i = 0; i < samples.size(); ++i) values[i] = samples[i].*column.member;
    Dataset dataset = file.write_dataset(column.name, values);
    if (c == 0) {
      dataset.make_dimension_scale(column.name);
    } else {
      dataset.attach_dimension_scale(time, 0);
    }
    dataset.set_attribute("units", column.units);
    dataset.set_attribute("description", column.description);
    if (c == 0) time = std::move(dataset);
  }
}

void write_root_attributes(Hdf5File& file, const PointSummary& summary, const std::string& scene_text) {
  file.set_attribute("T", summary.T);
  file.set_attribute("regime", summary.regime.label());
  file.set_attribute("n", summary.regime.n);
  file.set_attribute("k", summary.regime.k);
  file.set_attribute("T_con", summary.T_con);
  file.set_attribute("k_con", summary.k_con);
  file.set_attribute("scene", scene_text);
  file.set_attribute("vibromap_version", VIBROMAP_VERSION);
}

}  // namespace

void write_trajectory(const std::string& path, const PointSummary& summary, const std::string& scene_text) {
  write_hdf5_atomically(path, [&](Hdf5File& file) {
    write_columns(file, summary.trajectory);
    write_root_attributes(file, summary, scene_text);
    detail::seal_attributes(file, kTrajectoryFormat);  // last: the format version, then the seal over every attribute (attribute_seal.hpp)
  });
}

void check_trajectory_fits(const std::string& path, const std::string& option, long periods, long samples,
                           int copies) {
  namespace fs = std::filesystem;
  const double n = static_cast<double>(periods) * static_cast<double>(samples);
  // The samples (7 float64 each) are kept once by the solver and once, column by column, by the
  // writer; a vector may hold twice its size while it grows.
  const double memory = 3.0 * n * static_cast<double>(sizeof(TrajectorySample)) * static_cast<double>(copies);
  const double file = n * static_cast<double>(sizeof(TrajectorySample));
  const std::string what = option + ": " + std::to_string(periods) + " periods x " + std::to_string(samples) +
                           " samples ([analysis] trajectory_periods, trajectory_samples)" +
                           (copies > 1 ? ", " + std::to_string(copies) + " trajectories at once," : "");
  if (const std::uint64_t avail = available_memory(); avail > 0 && memory > 0.5 * static_cast<double>(avail))
    throw IoError(path + ": " + what + " need about " + gigabytes(memory) + " of memory, more than half the " +
                  gigabytes(static_cast<double>(avail)) + " available; keep fewer periods or samples");
  std::error_code ec;
  const fs::path dir = fs::path(path).parent_path();
  const fs::space_info space = fs::space(dir.empty() ? fs::path(".") : dir, ec);
  if (!ec && file > static_cast<double>(space.available))
    throw IoError(path + ": " + what + " make a " + gigabytes(file) + " file; its file system has " +
                  gigabytes(static_cast<double>(space.available)) + " free");
}

const std::array<TrajectoryColumn, 7>& trajectory_columns() { return kTrajectoryColumns; }

}  // namespace vibromap
