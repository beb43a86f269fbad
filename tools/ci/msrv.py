#!/usr/bin/env python3
"""The workspace's minimum supported Rust version (rust-version in Cargo.toml), checked
without a second toolchain (CI has none):

1. every dependency in the build graph declares a rust-version no newer than ours;
2. the installed toolchain is at least that version;
3. the language features the code uses are stable at that version: let chains (`if let ...
   && let ...`, Rust 1.88 in the 2024 edition) are the newest we use, so the floor is 1.88;
   std APIs newer than the MSRV are caught by clippy's `incompatible_msrv` lint, which the
   `-D warnings` clippy run of .ci/run enforces against the declared rust-version.
"""
import json, re, subprocess, sys

def version(s):
    parts = [int(p) for p in re.findall(r"\d+", s)[:3]]
    return tuple(parts + [0] * (3 - len(parts)))

meta = json.loads(subprocess.check_output(["cargo", "metadata", "--format-version", "1", "--locked"]))
ws = set(meta["workspace_members"])
ours = {p["rust_version"] for p in meta["packages"] if p["id"] in ws}
if len(ours) != 1 or None in ours:
    sys.exit(f"msrv: the workspace members must share one rust-version (found {sorted(map(str, ours))})")
msrv = ours.pop()
LANGUAGE_FLOOR = "1.88"  # let chains
bad = []
if version(msrv) < version(LANGUAGE_FLOOR):
    bad.append(f"rust-version {msrv} is below {LANGUAGE_FLOOR}, where let chains (used in the code) became stable")
for p in meta["packages"]:
    rv = p.get("rust_version")
    if p["id"] not in ws and rv and version(rv) > version(msrv):
        bad.append(f"{p['name']} {p['version']} needs Rust {rv}")
rustc = subprocess.check_output(["rustc", "--version"], text=True)
if version(rustc.split()[1]) < version(msrv):
    bad.append(f"the installed {rustc.strip()} is older than the MSRV {msrv}")
if bad:
    sys.exit("msrv: " + "; ".join(bad))
print(f"msrv: rust-version {msrv}; no dependency needs a newer Rust; {rustc.strip()} installed")
