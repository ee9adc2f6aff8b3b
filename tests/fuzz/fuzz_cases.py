"""The cases of the command-line fuzzer (fuzz_cli.py): what to run, in which directory, and
what must hold afterwards. Pure: nothing here runs vibromap or touches the disk except to read
the scenes under jobs/.

A case is a Draft (the command line, the files to make in its scratch directory, and its
expectations) built from a base command by a list of mutations. Each mutation is a kind and a
seed of its own, so a case is rebuilt exactly from (base, mutations) and a failing case can be
shrunk by dropping mutations one at a time (fuzz_cli.py --minimise).

Classes (issue #28):
  scene       mutated scene files: keys deleted, duplicated, retyped, numbers replaced by
              extremes, sections mangled, truncation, random bytes, deep nesting, long lines
  scene-path  scenes that are not sane regular files: /dev/null, /dev/zero, /dev/urandom, a
              FIFO, a directory, a sparse 1 GiB file, a missing or empty path, long names
  options     mutated options: --set with extremes or malformed, empty values, unknown
              options, bad grids, planes, ranges, laws and targets
  output      hostile outputs: a symbolic link to a canary, a dangling link, a FIFO, a device
              node, a directory, NAME_MAX+1 names, empty names, missing directories, an
              existing file, links in place of the lock, journal and derived files
  signal      SIGTERM or SIGINT during a longer run: it must end within a bound
  damage      bytes flipped in a finished map, or its format version changed (another number, or
              none), then sweep --resume, summarize_map, plot_regime_map or plot_kcon_map (each must
              refuse in one line, never die of a signal)
"""
import ast
import copy
import functools
import math
import os
import random
import re
from dataclasses import dataclass, field

CLASSES = ("scene", "scene-path", "options", "output", "signal", "damage")
# How often each class is drawn (signal cases take seconds, the others a fraction of one).
CLASS_WEIGHTS = {"scene": 5, "scene-path": 2, "options": 5, "output": 4, "signal": 1, "damage": 1}

SCENE = "scene.toml"     # the scene's name in the scratch directory
OUT = "out.h5"           # the output's name in the scratch directory
CANARY_DIR = "keep"      # canaries live here, inside the scratch directory
CANARY = f"{CANARY_DIR}/canary.txt"
CANARY_TEXT = b"canary: a file no vibromap run may change\n"

# Numbers a scene or an option may be given: zeros, tiny and huge floats, non-finite values
# (TOML has nan and inf), integer limits and integers past every limit.
EXTREME_NUMBERS = ("0", "-0.0", "-1", "1e-300", "-1e-300", "5e-324", "1e308", "-1e308",
                   "1.7976931348623157e308", "nan", "-nan", "inf", "-inf", "2147483647",
                   "-2147483648", "2147483648", "4294967297", "9223372036854775807",
                   "-9223372036854775808", "99999999999999999999999", "1e-9", "1e9", "1e15",
                   "0.5", "1", "3", "64", "65", "1e6")
# Values of another type, or empty ones, for any key.
RETYPED_VALUES = ('"abc"', '""', "true", "false", "[]", "[1, 2]", "[[1], [2]]", "{}",
                  "{ from = 1, to = 2, n = 2 }", "1979-05-27", "07:32:00", '"1e3"', "'single'",
                  '"\\u0000"', '"' + "x" * 300 + '"', "0x10", "1_000", "+1", ".5", "1e",
                  "--1", "'''multi\nline'''")
# Non-TOML --set values: read as a string, or refused.
RAW_SET_VALUES = ("", " ", "abc", "1,2", "1 2", "=", "[", "{", "]]", "\\", "1e", "1..2",
                  "0x", "nan(1)", "1e99999", "-1e99999", "\u00e9", "\t")
STRING_VALUES = ('"hertz"', '"flores"', '"rk4"', '"dopri5"', '"shooting"', '"integrate"',
                 '"bogus"', '""', '"HERTZ"', '" hertz"', '"all"', "1", "[]", '["hertz", "bogus"]')
BAD_GRIDS = ("", "0x0", "1x1", "1x3", "4097x2", "2x4097", "-3x3", "3x", "x3", "3x3x3",
             "99999999999999999999x2", "3X3", " 3x3", "3x3 ", "3.5x3", "nanx3", "3*3",
             "2147483648x2", "x", "3x-3", "0x10")
BAD_PLANES = ("", "x1,x1", "x1", "q1,v1", ",", "x1,v1,x2", "X1,V1", "x1, v1", "x1;v1", "v2,x2")
BAD_AT = ("", "x2", "=1", "x2=", "x2=nan", "x2=inf", "x2=1e308", "x9=1", "x2=1=2", "x1=0",
          "v2=-1e308", "x2=abc")
BAD_NUMBERS = ("", " ", "abc", "0", "-0", "-1", "1e-300", "1e308", "nan", "inf", "-inf",
               "2147483647", "2147483648", "-2147483649", "99999999999999999999", "0x10",
               "1e", "1.5", "1,5", "+", "5e-324")
UNKNOWN_OPTIONS = ("--frobnicate", "-Z", "--", "-", "--set", "--output=", "---x", "--e=",
                   "--help=1", "-qq", "--quiet=yes", "--format", "-f=xml")
MALFORMED_SETS = ("nokey", "=5", "a.b.c.d=1", "system.m1=", "system.m1", "system.=1",
                  ".m1=1", "bogus.m1=1", "system.bogus=1", "system.m1==1", "m1=1",
                  "system.m1 = 1", "sweep.=1", "sweep.bogus={from=1,to=2,n=2}",
                  "census.x1=[1]", "census.x1=[1,2,3]", "optimise.m2={min=1}", "SYSTEM.M1=1",
                  "system.m1=1\nsystem.m2=2", "x" * 5000 + "=1")
LAWS = ("hertz", "hunt-crossley", "lankarani-nikravesh", "flores", "gonthier")

# Options that take a value, per command (checked against each command's --help at start-up:
# fuzz_cli.py drops those the binary does not list).
VALUE_OPTIONS = {
    "run": ("-f", "-t"),
    "sweep": ("-o", "-f"),
    "accuracy": ("--csv", "-f"),
    "optimise": ("-o", "-f"),
    "orbit-diagram": ("-p", "--from", "--to", "-n", "--scale", "--transient", "--keep", "-o", "-f"),
    "continue": ("-p", "--from", "--to", "--ds-max", "--max-points", "--pd-depth", "--curve", "--param2", "--from2",
                 "--to2", "-o", "-f"),
    "basins": ("--plane", "--grid", "--at", "-o", "--checkpoint", "-f"),
    "restitution": ("--law", "--e", "-f"),
    "keys": (),
}
NUMERIC_OPTIONS = ("--from", "--to", "-n", "--transient", "--keep", "--ds-max", "--max-points",
                   "--pd-depth", "--checkpoint", "--e", "--from2", "--to2")
