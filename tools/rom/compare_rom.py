"""Compare the arrays of two squeal .rom files (docs/rom-format.md): for each array both hold,
the largest entry of the difference over the largest entry of the first, and whether the bytes
are the same.

    python3 tools/rom/compare_rom.py before.rom after.rom
"""
import sys
import numpy as np
from read_rom import read_rom

def main(a_path, b_path):
    _, a = read_rom(a_path)
    _, b = read_rom(b_path)
    worst = 0.0
    for name in sorted(set(a) & set(b)):
        x, y = a[name], b[name]
        if x.shape != y.shape:
            print(f"{name}: shapes differ {x.shape} / {y.shape}")
            worst = float("inf")
            continue
        same = x.tobytes() == y.tobytes()
        if x.dtype.kind == "f" and x.size:
            size = np.abs(x).max()
            rel = np.abs(x - y).max() / size if size > 0 else 0.0
            worst = max(worst, rel)
            print(f"{name}: {x.shape}, max|diff|/max|a| {rel:.2e}{' (same bits)' if same else ''}")
        else:
            print(f"{name}: {x.shape}, {'same' if same else 'DIFFERENT'}")
    for name in sorted(set(a) ^ set(b)):
        print(f"{name}: in one file only")
    print(f"worst relative difference {worst:.2e}")

if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
