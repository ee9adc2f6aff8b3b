"""Tests of postprocess/plot_restitution.py on JSON in the layout of `vibromap restitution
--format json` (src/cli/restitution_command.cpp)."""

from __future__ import annotations

import json
import os
import sys

import matplotlib.pyplot as plt

import conftest
from conftest import run, png_size
from vibromap.plot import _restitution as pr

SCRIPT = conftest.script("plot_restitution")

# Two laws, given out of e order: the reader sorts each law's points by e.
ROWS = [
    {"law": "flores", "e": 0.5, "chi": 1.6, "e_effective": 0.47},
    {"law": "flores", "e": 0.1, "chi": 14.4, "e_effective": 0.069},
    {"law": "hunt-crossley", "e": 0.1, "chi": 1.35, "e_effective": 0.516},
    {"law": "hunt-crossley", "e": 0.5, "chi": 0.75, "e_effective": 0.663},
]


def test_rows_are_grouped_by_law_and_sorted_by_e(tmp_path):
    path = tmp_path / "r.json"
    path.write_text(json.dumps(ROWS))
    laws = pr.read_rows(str(path))
    assert list(laws) == ["flores", "hunt-crossley"]
    assert laws["flores"] == [(0.1, 0.069), (0.5, 0.47)]


def test_figure_has_one_line_per_law_and_the_differences(tmp_path):
    path = tmp_path / "r.json"
    path.write_text(json.dumps(ROWS))
    fig = pr.make_figure(pr.read_rows(str(path)))
    ax, diff = fig.axes
    labels = [line.get_label() for line in ax.get_lines()]
    assert labels == ["e_effective = e", "flores", "hunt-crossley"]
    flores = diff.get_lines()[1]
    assert list(flores.get_ydata()) == [0.069 - 0.1, 0.47 - 0.5]
    plt.close(fig)


def test_script_writes_a_png_and_refuses_bad_input(tmp_path):
    path = tmp_path / "r.json"
    path.write_text(json.dumps(ROWS))
    out = tmp_path / "r.png"
    r = run([*SCRIPT, str(path), "-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert png_size(out) == (1350, 675)
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps([{"law": "flores", "e": 0.5}]))
    r = run([*SCRIPT, str(bad), "-o", str(out)])
    assert r.returncode == 2
    assert r.stderr.startswith("plot_restitution: error:") and "e_effective" in r.stderr