# The option naming each writing command's output file.
OUTPUT_OPTION = {"run": "-t", "sweep": "-o", "optimise": "-o", "basins": "-o",
                 "orbit-diagram": "-o", "continue": "-o", "accuracy": "--csv"}
# Default output names (no -o), from the scene's name.
DEFAULT_OUTPUT = {"sweep": "scene.h5", "optimise": "scene_optimise.h5", "basins": "scene_basins.h5"}
# Commands that keep a checkpoint: SIGTERM must end them with exit code 3 (or 0), never by death.
CHECKPOINTING = ("sweep", "basins", "optimise")
# Commands a stop signal must end with exit 3, never by the signal's default action: the
# checkpointing campaigns, and continue (stopped before its next point, what it found written).
STOPS_WITH_EXIT_3 = CHECKPOINTING + ("continue",)
SCENE_COMMANDS = ("run", "sweep", "accuracy", "optimise", "orbit-diagram", "continue", "basins")
ALL_COMMANDS = SCENE_COMMANDS + ("restitution", "keys")


# The postprocess scripts a damaged map is given to (each run as a program: postprocess/vibromap-post NAME map.h5).
POSTPROCESS_SCRIPTS = ("summarize_map", "plot_regime_map", "plot_kcon_map")


@dataclass
class Setup:
    """One thing made in the case's scratch directory before the run."""
    kind: str        # file, fifo, dir, symlink, device, sparse, copy, flip, version
    name: str        # path relative to the scratch directory
    # file: content; symlink: target; copy: a key of the shared files; sparse: size; flip: a repr
    # of the flips; version: a repr of the map's new format version (None: the attribute removed)
    data: bytes = b""


@dataclass
class Draft:
    """A case under construction, and once built, the case itself."""
    command: str
    args: list                      # arguments after the executable
    scene: bytes = b""              # content of SCENE (written when the args name it)
    setup: list = field(default_factory=list)
    expect: tuple = ()              # exit codes the case must end with (empty: any of 0, 2, 3, 4)
    expect_why: str = ""            # what the expectation stands for, for the report
    canaries: list = field(default_factory=list)   # paths that must not change (lstat and content)
    absent: list = field(default_factory=list)     # paths that must still not exist afterwards
    json: bool = False              # stdout is JSON on exit 0
    signal: tuple = ()              # (signal name, delay in s)
    post: str = ""                  # damage: "resume", or a POSTPROCESS_SCRIPTS script's name
    quick: bool = False             # a refusal must come within the quick bound
    notes: list = field(default_factory=list)      # one line per mutation applied


@dataclass
class Case:
    index: int
    cls: str
    base: str                       # the base command's name (e.g. "sweep:e1_e2")
    mutations: list                 # [(kind, seed)], applied in order
    draft: Draft


# ---- base commands -----------------------------------------------------------------------

def shrink_scene(text):
    """A scene's [sweep] reduced to two values an axis (n = 2, the first two of each values
    list), so a sweep of it costs a fraction of a second."""
    text = re.sub(r"([{,]\s*)n\s*=\s*\d+", r"\1n = 2", text)
    return re.sub(r"(values\s*=\s*\[)([^,\]]*),([^,\]]*)(,[^\]]*)?\]", r"\1\2,\3]", text)


def load_scenes(jobs):
    """The scenes the cases start from, shrunk, by name (jobs/<folder>/<name>.toml)."""
    names = {"table1": "paper/table1.toml", "table2": "paper/table2.toml",
             "e1_e2": "demo/e1_e2.toml", "frequency_response": "demo/frequency_response.toml",
             "restitution_e2": "demo/restitution_e2.toml", "optimise_law": "demo/optimise_law.toml",
             "optimise_box": "paper/optimise_box.toml", "optimise_robust": "paper/optimise_robust.toml",
             "extremes": "study/extremes.toml"}
    scenes = {}
    for name, rel in names.items():
        with open(os.path.join(jobs, rel), encoding="utf-8") as f:
            scenes[name] = shrink_scene(f.read()).encode()
    return scenes


# Scenes each command starts from.
COMMAND_SCENES = {
    "run": ("table1", "table2", "restitution_e2", "optimise_law"),
    "sweep": ("e1_e2", "frequency_response", "restitution_e2", "extremes", "optimise_box"),
    "accuracy": ("table1", "table2"),
    "optimise": ("optimise_law", "optimise_box", "optimise_robust"),
    "orbit-diagram": ("table1", "table2"),
    "continue": ("table1", "table2"),
    "basins": ("table1", "table2"),
}
CHEAP = ["--set", "analysis.max_periods=20"]
OPTIMISE_CHEAP = ["--set", "optimise.max_evaluations=3", "--set", "optimise.seeds=1",
                  "--set", "optimise.best=1", "--set", "optimise.soft_check_initial_conditions=4",
                  "--set", "census.initial_conditions=4"]


def base_args(command, rng, out=OUT):
    """A cheap command line of `command` on SCENE writing `out` (None: no output option)."""
    o = (lambda opt: [opt, out] if out is not None else [])
    if command == "run":
        return ["run", SCENE, *CHEAP] + (["-t", out] if out is not None and rng.random() < 0.3 else [])
    if command == "sweep":
        return ["sweep", SCENE, *o("-o"), "-q", *CHEAP]
    if command == "optimise":
        return ["optimise", SCENE, *o("-o"), "-q", *CHEAP, *OPTIMISE_CHEAP]
    if command == "basins":
        return ["basins", SCENE, "--grid", "3x3", *o("-o"), "-q", *CHEAP]
    if command == "orbit-diagram":
        return ["orbit-diagram", SCENE, "-p", "forcing.omega", "--from", "7", "--to", "7.5", "-n", "3",
                "--transient", "5", "--keep", "2", "-q", *o("-o")]
    if command == "continue":
        return ["continue", SCENE, "-p", "forcing.omega", "--from", "7", "--to", "7.5",
                "--max-points", "20", *o("-o"), *CHEAP]
    if command == "accuracy":
        return ["accuracy", SCENE, "-q", *(["--csv", "out.csv"] if out is not None else []),
                "--set", "analysis.max_periods=5"]
    if command == "restitution":
        return ["restitution", "--e", rng.choice(("0.5", "0.9", "1"))]
    return ["keys"] + (["--toml"] if rng.random() < 0.5 else [])


