"""The unit audit at the size of a real paper (issue 65): a generated paper of 1,000 relations
with five planted unit errors, audited by `verify audit` and `verify audit --power`, each timed
(median of REPEATS runs, wall clock, one process at a time).

The paper: 100 blocks of ten relations on a body k, with the length x_k, time t_k and mass m_k
declared in the units file and every other unit inferred (v = x/t, a = v/t, F = m a, E = F x,
P = E/t, p = m v, F t = p, E = p v, P = F v, W = m v^2/2); in five blocks `F t = p` is printed
`F = p t` (a unit error, kg m s^-2 against kg m). The audit must call exactly those five
inconsistent (checked here: a run that misses one is no time).

    python3 benches/audit_size.py [path/to/verify]    # default target/release/verify
"""

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

BLOCKS = 100
PLANTED = {7, 23, 51, 68, 94}
REPEATS = 3


def paper():
    """The LaTeX of the paper and its units file."""
    rows = []
    units = ["[symbols]"]
    for k in range(BLOCKS):
        s = f"_{{{k}}}"
        units += [f'x{k} = "m"', f't{k} = "s"', f'm{k} = "kg"']
        ft = f"F{s} = p{s} t{s}" if k in PLANTED else f"F{s} t{s} = p{s}"
        for rel in [
            f"v{s} = \\frac{{x{s}}}{{t{s}}}",
            f"a{s} = \\frac{{v{s}}}{{t{s}}}",
            f"F{s} = m{s} a{s}",
            f"E{s} = F{s} x{s}",
            f"P{s} = \\frac{{E{s}}}{{t{s}}}",
            f"p{s} = m{s} v{s}",
            ft,
            f"E{s} = p{s} v{s}",
            f"P{s} = F{s} v{s}",
            f"W{s} = \\frac{{1}}{{2}} m{s} v{s}^{{2}}",
        ]:
            rows.append(f"\\begin{{equation}}\n{rel}\n\\end{{equation}}\n")
    return "".join(rows), "\n".join(units) + "\n"


def timed(cmd):
    t0 = time.perf_counter()
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    return time.perf_counter() - t0, json.loads(out)


def main():
    verify = sys.argv[1] if len(sys.argv) > 1 else "target/release/verify"
    tex, units = paper()
    with tempfile.TemporaryDirectory() as d:
        p, u = os.path.join(d, "paper.tex"), os.path.join(d, "units.toml")
        open(p, "w").write(tex)
        open(u, "w").write(units)
        base = [verify, "audit", p, "--units", u, "--format", "json"]
        for name, cmd in [("verify audit", base), ("verify audit --power", base + ["--power"])]:
            times = []
            for _ in range(REPEATS):
                t, j = timed(cmd)
                bad = [r for r in j["relations"] if r["status"] == "inconsistent"]
                assert len(j["relations"]) == 10 * BLOCKS, len(j["relations"])
                assert len(bad) == len(PLANTED), [r["latex"] for r in bad]
                times.append(t)
            extra = ""
            if "power" in j:
                pw = j["power"]
                extra = f"; power {pw['caught']} of {pw['misprints']} misprints of {pw['measured']} of {pw['consistent']} consistent relations"
            print(f"| {name} | {10 * BLOCKS} relations, {len(PLANTED)} planted | {statistics.median(times):.2f} s | {extra.lstrip('; ')} |")


if __name__ == "__main__":
    main()
