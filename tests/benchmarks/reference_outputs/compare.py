#!/usr/bin/python3
"""compare.py A B: the reference outputs of two binaries, dataset by dataset.

Text outputs (stdout, .csv) are compared after masking timings; JSON outputs are compared
as values with timing keys dropped; HDF5 files dataset by dataset and attribute by attribute,
timing datasets and attributes skipped. Prints one line per difference and a summary."""
import json, os, re, sys
import numpy as np
import h5py

TIMING = re.compile(r'(wall|_per_s$|checkpoint.*_s$|^elapsed|_seconds$|^time_s$|^seconds$|cpu_s|start_time|finished|created|date)', re.I)
TIME_TEXT = re.compile(r'\d+(\.\d+)?(e[-+]?\d+)?\s*(s|ms|us)\b|[0-9.]+(e[-+]?\d+)? ?[a-z ]+/s|\d{4}-\d\d-\d\dT[0-9:.]+Z?')

def mask_wall_columns(t):
    """Tables whose last column is "wall s": that column masked, header to the blank line."""
    out, in_table = [], False
    for line in t.split('\n'):
        if not line.strip():
            in_table = False
        elif 'wall s' in line:
            in_table = True
        elif in_table:
            line = re.sub(r'\s\S+$', ' <T>', line)
        out.append(line)
    return '\n'.join(out)

def mask_text(t):
    t = mask_wall_columns(t)
    t = re.sub(r'(?m)^(\s*wall time\b).*$', r'\1 <T>', t)
    return TIME_TEXT.sub('<T>', t)

def mask_csv(t):
    """A CSV without its timing columns (named *wall*, *_s, *time*)."""
    import csv, io
    rows = list(csv.reader(io.StringIO(t)))
    if not rows:
        return t
    keep = [i for i, h in enumerate(rows[0]) if not TIMING.search(h) and not re.search(r'time|_s$', h)]
    return '\n'.join(','.join(r[i] for i in keep if i < len(r)) for r in rows)

def strip_json(x):
    if isinstance(x, dict):
        return {k: strip_json(v) for k, v in x.items() if not TIMING.search(k)}
    if isinstance(x, list):
        return [strip_json(v) for v in x]
    return x

def diff_json(a, b, path, out):
    if type(a) != type(b):
        out.append(f'{path}: type {type(a).__name__} vs {type(b).__name__}')
    elif isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                out.append(f'{path}/{k}: only in {"B" if k not in a else "A"}')
            else:
                diff_json(a[k], b[k], f'{path}/{k}', out)
    elif isinstance(a, list):
        if len(a) != len(b):
            out.append(f'{path}: length {len(a)} vs {len(b)}')
        for i, (u, v) in enumerate(zip(a, b)):
            diff_json(u, v, f'{path}[{i}]', out)
    elif a != b and not (isinstance(a, float) and a != a and b != b):
        out.append(f'{path}: {a!r} vs {b!r}')

def deref(f, x):
    """Object references (dimension scales) as the names of what they point to."""
    if isinstance(x, h5py.Reference):
        return f[x].name if x else None
    if isinstance(x, np.ndarray) and x.dtype.kind == 'O':
        return [deref(f, y) for y in x.tolist()]
    if isinstance(x, np.ndarray) and x.dtype.names:
        return [tuple(deref(f, y) for y in row) for row in x.tolist()]
    if isinstance(x, (list, tuple)):
        return [deref(f, y) for y in x]
    return x

def attr_eq(u, v):
    try:
        return np.array_equal(np.asarray(u), np.asarray(v), equal_nan=True)
    except TypeError:
        return np.array_equal(np.asarray(u), np.asarray(v))

def diff_h5(fa, fb, out):
    def walk(ga, gb, path):
        for k in sorted(set(ga.attrs) | set(gb.attrs)):
            if TIMING.search(k) or k in ('checksum', 'attribute_checksum', 'attributes_sha256'):
                continue
            if k not in ga.attrs or k not in gb.attrs:
                out.append(f'{path}@{k}: only in {"B" if k not in ga.attrs else "A"}')
            elif k in ('DIMENSION_LIST', 'REFERENCE_LIST'):
                if deref(ga.file, ga.attrs[k]) != deref(gb.file, gb.attrs[k]):
                    out.append(f'{path}@{k}: dimension scales differ')
            elif not attr_eq(ga.attrs[k], gb.attrs[k]):
                out.append(f'{path}@{k}: {str(ga.attrs[k])[:80]} vs {str(gb.attrs[k])[:80]}')
        if not isinstance(ga, h5py.Group):
            return
        for k in sorted(set(ga) | set(gb)):
            p = f'{path}/{k}'
            if TIMING.search(k):
                continue
            if k not in ga or k not in gb:
                out.append(f'{p}: only in {"B" if k not in ga else "A"}')
                continue
            a, b = ga[k], gb[k]
            if isinstance(a, h5py.Dataset):
                x, y = a[()], b[()]
                if a.dtype != b.dtype or a.shape != b.shape:
                    out.append(f'{p}: dtype/shape {a.dtype}{a.shape} vs {b.dtype}{b.shape}')
                elif a.dtype.kind in 'fc':
                    if not np.array_equal(x, y, equal_nan=True):
                        out.append(f'{p}: values differ ({np.sum(~((x == y) | (np.isnan(x) & np.isnan(y))))} elements)')
                elif not np.array_equal(x, y):
                    out.append(f'{p}: values differ')
            walk(a, b, p)
    walk(fa, fb, '')

def main(A, B):
    total = 0
    names = sorted(set(os.listdir(A)) | set(os.listdir(B)))
    for n in names:
        pa, pb = os.path.join(A, n), os.path.join(B, n)
        out = []
        if not os.path.exists(pa) or not os.path.exists(pb):
            out.append('only in ' + ('B' if not os.path.exists(pa) else 'A'))
        elif n.endswith('.h5'):
            with h5py.File(pa, 'r') as fa, h5py.File(pb, 'r') as fb:
                diff_h5(fa, fb, out)
        elif n.endswith('.err'):
            continue
        elif n.endswith('.csv'):
            if mask_csv(open(pa).read()) != mask_csv(open(pb).read()):
                out.append('CSV values differ (timing columns aside)')
        else:
            ta, tb = open(pa).read(), open(pb).read()
            try:
                ja, jb = json.loads(ta), json.loads(tb)
                diff_json(strip_json(ja), strip_json(jb), '', out)
            except ValueError:
                if mask_text(ta) != mask_text(tb):
                    la, lb = mask_text(ta).splitlines(), mask_text(tb).splitlines()
                    for i, (u, v) in enumerate(zip(la, lb)):
                        if u != v:
                            out.append(f'line {i+1}: {u[:100]!r} vs {v[:100]!r}')
                            break
                    if len(la) != len(lb):
                        out.append(f'{len(la)} vs {len(lb)} lines')
        status = 'identical' if not out else f'{len(out)} difference(s)'
        print(f'{n:28s} {status}')
        for o in out[:8]:
            print('    ' + o)
        total += bool(out)
    print(f'{len(names)} outputs, {total} differ')
    return 1 if total else 0

if __name__ == '__main__':
    sys.exit(main(sys.argv[1], sys.argv[2]))
