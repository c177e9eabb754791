#!/usr/bin/env python3
"""Whether two result folders hold the same result up to float rounding: labels.bin (labels.txt in
older folders) byte for byte, and in surfaces.json, planes.json and coverage.json (and the records
of surfaces.ply and coverage.ply) the same structure, every string and integer equal (but
result_id, a hash of the exact bytes) and every real
number within a relative tolerance (of the larger magnitude, floored at 1e-3).
Used where bytes cannot match: builds for another CPU architecture (scripts/check-aarch64.sh).
Usage: same-result.py A B [--tolerance 1e-3]"""
import argparse
import json
import struct
import sys
from pathlib import Path

PLY_TYPES = {"float": "f", "double": "d", "uint": "I", "int": "i", "uchar": "B"}


def ply_rows(path):
    """The vertices of a binary little-endian PLY with one element (surfaces.ply, coverage.ply),
    as lists."""
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    fmt = "<" + "".join(PLY_TYPES[line.split()[1]] for line in data[:end].decode().splitlines()
                        if line.startswith("property "))
    return [list(row) for row in struct.iter_unpack(fmt, data[end:])]


def differences(a, b, path, out):
    if isinstance(a, dict) and isinstance(b, dict):
        if a.keys() != b.keys():
            out.append((float("inf"), f"{path}: keys differ"))
            return
        for k in a:
            # result_id hashes the exact bytes of the result, so it differs wherever the numbers
            # differ by rounding; the numbers themselves are compared below.
            if k == "result_id":
                continue
            differences(a[k], b[k], f"{path}.{k}", out)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append((float("inf"), f"{path}: {len(a)} vs {len(b)} entries"))
            return
        for i, (x, y) in enumerate(zip(a, b)):
            differences(x, y, f"{path}[{i}]", out)
    elif isinstance(a, float) or isinstance(b, float):
        if isinstance(a, (int, float)) and isinstance(b, (int, float)):
            rel = abs(a - b) / max(abs(a), abs(b), 1e-3)
            if rel > 0:
                out.append((rel, f"{path}: {a!r} vs {b!r}"))
        else:
            out.append((float("inf"), f"{path}: {a!r} vs {b!r}"))
    elif a != b:
        out.append((float("inf"), f"{path}: {a!r} vs {b!r}"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a", type=Path)
    ap.add_argument("b", type=Path)
    ap.add_argument("--tolerance", type=float, default=1e-3)
    args = ap.parse_args()
    ok = True
    labels = "labels.bin" if (args.a / "labels.bin").exists() else "labels.txt"  # older folders
    if (args.a / labels).read_bytes() != (args.b / labels).read_bytes():
        print(f"same-result: {labels} differs", file=sys.stderr)
        ok = False
    for name in (
            "surfaces.json", "surfaces.ply", "planes.json", "coverage.json", "coverage.ply"):
        out = []
        if name.endswith(".ply"):
            if not (args.a / name).exists() and not (args.b / name).exists():
                continue  # older folders: surfaces and goals inline in the JSON
            differences(ply_rows(args.a / name), ply_rows(args.b / name), name, out)
        else:
            differences(json.loads((args.a / name).read_text()),
                        json.loads((args.b / name).read_text()), name, out)
        worst = max(out, default=(0.0, ""))
        print(f"same-result: {name}: {len(out)} numbers differ, largest relative difference "
              f"{worst[0]:.2g}{' (' + worst[1] + ')' if out else ''}", file=sys.stderr)
        ok = ok and worst[0] <= args.tolerance
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
