"""Maps with one random byte of dataset storage flipped are never accepted silently: the
Python reader refuses them with a one-line reason, and `vibromap sweep --resume` either refuses
them with one error line or repairs them, ending with the undamaged map (every dataset but
wall_s identical to the reference).

VIBROMAP_DAMAGED_MAPS sets how many damaged copies are tried (16 by default; the README's
figure is from 80). Run by ctest (tests/campaigns/sweep_tests.cmake)."""
import os
import random
import shutil
import subprocess
import sys

import h5py
import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "postprocess"))
from campaign_helpers import ENV, EXE, reference_map  # noqa: E402
from vibromap import _io as vibromap_h5  # noqa: E402

TRIALS = int(os.environ.get("VIBROMAP_DAMAGED_MAPS", "16"))

# Cheap cells (no forcing: no contact), 2 chunks per dataset.
SCENE = """
[forcing]
F0 = 0.0

[sweep]
E1 = { from = 2e4, to = 2.1e11, n = 200, scale = "log" }
E2 = { from = 2e4, to = 2.1e11, n = 300, scale = "log" }
store = ["T_con", "k_con", "periods"]
"""


def storage(path):
    """(dataset name, byte offset, size) of every chunk of every dataset of the file."""
    chunks = []
    with h5py.File(path, "r") as f:
        for name, item in f.items():
            if not isinstance(item, h5py.Dataset):
                continue
            for i in range(item.id.get_num_chunks()):
                info = item.id.get_chunk_info(i)
                chunks.append((name, info.byte_offset, info.size))
    return chunks


def flip(path, offset):
    with open(path, "r+b") as f:
        f.seek(offset)
        byte = f.read(1)[0]
        f.seek(offset)
        f.write(bytes([byte ^ random.randint(1, 255)]))


def same_map(a, b):
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        if sorted(fa) != sorted(fb):
            return False
        return all(name == "wall_s" or np.array_equal(fa[name][()], fb[name][()], equal_nan=True) for name in fa)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    return reference_map(tmp_path_factory.mktemp("damaged"), SCENE)


def test_no_damaged_map_is_accepted_silently(reference, tmp_path):
    scene, ref = reference
    chunks = storage(ref)
    assert {name for name, _, _ in chunks} >= {"E1", "E2", "done", "regime", "T_con", "periods"}
    rng = random.Random(20261123)
    random.seed(20261123)
    outcomes = {"refused": 0, "repaired": 0}
    for trial in range(TRIALS):
        name, offset, size = rng.choice(chunks)
        damaged = tmp_path / f"damaged{trial}.h5"
        shutil.copy(ref, damaged)
        flip(damaged, offset + rng.randrange(size))
        with pytest.raises(vibromap_h5.VibromapFileError, match="damaged|cannot"):
            vibromap_h5.read_map(str(damaged))
        proc = subprocess.run([EXE, "sweep", str(scene), "-o", str(damaged), "-q", "--resume"], env=ENV,
                              capture_output=True, text=True, timeout=300)
        context = f"trial {trial}: byte in a chunk of '{name}'\n{proc.stderr}"
        if proc.returncode == 0:
            assert same_map(ref, damaged), context
            assert "damaged chunk" in proc.stderr, context  # the repair is said
            outcomes["repaired"] += 1
        else:
            assert proc.returncode in (2, 4), context
            assert proc.stderr.count("vibromap: error: ") == 1, context
            outcomes["refused"] += 1
        damaged.unlink()
    print(f"{TRIALS} damaged maps: {outcomes['repaired']} repaired to the reference, {outcomes['refused']} refused")
    assert sum(outcomes.values()) == TRIALS