def base_draft(command, rng, scenes, out=OUT):
    """A draft of a cheap, valid run of `command` (a scene picked for it)."""
    args = base_args(command, rng, out)
    name = rng.choice(COMMAND_SCENES[command]) if command in COMMAND_SCENES else ""
    draft = Draft(command=command, args=args, scene=scenes[name] if name else b"")
    if rng.random() < 0.5 and command not in ("keys",):
        args += ["-f", "json"]
        draft.json = True
    return f"{command}:{name}" if name else command, draft


# ---- helpers on arguments ----------------------------------------------------------------

def set_option(args, opt, value):
    """Give `opt` the value `value`: replace the value after its first occurrence or append."""
    if opt in args:
        i = args.index(opt)
        if i + 1 < len(args):
            args[i + 1] = value
            return
    args += [opt, value]


def drop_option(args, opt, has_value=True):
    while opt in args:
        i = args.index(opt)
        del args[i:i + (2 if has_value else 1)]


def output_of(draft):
    """The output file the draft names (its output option's value), or None."""
    opt = OUTPUT_OPTION.get(draft.command)
    if opt and opt in draft.args:
        i = draft.args.index(opt)
        return draft.args[i + 1] if i + 1 < len(draft.args) else None
    return None


# ---- the key catalogue -------------------------------------------------------------------

@dataclass
class Key:
    name: str   # section.key
    kind: str   # float, int, bool, string, array, box, axis


def parse_keys(text):
    """Scene keys from `vibromap keys` (first column section.key, the type read off the
    'allowed' column). Unknown formats give floats: the fuzzer only needs a guess."""
    keys = []
    for line in text.splitlines():
        m = re.match(r"^((system|contact|forcing|solver|analysis|initial|sweep|optimise|census)\.\w+)\s+(.*)$", line)
        if not m:
            continue
        name, rest = m.group(1), m.group(3)
        if name == "sweep.KEY":
            kind = "axis"
        elif "an integer" in rest:
            kind = "int"
        elif "true or false" in rest:
            kind = "bool"
        elif "one of" in rest or "a name" in rest or "a law" in rest or "a path" in rest or "quantity" in rest or "every axis" in rest or '"(n,k)"' in rest:
            kind = "string"
        elif "[lo, hi]" in rest:
            kind = "array"
        elif "{ min, max" in rest:
            kind = "box"
        else:
            kind = "float"
        keys.append(Key(name, kind))
    return keys


FALLBACK_KEYS = [Key(n, k) for n, k in (
    ("system.m1", "float"), ("system.m2", "float"), ("system.omega1", "float"), ("system.k2", "float"),
    ("system.D", "float"), ("contact.E1", "float"), ("contact.nu1", "float"), ("contact.R2", "float"),
    ("contact.law", "string"), ("contact.restitution", "float"), ("forcing.omega", "float"),
    ("forcing.F0", "float"), ("solver.method", "string"), ("solver.rtol", "float"),
    ("solver.rk4_steps", "int"), ("solver.max_steps", "int"), ("analysis.max_periods", "int"),
    ("analysis.n_max", "int"), ("census.initial_conditions", "int"), ("census.x1", "array"),
    ("optimise.m2", "box"), ("sweep.KEY", "axis"))]


def number(rng):
    return rng.choice(EXTREME_NUMBERS)


def value_for(key, rng):
    """A TOML value for `key`: mostly extreme values of its own type, sometimes another type."""
    if rng.random() < 0.15:
        return rng.choice(RETYPED_VALUES)
    if key.kind == "bool":
        return rng.choice(("true", "false", "1", '"yes"'))
    if key.kind == "string":
        return rng.choice(STRING_VALUES)
    if key.kind == "array":
        return rng.choice((f"[{number(rng)}, {number(rng)}]", "[]", f"[{number(rng)}]",
                           f"[-{rng.choice(('1e308', '1e300', '1'))}, {rng.choice(('1e308', '1e300', '1'))}]"))
    if key.kind == "box":
        scale = rng.choice(("", ", scale = \"log\"", ", scale = \"bogus\""))
        return f"{{ min = {number(rng)}, max = {number(rng)}{scale} }}"
    if key.kind == "axis":
        return axis_value(rng)
    if key.kind == "int":
        return rng.choice(("0", "-1", "1", "2", "2147483647", "2147483648", "-2147483648",
                           "9223372036854775807", "99999999999999999999999", "1e9", "1.5", "64", "65"))
    return number(rng)


def axis_value(rng):
    """A [sweep] axis: { from, to, n } or { values } with extreme numbers."""
    if rng.random() < 0.7:
        n = rng.choice(("2", "0", "1", "-1", "3", "2147483647", "99999999999999999999", "1e3", "1.5"))
        scale = rng.choice(("", ", scale = \"log\"", ", scale = \"lin\"", ", scale = \"x\""))
        return f"{{ from = {number(rng)}, to = {number(rng)}, n = {n}{scale} }}"
    values = ", ".join(number(rng) for _ in range(rng.randint(0, 3)))
    return f"{{ values = [{values}] }}"


def axis_key(rng, keys):
    """A [sweep] axis name: a real scene key, a bare key, or none at all."""
    real = [k.name for k in keys if k.kind in ("float", "int") and k.name.split(".")[0]
            in ("system", "contact", "forcing", "solver", "analysis")]
    return rng.choice(real + ["E1", "omega", "contact.law", "bogus.key", "sweep.order", "m2"])


# ---- scene mutations ---------------------------------------------------------------------

KEY_LINE = re.compile(r'^(\s*)((?:"[^"\n]*"|[A-Za-z0-9_-]+)(?:\s*\.\s*(?:"[^"\n]*"|[A-Za-z0-9_-]+))*)\s*=\s*(.*)$')
SECTION_LINE = re.compile(r"^\s*\[([^\]]*)\]\s*(#.*)?$")
NUMBER_TOKEN = re.compile(r"(?<![\w.\"])[-+]?(?:\d[\d_]*(?:\.\d*)?(?:[eE][-+]?\d+)?|inf|nan)(?![\w.])")


def split_value(value):
    """A key line's value without its trailing comment."""
    if "#" not in value:  # the common case, and every line of the stress scenes' many keys
        return value.rstrip(), ""
    quote = None
    for i, c in enumerate(value):
        if quote:
            quote = None if c == quote else quote
        elif c in "\"'":
            quote = c
        elif c == "#":
            return value[:i].rstrip(), value[i:]
    return value.rstrip(), ""


