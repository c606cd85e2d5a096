"""The overhead of the Python package on a sweep (issue 55): a 20,000-point Hertz sweep through
`impact sweep --format json` (the command line, its output parsed as a script would) and through
`impactcheck.sweep_rows` / `impactcheck.sweep` (a DataFrame), median of 5 runs each; and one run
with its path (`impact run --trace FILE.json`, both files parsed, against `impactcheck.run`, which
gives NumPy arrays), median of 21. Prints Markdown tables for reports/performance.md."""

import json
import statistics
import subprocess
import sys
import tempfile
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


PATH_SCENE = str(ROOT / "scenes" / "oscillator_wall.toml")


def cli_run(trace):
    out = subprocess.run(
        [str(ROOT / "target/release/impact"), "run", PATH_SCENE, "--format", "json", "--trace", trace],
        capture_output=True, text=True, check=True,
    ).stdout
    return json.loads(out), json.loads(Path(trace).read_text())


def main():
    base = timed(cli)
    rows = timed(lambda: ic.sweep_rows(SCENE, VARY))
    frame = timed(lambda: ic.sweep(SCENE, VARY))
    print("| path (20,000 Hertz impacts, all cores) | median of 5 | against the command line |")
    print("|---|---|---|")
    print(f"| `impact sweep --format json`, parsed by `json.loads` | {base:.3f} s | 1 |")
    print(f"| `impactcheck.sweep_rows` (dicts) | {rows:.3f} s | {rows / base:.3f} |")
    print(f"| `impactcheck.sweep` (a pandas DataFrame) | {frame:.3f} s | {frame / base:.3f} |")
    with tempfile.TemporaryDirectory() as d:
        trace = str(Path(d) / "t.json")
        one = timed(lambda: cli_run(trace), repeats=21)
    py = timed(lambda: ic.run(PATH_SCENE), repeats=21)
    steps = len(ic.run(PATH_SCENE).time)
    print()
    print(f"| one run with its path (`scenes/oscillator_wall.toml`, {steps} steps) | median of 21 | against the command line |")
    print("|---|---|---|")
    print(f"| `impact run --format json --trace t.json`, both parsed by `json.loads` | {one * 1e3:.2f} ms | 1 |")
    print(f"| `impactcheck.run` (a dict and NumPy arrays) | {py * 1e3:.2f} ms | {py / one:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
