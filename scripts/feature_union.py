"""Check that the Python module's build and the tests' build ask for the same features of
every dependency they share, so that Cargo compiles each of them once (a shared crate with
two feature sets is compiled twice, and so is everything above it: faer, nalgebra, dcfm).

The module is built by maturin for reference/dcfm-py alone; the tests by
`cargo test --workspace` (the default members with their dev-dependencies). Where the two
differ, the missing features go into solver/feature-union/Cargo.toml; this script names
them. Exit status 0 when the builds agree, 1 otherwise.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LINE = re.compile(r"^(\S+) (v\S+)(?: \([^)]*\))?(?: \(proc-macro\))? \[(.*)\](?: \(\*\))?$")


def features(args: list[str]) -> dict[tuple[str, str], frozenset[str]]:
    """Package (name, version) -> its enabled features, from `cargo tree`."""
    cmd = ["cargo", "tree", "--locked", "--prefix", "none", "-f", "{p} [{f}]", *args]
    out = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"feature_union: `{' '.join(cmd)}` failed:\n{out.stderr}")
    found: dict[tuple[str, str], set[str]] = {}
    for line in out.stdout.splitlines():
        m = LINE.match(line.strip())
        if m is None:
            continue
        found.setdefault((m[1], m[2]), set()).update(f for f in m[3].split(",") if f)
    return {k: frozenset(v) for k, v in found.items()}


def main() -> int:
    module = features(["-p", "dcfm-py", "-e", "normal,build"])
    tests = features(["--workspace", "--exclude", "dcfm-py", "-e", "normal,build,dev"])
    shared = sorted(set(module) & set(tests))
    differ = [(k, module[k], tests[k]) for k in shared if module[k] != tests[k]]
    for (name, version), m, t in differ:
        print(
            f"feature_union: {name} {version}: only the module's build has {sorted(m - t)}, "
            f"only the tests' build has {sorted(t - m)}: add the union to "
            "solver/feature-union/Cargo.toml"
        )
    if differ:
        return 1
    print(f"feature_union: the module's and the tests' builds agree on all {len(shared)} shared crates")
    return 0


if __name__ == "__main__":
    sys.exit(main())