# Lines of a scene looked at for a key to change: the scenes' own are a few hundred; a stress
# structure's 100,000 keys past them would make every case that meets one slow to build.
MAX_SCANNED_LINES = 2000


def key_lines(lines):
    """The indices of the key lines among the first MAX_SCANNED_LINES."""
    return [i for i, line in enumerate(lines[:MAX_SCANNED_LINES]) if KEY_LINE.match(line)]


def number_lines(lines):
    """The indices of the key lines (among the first MAX_SCANNED_LINES) whose value (without
    its comment) holds a number."""
    found = []
    for i, line in enumerate(lines[:MAX_SCANNED_LINES]):
        m = KEY_LINE.match(line)
        if m and NUMBER_TOKEN.search(split_value(m.group(3))[0]):
            found.append(i)
    return found


def section_lines(lines):
    return [i for i, line in enumerate(lines) if SECTION_LINE.match(line)]


def scene_lines(draft):
    return draft.scene.decode("utf-8", "replace").split("\n")


def put_lines(draft, lines):
    draft.scene = "\n".join(lines).encode("utf-8", "surrogatepass")


def mut_delete_key(draft, rng, keys):
    lines = scene_lines(draft)
    idx = key_lines(lines)
    if idx:
        i = rng.choice(idx)
        draft.notes.append(f"scene: deleted '{lines[i].strip()[:60]}'")
        del lines[i]
        put_lines(draft, lines)


def mut_duplicate_key(draft, rng, keys):
    lines = scene_lines(draft)
    idx = key_lines(lines)
    if idx:
        i = rng.choice(idx)
        m = KEY_LINE.match(lines[i])
        line = f"{m.group(2)} = {value_for(Key(m.group(2), 'float'), rng)}" if rng.random() < 0.5 else lines[i]
        lines.insert(i + 1, line)
        draft.notes.append(f"scene: duplicated key '{m.group(2)}' as '{line[:60]}'")
        put_lines(draft, lines)


def mut_retype(draft, rng, keys):
    lines = scene_lines(draft)
    idx = key_lines(lines)
    if idx:
        i = rng.choice(idx)
        m = KEY_LINE.match(lines[i])
        new = rng.choice(RETYPED_VALUES)
        lines[i] = f"{m.group(1)}{m.group(2)} = {new}"
        draft.notes.append(f"scene: {m.group(2)} = {new[:60]}")
        put_lines(draft, lines)


def mut_extreme(draft, rng, keys):
    """One number inside a value (a scalar, an axis, a box, an array) made extreme."""
    lines = scene_lines(draft)
    idx = number_lines(lines)
    if not idx:
        return
    i = rng.choice(idx)
    m = KEY_LINE.match(lines[i])
    value, _ = split_value(m.group(3))
    tokens = list(NUMBER_TOKEN.finditer(value))
    t = rng.choice(tokens)
    new = number(rng)
    value = value[:t.start()] + new + value[t.end():]
    lines[i] = f"{m.group(1)}{m.group(2)} = {value}"
    draft.notes.append(f"scene: {m.group(2)} = {value[:80]}")
    put_lines(draft, lines)


def mut_scale(draft, rng, keys):
    """One number scaled by a power of ten or nudged: a value that is mostly still allowed,
    so the run goes on to compute and write (the outputs' numbers are then checked)."""
    lines = scene_lines(draft)
    idx = number_lines(lines)
    if not idx:
        return
    i = rng.choice(idx)
    m = KEY_LINE.match(lines[i])
    value, _ = split_value(m.group(3))
    t = rng.choice(list(NUMBER_TOKEN.finditer(value)))
    try:
        x = float(t.group(0).replace("_", ""))
    except ValueError:
        return
    factor = rng.choice((1e-6, 1e-3, 0.1, 0.5, 0.99, 1.01, 2.0, 10.0, 1e3, 1e6))
    y = x * factor
    if not math.isfinite(y):  # nan, inf (a TOML token, or an overflow): written as TOML writes it
        new = "nan" if math.isnan(y) else ("inf" if y > 0 else "-inf")
    elif "." in t.group(0) or "e" in t.group(0).lower() or factor < 1:
        new = repr(y)
    else:
        new = str(int(y))
    value = value[:t.start()] + new + value[t.end():]
    lines[i] = f"{m.group(1)}{m.group(2)} = {value}"
    draft.notes.append(f"scene: {m.group(2)} = {value[:80]}")
    put_lines(draft, lines)


def mut_add_key(draft, rng, keys):
    """A key of the catalogue (or an unknown one) with an extreme value, in its section."""
    lines = scene_lines(draft)
    key = rng.choice(keys)
    section, name = key.name.split(".", 1)
    if key.kind == "axis":
        section, name, value = "sweep", f'"{axis_key(rng, keys)}"', axis_value(rng)
    elif rng.random() < 0.1:
        name, value = rng.choice(("bogus", "M1", "m1 ", "k1", "omega")), number(rng)
    else:
        value = value_for(key, rng)
    header = [i for i in section_lines(lines) if SECTION_LINE.match(lines[i]).group(1).strip() == section]
    if header:
        lines.insert(header[0] + 1, f"{name} = {value}")
    else:
        lines += [f"[{section}]", f"{name} = {value}"]
    draft.notes.append(f"scene: [{section}] {name} = {value[:80]}")
    put_lines(draft, lines)


def mut_sections(draft, rng, keys):
    lines = scene_lines(draft)
    heads = section_lines(lines)
    choice = rng.randrange(5)
    if choice == 0 and heads:
        i = rng.choice(heads)
        draft.notes.append(f"scene: removed the header '{lines[i].strip()}'")
        del lines[i]
    elif choice == 1 and heads:
        i = rng.choice(heads)
        lines.append(lines[i])
        lines.append("m1 = 1")
        draft.notes.append(f"scene: the header '{lines[i].strip()}' twice")
    elif choice == 2:
        new = rng.choice(("[bogus]", "[]", "[system.sub]", "[[system]]", "[ system ]", "[sweep", "[census]\n[census]"))
        lines.append(new)
        lines.append("x = 1")
        draft.notes.append(f"scene: added '{new}'")
    elif choice == 3:
        lines.insert(0, "m1 = 5")
        draft.notes.append("scene: a key before any section")
    else:
        lines = [line.replace("[", "[[", 1).replace("]", "]]", 1) if SECTION_LINE.match(line) else line for line in lines]
        draft.notes.append("scene: every section an array of tables")
    put_lines(draft, lines)


