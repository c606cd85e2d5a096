"""The overhead of the Python package on a sweep (issue 55): a 20,000-point Hertz sweep through
`impact sweep --format json` (the command line, its output parsed as a script would) and through
`impactcheck.sweep_rows` / `impactcheck.sweep` (a DataFrame), median of 5 runs each, in one run.
Prints a Markdown table for reports/performance.md."""

import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import impactcheck as ic

ROOT = Path(__file__).resolve().parents[1]  # benches/ -> the repository
SCENE = str(ROOT / "scenes" / "hertz.toml")
VARY = "impactor.v0=0.1:10:20000"


def timed(f, repeats=5):
    ts = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        f()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts)


def cli():
    out = subprocess.run(
        [str(ROOT / "target/release/impact"), "sweep", SCENE, "--vary", VARY, "--format", "json", "--quiet"],
        capture_output=True, text=True, check=True,
    ).stdout
    return json.loads(out)["runs"]


def main():
    base = timed(cli)
    rows = timed(lambda: ic.sweep_rows(SCENE, VARY))
    frame = timed(lambda: ic.sweep(SCENE, VARY))
    print("| path (20,000 Hertz impacts, all cores) | median of 5 | against the command line |")
    print("|---|---|---|")
    print(f"| `impact sweep --format json`, parsed by `json.loads` | {base:.3f} s | 1 |")
    print(f"| `impactcheck.sweep_rows` (dicts) | {rows:.3f} s | {rows / base:.3f} |")
    print(f"| `impactcheck.sweep` (a pandas DataFrame) | {frame:.3f} s | {frame / base:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
