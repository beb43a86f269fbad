"""Read a squeal reduced-model file (.rom) with numpy alone (docs/rom-format.md).

    python3 tools/rom/read_rom.py brake.rom     # summary and the lowest frequencies
"""
import json, struct, sys
import numpy as np

DTYPES = {"F64": "<f8", "U64": "<u8", "U8": "u1"}

def read_rom(path):
    """Returns (header, arrays): the squeal header (a dict) and {name: numpy array}."""
    with open(path, "rb") as f:
        (n,) = struct.unpack("<Q", f.read(8))      # length of the JSON table, u64 LE
        table = json.loads(f.read(n))               # array table and __metadata__
        data = f.read()                             # the arrays' bytes
    header = json.loads(table.pop("__metadata__")["squeal"])
    arrays = {}
    for name, t in table.items():
        start, end = t["data_offsets"]              # byte range in `data`
        arrays[name] = np.frombuffer(data[start:end], DTYPES[t["dtype"]]).reshape(t["shape"])
    return header, arrays

def frequencies_hz(K, M):
    """Natural frequencies of K x = w^2 M x (M positive definite), ascending."""
    L = np.linalg.cholesky(M)
    A = np.linalg.solve(L, np.linalg.solve(L, K).T)  # L^-1 K L^-T
    w2 = np.linalg.eigvalsh((A + A.T) / 2)
    return np.sqrt(np.clip(w2, 0, None)) / (2 * np.pi)

if __name__ == "__main__":
    header, arrays = read_rom(sys.argv[1] if len(sys.argv) > 1 else "brake.rom")
    print(f"{header['format']} version {header['version']}, made by {header['tool_version']}")
    for part in header["parts"]:
        p = part["name"]
        K, M = arrays[p + ".K"], arrays[p + ".M"]
        basis = arrays.get(p + ".basis")
        print(f"{p}: {K.shape[0]} reduced dofs, mesh {part['mesh']['path']} "
              f"(sha256 {part['mesh']['sha256'][:12]}...), interface {part['interface']}, "
              f"basis {'none' if basis is None else basis.shape}")
        print(f"  fixed-interface (Hz): {np.round(part['fixed_interface_hz'][:5], 2)}")
        print(f"  free boundary   (Hz): {np.round(frequencies_hz(K, M)[:5], 2)}")
        if basis is not None:
            # Expand the first fixed-interface mode onto the mesh: one row per free dof.
            q = np.zeros(K.shape[0])
            q[[i for i, d in enumerate(part["dofs"]) if d["kind"] == "mode"][0]] = 1.0
            u = basis @ q
            node, direction = arrays[p + ".dof_node"], arrays[p + ".dof_dir"]
            k = np.argmax(np.abs(u))
            print(f"  mode 1 on the mesh: largest motion {u[k]:.3e} at node {node[k]}, "
                  f"direction {'xyz'[direction[k]]}")