def mut_truncate(draft, rng, keys):
    cut = rng.randrange(len(draft.scene) + 1)
    draft.scene = draft.scene[:cut]
    draft.notes.append(f"scene: truncated to {cut} bytes")


def mut_flip(draft, rng, keys):
    data = bytearray(draft.scene)
    flips = rng.randint(1, 4)
    for _ in range(flips if data else 0):
        data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
    draft.scene = bytes(data)
    draft.notes.append(f"scene: {flips} bits flipped")


def mut_garbage(draft, rng, keys):
    junk = bytes(rng.randrange(256) for _ in range(rng.randint(0, 2048)))
    if rng.random() < 0.5:
        draft.scene = junk
        draft.notes.append(f"scene: {len(junk)} random bytes")
    else:
        at = rng.randrange(len(draft.scene) + 1)
        draft.scene = draft.scene[:at] + junk[:64] + draft.scene[at:]
        draft.notes.append(f"scene: {len(junk[:64])} random bytes inserted at {at}")


# The stress structures of mut_monster, each built once when first drawn (some are megabytes:
# building all of them for every draw made case generation slow).
MONSTERS = (
    ("[system]", lambda: "x = " + "[" * 100000 + "]" * 100000),
    ("[system]", lambda: "x = " + "{ a = " * 20000 + "1" + " }" * 20000),
    ("[system]", lambda: "x = \"" + "a" * 1000000 + "\""),
    ("", lambda: "# " + "c" * 3000000),
    ("[bogus]", lambda: "\n".join(f"k{i} = {i}" for i in range(100000))),
    ("[system]", lambda: "x = \"\x00\"\n\x00"),
    ("[sweep]", lambda: "store = [" + "\"T_con\", " * 100000 + "]"),
)


@functools.lru_cache(maxsize=None)
def monster(choice):
    section, make = MONSTERS[choice]
    extra = make()
    return ("\n" + section + "\n" + extra + "\n").encode(), len(extra)


def mut_monster(draft, rng, keys):
    """Structures that stress a parser: deep nesting, long lines, many keys, NUL bytes."""
    choice = rng.randrange(len(MONSTERS))
    text, size = monster(choice)
    draft.scene = draft.scene + text
    draft.notes.append(f"scene: stress structure {choice} ({size} bytes)")


def mut_encoding(draft, rng, keys):
    choice = rng.randrange(4)
    if choice == 0:
        draft.scene = draft.scene.replace(b"\n", b"\r\n")
        draft.notes.append("scene: CRLF line ends")
    elif choice == 1:
        draft.scene = b"\xef\xbb\xbf" + draft.scene
        draft.notes.append("scene: a UTF-8 byte order mark")
    elif choice == 2:
        draft.scene = draft.scene.decode("utf-8", "replace").encode("utf-16")
        draft.notes.append("scene: UTF-16")
    else:
        draft.scene = draft.scene.replace(b"\n", b"\r")
        draft.notes.append("scene: CR line ends")


SCENE_MUTATIONS = {
    "delete_key": (mut_delete_key, 3), "duplicate_key": (mut_duplicate_key, 2), "retype": (mut_retype, 3),
    "extreme": (mut_extreme, 8), "scale": (mut_scale, 6), "add_key": (mut_add_key, 6), "sections": (mut_sections, 1),
    "truncate": (mut_truncate, 2), "flip": (mut_flip, 2), "garbage": (mut_garbage, 1),
    "monster": (mut_monster, 1), "encoding": (mut_encoding, 1),
}


# ---- option mutations --------------------------------------------------------------------

def mut_set_extreme(draft, rng, keys):
    key = rng.choice(keys)
    if key.kind == "axis":
        text = f"sweep.{axis_key(rng, keys)}={axis_value(rng)}"
    else:
        text = f"{key.name}={value_for(key, rng)}"
    draft.args += ["--set", text]
    draft.notes.append(f"--set {text[:100]}")


def mut_set_scaled(draft, rng, keys):
    """--set of a real key to its default scaled by a power of ten: mostly allowed values."""
    reals = [k for k in keys if k.kind == "float" and k.name.split(".")[0] in ("system", "contact", "forcing", "initial")]
    if not reals:
        return mut_set_extreme(draft, rng, keys)
    key = rng.choice(reals)
    value = rng.choice(("1e-6", "1e-3", "0.1", "0.5", "2", "10", "1e3", "1e6", "1e9", "1e12"))
    scale = {"system.m1": 1000, "system.m2": 100, "system.omega1": 6.283, "system.omega2": 5.646, "system.D": 0.05,
             "contact.E1": 2.1e11, "contact.E2": 2.1e11, "contact.R1": 2, "contact.R2": 2, "forcing.F0": 500,
             "forcing.omega": 7.23, "contact.q": 0.319}.get(key.name, 1.0)
    text = f"{key.name}={float(value) * scale:.6g}"
    draft.args += ["--set", text]
    draft.notes.append(f"--set {text}")


def mut_set_raw(draft, rng, keys):
    key = rng.choice(keys)
    text = f"{key.name}={rng.choice(RAW_SET_VALUES)}" if rng.random() < 0.6 else rng.choice(MALFORMED_SETS)
    draft.args += ["--set", text]
    draft.notes.append(f"--set {text[:100]!r}")


def mut_empty_value(draft, rng, keys):
    options = VALUE_OPTIONS.get(draft.command, ())
    if not options:
        return mut_unknown_option(draft, rng, keys)
    opt = rng.choice(options)
    set_option(draft.args, opt, "")
    draft.notes.append(f"{opt} ''")


def mut_unknown_option(draft, rng, keys):
    choice = rng.randrange(5)
    if choice == 0:
        opt = rng.choice(UNKNOWN_OPTIONS)
        draft.args.append(opt)
        draft.notes.append(f"unknown option {opt!r} at the end")
    elif choice == 1:
        opt = rng.choice(UNKNOWN_OPTIONS)
        draft.args.insert(1, opt)
        draft.notes.append(f"unknown option {opt!r} first")
    elif choice == 2:
        options = VALUE_OPTIONS.get(draft.command, ())
        if options:
            opt = rng.choice(options)
            drop_option(draft.args, opt)
            draft.args.append(opt)
            draft.notes.append(f"{opt} without its value")
    elif choice == 3:
        extra = rng.choice((SCENE, "other.toml", "", "-", "run"))
        draft.args.append(extra)
        draft.notes.append(f"extra positional {extra!r}")
    else:
        flag = rng.choice(("--resume", "--overwrite", "--census", "--labels", "--toml", "-q", "--quiet"))
        draft.args.append(flag)
        if rng.random() < 0.3:
            draft.args.append("--resume" if flag == "--overwrite" else "--overwrite")
        draft.notes.append(f"flag {flag}")


