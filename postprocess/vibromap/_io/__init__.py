"""Readers for the HDF5 files vibromap writes, shared by vibromap.files, vibromap.plot and the
scripts of vibromap-post: one import for every reader, whose code lives in modules of its own:

  h5io      open_h5, read_dataset, VibromapFileError, FileVersionError, FORMAT_VERSIONS,
            write_plot, save_figure: opening a file (its format version and checksum
            checked), reading a dataset, one-line errors for a damaged file or one of
            another format version, writing a figure
  map       read_map, SweepMap, MapAxis, axis_name: a map file (its layout is described
            there)
  regimes   the flag codes of a map (regime, status, stable, soft), regime_labels,
            regime_counts
  soft      add_soft_cells, SoftInfo, hertz_validity, impact_cells: soft and Hertz-valid
            cells by the one definition of a soft motion
  slice     slice2d, MapSlice, cell_edges, cell_boundary, parse_fix: slices to plot
  runfiles  read_trajectory, Trajectory, read_basins, Basins: trajectory and basins files
  curves    read_curves: a curve file of vibromap continue --curve (bifurcation and
            level curves in a plane of two scene keys)

Every reader returns numpy arrays and plain Python numbers and strings, and raises
VibromapFileError with a one-line message (naming the file) when the file is missing, is not
HDF5, is of another format version, lacks what the reader needs, or is damaged: open_h5 checks
the file's format version (FileVersionError, the one line vibromap prints: "FILE: a regime map of
format version 0; this vibromap reads version 2 only: make the file again with this vibromap")
and then the attribute checksum vibromap writes into every file (_io/seal.py; "FILE:
damaged: its attributes fail their checksum (...)"), a chunk that fails its Fletcher32 checksum is
named, and whatever else h5py raises while reading a damaged or truncated file becomes one line
too. Scripts turn that into exit status 2. Only the current format of each kind is read.

The package imports them from here (`from vibromap._io import read_map`); every name the
modules above define, the private helpers some scripts use included, is this module's too
(postprocess/tests/test_readers.py checks it).
"""

# fmt: off
from .h5io import (FORMAT_VERSIONS, KIND_MARKS, READ_ERRORS, VERSION_ATTRIBUTE, FileVersionError, OpenFile,
                           VibromapFileError, _attribute_value, _check_kind_mark, _flag_meanings, _missing_chunk,
                           _one_line, _scalar, _stored_version, _text, open_h5, read_dataset, save_figure,
                           version_refusal, write_plot)
from .regimes import (FLAG_NO, FLAG_UNKNOWN, FLAG_YES, HERTZ_KEY, HERTZ_LIMIT_DEFAULT, NOT_COMPUTED,
                              REGIME_FLAG_MEANINGS, REGIME_FLAG_VALUES, REGIME_PERIODIC, SOFT_FROM_MAP, SOFT_KEY,
                              STABLE_FLAG_MEANINGS, STABLE_FLAG_VALUES, STABLE_NO, STABLE_UNKNOWN, STABLE_YES,
                              STATUS_FLAG_MEANINGS, STATUS_FLAG_VALUES, STEADY_ANSWERS, _label_key, regime_counts,
                              regime_labels)
from .map import (CENSUS_ATTRACTOR, CENSUS_CELL, FAMILY_DATASETS, FAMILY_EDGE, FAMILY_LABEL_CHANGE,
                          MAP_ATTRIBUTES, MAP_REQUIRED, NOT_COMPUTED_NOTE, REFINE_ATTRIBUTES, REFINE_DATASETS, MapAxis,
                          SweepMap, _check_layout, _check_progress_attributes, _check_soft_attributes, _map_axes,
                          _read_cells, axis_name, census_regimes, read_map)
from .soft import (SoftInfo, add_soft_cells, computed_soft, hertz_validity, impact_cells,
                           periodic_with_impacts)
from .slice import (FixedValue, MapSlice, MapSliceError, _nearest_index, _runs, cell_boundary, cell_edges,
                            parse_fix, slice2d)
from .runfiles import (BASINS_ATTRIBUTES, BASINS_NOT_COMPUTED, BASINS_OVERLAP, BASINS_UNLISTED,
                            BASINS_UNRESOLVED, TRAJECTORY_ATTRIBUTES, TRAJECTORY_COLUMNS, BasinAttractor, BasinEntropy,
                            Basins, Trajectory, _read_basin_entropy, read_basins, read_trajectory)
from .curves import (CURVE_FILE_KIND, CURVE_KINDS, CURVE_VALUES, _CURVE_GROUP, _check_kind, _codim2, _column,
                             _curve, read_curves)
# fmt: on

# The modules whose names this one re-exports (the test of the re-export reads it).
MODULES = tuple(f"{__name__}.{name}" for name in ("h5io", "regimes", "map", "soft", "slice", "runfiles", "curves"))

__all__ = [name for name in dir() if not name.startswith("_") and name != "MODULES"]  # the public names
