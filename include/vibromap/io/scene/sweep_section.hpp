#pragma once
// The [sweep] section of a scene: the grid's axes, what to store, and how often to
// checkpoint and report. scene.hpp's file comment shows the section; `vibromap keys`
// documents its keys.

#include <cstddef>
#include <string>
#include <vector>

#include "vibromap/core/quantities.hpp"
#include "vibromap/core/grid.hpp"
#include "vibromap/core/refine/refine_compare.hpp"

namespace vibromap {

// The most axes a [sweep] may have.
inline constexpr std::size_t kMaxSweepAxes = 8;

struct SweepOptions {
  std::vector<Axis> axes;  // the swept keys, at most kMaxSweepAxes (order: first axis slowest in the flat index)
  // Optional quantities to store; hertz_valid is always among them (read_sweep adds it).
  std::vector<Quantity> store = {Quantity::T_con, Quantity::k_con, Quantity::F_max, Quantity::z_max, Quantity::hertz_valid};
  double checkpoint_interval = 60.0;  // seconds between checkpoints of the map file, s
  double progress_interval = 10.0;    // seconds between progress lines when stderr is not a terminal, s
  // Adaptive refinement (docs/design-refine.md): levels (0: the uniform map of the
  // axes given), the quantities whose difference refines a cell, and the share of inherited
  // points solved again to audit the inference.
  int refine = 0;
  std::vector<RefineOn> refine_on = default_refine_on();
  double refine_audit = 0.01;
  bool refine_speckle = true;  // speckled coarse cells solved whole (core/refine/refine.hpp)
};

// "regime", "k_con:0.1": a refine_on entry as the scene writes it.
std::string refine_on_text(const RefineOn& on);

}  // namespace vibromap