def mut_numeric_option(draft, rng, keys):
    options = [o for o in VALUE_OPTIONS.get(draft.command, ()) if o in NUMERIC_OPTIONS]
    if not options:
        return mut_set_extreme(draft, rng, keys)
    opt = rng.choice(options)
    value = rng.choice(BAD_NUMBERS)
    set_option(draft.args, opt, value)
    draft.notes.append(f"{opt} {value!r}")


def mut_special_option(draft, rng, keys):
    """The command's own value options: grids, planes, --at, -p, ranges, laws, formats."""
    c = draft.command
    if c == "basins":
        opt, value = rng.choice((("--grid", rng.choice(BAD_GRIDS)), ("--plane", rng.choice(BAD_PLANES)),
                                 ("--at", rng.choice(BAD_AT)), ("--checkpoint", rng.choice(BAD_NUMBERS))))
    elif c == "continue" and rng.randrange(4) == 0:  # a curve in two parameters, its options bent
        k = rng.choice(keys)
        set_option(draft.args, "--curve", rng.choice(("fold", "grazing", "level:k_con=10", "level:k_con=nan",
                                                      "level:bogus=1", "level:z_ratio", "neimark-sacker", "")))
        set_option(draft.args, "--param2", rng.choice((k.name, "forcing.F0", "forcing.omega", "bogus", "")))
        lo, hi = rng.choice((("400", "600"), ("600", "400"), ("nan", "1"), ("-1e308", "1e308"), ("0", "0")))
        set_option(draft.args, "--from2", lo)
        opt, value = "--to2", hi
    elif c in ("orbit-diagram", "continue"):
        choice = rng.randrange(3)
        if choice == 0:
            k = rng.choice(keys)
            opt, value = "-p", rng.choice((k.name, "", "omega", "bogus", "contact.law", "sweep.order", "system"))
        elif choice == 1:
            lo, hi = rng.choice((("1e-300", "1e308"), ("0", "1"), ("7", "7"), ("8", "7"), ("-1", "1"),
                                 ("nan", "7"), ("1e-9", "1e-8"), ("7", "1e308"), ("inf", "-inf")))
            set_option(draft.args, "--from", lo)
            opt, value = "--to", hi
        else:
            opt, value = (("--scale", rng.choice(("log", "bogus", ""))) if c == "orbit-diagram"
                          else ("--pd-depth", rng.choice(("9", "-1", "8", "0", "99999999999"))))
    elif c == "restitution":
        opt = rng.choice(("--law", "--e"))
        value = (rng.choice(LAWS + ("bogus", "", "HERTZ", "hertz,flores")) if opt == "--law"
                 else rng.choice(("1e-6", "1e-7", "1e-300", "5e-324", "0", "1", "1.0000001", "nan", "-1", "", "0.001")))
        draft.args += [opt, value]
        draft.notes.append(f"{opt} {value!r}")
        return
    elif c == "keys":
        opt, value = "--toml", rng.choice(("1", "x"))
    else:
        opt, value = "-f", rng.choice(("xml", "", "JSON", "json,table"))
    set_option(draft.args, opt, value)
    draft.notes.append(f"{opt} {value!r}")


def mut_repeat_option(draft, rng, keys):
    options = VALUE_OPTIONS.get(draft.command, ())
    if not options:
        return mut_unknown_option(draft, rng, keys)
    opt = rng.choice(options)
    draft.args += [opt, "b.h5" if opt in ("-o", "-t", "--csv") else "1"]
    draft.notes.append(f"{opt} given twice")


OPTION_MUTATIONS = {
    "set_extreme": (mut_set_extreme, 8), "set_scaled": (mut_set_scaled, 5), "set_raw": (mut_set_raw, 3), "empty_value": (mut_empty_value, 3),
    "unknown_option": (mut_unknown_option, 2), "numeric_option": (mut_numeric_option, 3),
    "special_option": (mut_special_option, 4), "repeat_option": (mut_repeat_option, 1),
}


# ---- output cases ------------------------------------------------------------------------

def name_max(path):
    try:
        return os.pathconf(path, "PC_NAME_MAX")
    except (OSError, ValueError):
        return 255


def out_hostile(draft, rng, kind, can_mknod):
    """Makes the draft's output (its output option's value, or the command's default name)
    the hostile `kind`; returns False when the kind cannot be made here."""
    target = output_of(draft) or DEFAULT_OUTPUT.get(draft.command)
    if target is None:
        return False
    refuse, why = (2,), f"an output that is {kind.replace('-', ' ')} is refused with exit 2"
    if kind == "symlink":
        draft.setup += [Setup("file", CANARY, CANARY_TEXT), Setup("symlink", target, CANARY.encode())]
        draft.canaries += [CANARY, target]
    elif kind == "dangling-symlink":
        draft.setup += [Setup("dir", CANARY_DIR), Setup("symlink", target, f"{CANARY_DIR}/absent.h5".encode())]
        draft.canaries.append(target)
        draft.absent.append(f"{CANARY_DIR}/absent.h5")
    elif kind == "symlink-to-dir":
        draft.setup += [Setup("file", CANARY, CANARY_TEXT), Setup("symlink", target, CANARY_DIR.encode())]
        draft.canaries += [CANARY, target, CANARY_DIR]
    elif kind == "fifo":
        draft.setup.append(Setup("fifo", target))
        draft.canaries.append(target)
    elif kind == "device":
        if not can_mknod:
            return False
        draft.setup.append(Setup("device", target))
        draft.canaries.append(target)
    elif kind == "directory":
        draft.setup += [Setup("dir", target), Setup("file", f"{target}/inside.txt", CANARY_TEXT)]
        draft.canaries += [target, f"{target}/inside.txt"]
    elif kind == "existing":
        draft.setup.append(Setup("file", target, CANARY_TEXT))
        draft.canaries.append(target)
        why = "an existing output without --overwrite is refused with exit 2"
    else:
        return False
    draft.expect, draft.expect_why = refuse, why
    return True


def out_name(draft, rng, kind, scratch_name_max):
    """Replaces the output's name by a bad one (too long, empty, in a missing directory, ...)."""
    opt = OUTPUT_OPTION[draft.command]
    names = {
        "too-long": "o" * (scratch_name_max + 1 - 3) + ".h5",
        "long-path": "/".join(["d" * 200] * 30) + "/o.h5",
        "empty": "",
        "missing-dir": "no_such_dir/out.h5",
        "trailing-slash": "out.h5/",
        "dot": ".",
        "dotdot": "..",
        "scene": SCENE,
        "dev-dir": "/proc/self/fdinfo/out.h5",
    }
    if kind not in names:
        return False
    set_option(draft.args, opt, names[kind])
    draft.notes.append(f"{opt} {names[kind][:40]!r}{'...' if len(names[kind]) > 40 else ''} ({kind})")
    if kind == "scene" and "--overwrite" in draft.args:
        return True  # the user asked for it
    draft.expect = (2,) if kind in ("scene", "dot", "dotdot") else (2, 4)
    draft.expect_why = f"an output named {kind.replace('-', ' ')} is refused (exit {' or '.join(map(str, draft.expect))})"
    if kind == "scene":
        draft.canaries.append(SCENE)
    return True


# Links in place of the files a writer makes beside its output.
SIDE_FILES = {"sweep": (".lock",), "basins": (".lock",), "optimise": (".lock", ".journal", "_map.h5", "_trajectory.h5")}

HOSTILE_KINDS = ("symlink", "dangling-symlink", "symlink-to-dir", "fifo", "device", "directory", "existing")
NAME_KINDS = ("too-long", "long-path", "empty", "missing-dir", "trailing-slash", "dot", "dotdot", "scene", "dev-dir")


def side_file(out, suffix):
    if suffix.startswith("_"):
        return out[:-3] + suffix if out.endswith(".h5") else out + suffix
    return out + suffix


# ---- the case generators -----------------------------------------------------------------

class Generator:
    """Builds case `index` of a class from a seed: the same seed, class list and index give
    the same case on every machine."""

    def __init__(self, seed, classes, scenes, keys, flags, can_mknod, name_max_here, jobs_dir):
        self.seed, self.classes, self.scenes, self.keys = seed, classes, scenes, keys
        self.flags, self.can_mknod, self.name_max = flags, can_mknod, name_max_here
        self.jobs_dir = jobs_dir
        self.damage_scene = scenes["e1_e2"]

    def rng(self, *parts):
        return random.Random(":".join(str(p) for p in (self.seed, *parts)))

    def case(self, index):
        rng = self.rng("case", index)
        cls = rng.choices(self.classes, weights=[CLASS_WEIGHTS[c] for c in self.classes])[0]
        base, mutations = getattr(self, "plan_" + cls.replace("-", "_"))(rng)
        return self.build(index, cls, base, mutations)

    def build(self, index, cls, base, mutations):
        """The case from its base and mutations (also used to shrink a failing case)."""
        brng = self.rng("base", index)
        draft = getattr(self, "base_" + cls.replace("-", "_"))(base, brng)
        table = {**SCENE_MUTATIONS, **OPTION_MUTATIONS}
        for kind, seed in mutations:
            table[kind][0](draft, random.Random(seed), self.keys)
        return Case(index, cls, base, list(mutations), draft)

    @staticmethod
    def pick(rng, table):
        names = list(table)
        return rng.choices(names, weights=[table[n][1] for n in names])[0]

    def mutations(self, rng, table, low, high):
        return [(self.pick(rng, table), rng.randrange(1 << 30)) for _ in range(rng.randint(low, high))]

    # scene
    def plan_scene(self, rng):
        command = rng.choices(SCENE_COMMANDS, weights=(4, 3, 1, 1, 1, 1, 2))[0]
        return command, self.mutations(rng, SCENE_MUTATIONS, 1, 3)

    def base_scene(self, command, rng):
        _, draft = base_draft(command, rng, self.scenes)
        return draft

    # options
    def plan_options(self, rng):
        command = rng.choices(ALL_COMMANDS, weights=(3, 2, 1, 2, 2, 2, 3, 2, 1))[0]
        return command, self.mutations(rng, OPTION_MUTATIONS, 1, 3)

    def base_options(self, command, rng):
        _, draft = base_draft(command, rng, self.scenes)
        return draft

    # scene-path
    SCENE_PATHS = ("/dev/null", "/dev/zero", "/dev/urandom", "fifo", "directory", "sparse",
                   "missing", "empty", "long-name", "empty-name", "link-to-zero", "link-to-scene",
                   "trailing-slash", "/proc/self/mem", "/proc/self/environ", "/etc/shadow-like")

    def plan_scene_path(self, rng):
        command = rng.choice(SCENE_COMMANDS)
        return f"{command}|{rng.choice(self.SCENE_PATHS)}", []

    def base_scene_path(self, base, rng):
        command, kind = base.split("|")
        _, draft = base_draft(command, rng, self.scenes)
        draft.scene = b""   # SCENE is not written: the path below replaces it
        path = {"fifo": "scene.fifo", "directory": "scene.d", "sparse": "big.toml", "missing": "missing.toml",
                "empty": "empty.toml", "long-name": "s" * (self.name_max + 1 - 5) + ".toml", "empty-name": "",
                "link-to-zero": "zero.toml", "link-to-scene": "link.toml", "trailing-slash": "real.toml/",
                "/etc/shadow-like": "unreadable.toml"}.get(kind, kind)
        make = {"fifo": [Setup("fifo", path)], "directory": [Setup("dir", path)],
                "sparse": [Setup("sparse", path, b"1073741824")], "empty": [Setup("file", path, b"")],
                "link-to-zero": [Setup("symlink", path, b"/dev/zero")],
                "link-to-scene": [Setup("file", "real.toml", self.scenes["table1"]), Setup("symlink", path, b"real.toml")],
                "trailing-slash": [Setup("file", "real.toml", self.scenes["table1"])],
                "/etc/shadow-like": [Setup("file", path, self.scenes["table1"], )]}.get(kind, [])
        draft.setup += make
        draft.args[draft.args.index(SCENE)] = path
        if kind == "/etc/shadow-like":
            draft.setup.append(Setup("chmod000", path))
        if kind not in ("link-to-scene", "/etc/shadow-like", "empty"):  # an empty scene: every key's default
            draft.expect = (2, 4) if kind in ("missing", "long-name", "empty-name", "trailing-slash", "/proc/self/mem") else (2,)
            draft.expect_why = f"a scene that is {kind} is refused at once (exit {' or '.join(map(str, draft.expect))})"
            draft.quick = True
        draft.notes.append(f"scene path: {kind}")
        return draft

    # output
    def plan_output(self, rng):
        command = rng.choice(tuple(OUTPUT_OPTION))
        kinds = HOSTILE_KINDS + NAME_KINDS + ("default-name", "side-file")
        return f"{command}|{rng.choice(kinds)}|{int(rng.random() < 0.5)}", []

    def base_output(self, base, rng):
        command, kind, overwrite = base.split("|")
        scene_rng = random.Random(rng.random())
        _, draft = base_draft(command, scene_rng, self.scenes)
        if command == "run" and "-t" not in draft.args:
            draft.args += ["-t", OUT]
        if overwrite == "1" and "--overwrite" in self.flags.get(command, ()):
            draft.args.append("--overwrite")
            draft.notes.append("--overwrite")
        if kind == "default-name" and command in DEFAULT_OUTPUT:
            drop_option(draft.args, OUTPUT_OPTION[command])
            kind = rng.choice(HOSTILE_KINDS)
            draft.notes.append(f"default output name {DEFAULT_OUTPUT[command]}")
        elif kind in ("default-name", "side-file") and command in SIDE_FILES:
            suffix = rng.choice(SIDE_FILES[command])
            name = side_file(OUT, suffix)
            draft.setup += [Setup("file", CANARY, CANARY_TEXT), Setup("symlink", name, CANARY.encode())]
            draft.canaries += [CANARY, name]
            draft.notes.append(f"{name} a link to {CANARY}")
            return draft
        elif kind in ("default-name", "side-file"):
            kind = "symlink"
        if kind in NAME_KINDS:
            out_name(draft, rng, kind, self.name_max)
        elif not out_hostile(draft, rng, kind, self.can_mknod):
            out_hostile(draft, rng, "symlink", self.can_mknod)
            kind = "symlink"
        if kind in HOSTILE_KINDS:
            draft.notes.append(f"output {output_of(draft) or DEFAULT_OUTPUT.get(command)} is {kind.replace('-', ' ')}")
        if "--overwrite" in draft.args and kind == "existing":  # replacing it is what was asked
            draft.expect, draft.expect_why = (), ""
            draft.canaries = [c for c in draft.canaries if c != output_of(draft) and c != DEFAULT_OUTPUT.get(command)]
        return draft

    # signal
    SIGNAL_RUNS = (
        ("sweep", ["sweep", "FULL:e1_e2", "-o", OUT, "-q"]),
        ("sweep", ["sweep", "FULL:extremes", "-o", OUT, "-q"]),
        ("basins", ["basins", "table2", "--grid", "24x24", "-o", OUT, "-q"]),
        ("optimise", ["optimise", "optimise_law", "-o", OUT, "-q"]),
        ("optimise", ["optimise", "optimise_box", "-o", OUT, "-q", "--set", "optimise.seeds=2"]),
        ("orbit-diagram", ["orbit-diagram", "table2", "-p", "forcing.omega", "--from", "3", "--to", "12", "-o", OUT, "-q"]),
        ("continue", ["continue", "table1", "-p", "forcing.omega", "--from", "3", "--to", "12"]),
        ("accuracy", ["accuracy", "table1", "-q"]),
        ("run", ["run", "table2", "--census", "--set", "census.initial_conditions=512"]),
        ("run", ["run", "table1", "--set", "forcing.omega=1e-9"]),
        ("run", ["run", "table1", "--set", "solver.method=\"rk4\"", "--set", "solver.rk4_steps=2147483647"]),
        ("continue", ["continue", "table1", "-p", "forcing.omega", "--from", "1e-300", "--to", "1e308"]),
        ("sweep", ["sweep", "/dev/zero", "-o", OUT, "-q"]),
        ("orbit-diagram", ["orbit-diagram", "/dev/urandom", "-p", "forcing.omega", "--from", "7", "--to", "8"]),
        ("optimise", ["optimise", "optimise_law", "-o", OUT, "-q", "--set", "system.omega1=2147483647"]),
    )

    def plan_signal(self, rng):
        i = rng.randrange(len(self.SIGNAL_RUNS))
        return f"{i}|{rng.choice(('SIGTERM', 'SIGINT'))}|{rng.uniform(0.3, 1.5):.2f}", []

    def base_signal(self, base, rng):
        i, signame, delay = base.split("|")
        command, args = self.SIGNAL_RUNS[int(i)]
        args = list(args)
        draft = Draft(command=command, args=args, signal=(signame, float(delay)))
        scene = args[1]
        if not scene.startswith("/"):
            full = scene.startswith("FULL:")
            name = scene.split(":")[-1]
            text = self.scenes[name]
            if full:  # the unshrunk scene: a run long enough to be stopped
                with open(os.path.join(self.jobs_dir, {"e1_e2": "demo/e1_e2.toml", "extremes": "study/extremes.toml"}[name]), "rb") as f:
                    text = f.read()
            draft.scene = text
            args[1] = SCENE
        draft.notes.append(f"{signame} after {delay} s")
        return draft

    # damage
    def plan_damage(self, rng):
        post = rng.choice(("resume", "resume") + POSTPROCESS_SCRIPTS)
        if rng.random() < 0.25:  # a map of another format version than 2 (None: made before files had one)
            return f"{post}|version {rng.choice((0, 1, 3, -1, 2**40, None))!r}", []
        flips = rng.randint(1, 3)
        offsets = [(rng.random() < 0.6, rng.random(), rng.randrange(8)) for _ in range(flips)]
        return f"{post}|{offsets!r}", []

    def base_damage(self, base, rng):
        post, offsets = base.split("|", 1)
        draft = Draft(command="sweep" if post == "resume" else post, args=[], post=post)
        draft.setup.append(Setup("copy", "map.h5", b"damage-map"))
        if offsets.startswith("version "):
            version = ast.literal_eval(offsets[len("version "):])
            draft.setup.append(Setup("version", "map.h5", repr(version).encode()))
            draft.expect, draft.expect_why = (2,), "a map of another format version is refused"
        else:
            draft.setup.append(Setup("flip", "map.h5", offsets.encode()))
        if post == "resume":
            draft.scene = self.damage_scene
            draft.args = ["sweep", SCENE, "-o", "map.h5", "--resume", "-q", "-f", "json"]
            draft.json = True
        draft.notes.append(f"damage: {post} after {offsets if offsets.startswith('version ') else 'flips ' + offsets}")
        return draft


def materialise_notes(case):
    return "; ".join(case.draft.notes)


def clone(draft):
    return copy.deepcopy(draft)
