"""The Python functions against their command-line twins on the same inputs (issue 55): the same
numbers to the bit (the JSON both print, parsed), and bad input raising ImpactcheckError with the
interpreter alive. The binaries are the ones the cargo test that runs these built (tests/python.rs
names their folder in IMPACTCHECK_BIN), else target/release."""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

import impactcheck as ic

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("IMPACTCHECK_BIN", ROOT / "target" / "release"))


def cli(name, *args):
    out = subprocess.run(
        [str(BIN / name), *args], cwd=ROOT, capture_output=True, text=True, check=True
    )
    return out.stdout


def test_describe_is_the_command_lines():
    assert ic.describe("hertz") == json.loads(cli("impact", "describe", "hertz", "--format", "json"))
    names = [d["name"] for d in ic.describe()]
    assert "hertz" in names and "ode" in names


def test_run_is_the_command_lines_for_a_path_a_text_and_a_dict():
    scene = ROOT / "scenes" / "hertz.toml"
    want = json.loads(cli("impact", "run", str(scene), "--format", "json"))
    assert ic.run(scene) == want
    assert ic.run(str(scene)) == want
    text = scene.read_text()
    assert ic.run(text) == want
    as_dict = {
        "model": "hertz",
        "impactor": {"mass": 1.0, "v0": 1.0},
        "contact": {"k": 1.0, "damping": 0.0},
        "solve": {"rtol": 1e-9, "atol": 1e-9, "method": "dop853", "t_end": "contact-end"},
    }
    assert ic.run(as_dict) == want


def test_a_sweep_of_20000_hertz_impacts_is_the_command_lines_to_the_bit():
    scene = str(ROOT / "scenes" / "hertz.toml")
    vary = "impactor.v0=0.1:10:20000"
    want = json.loads(cli("impact", "sweep", scene, "--vary", vary, "--format", "json", "--quiet"))["runs"]
    got = ic.sweep_rows(scene, vary)
    assert len(got) == 20000
    assert got == want  # floats parsed from the same text: equal to the bit
    frame = ic.sweep(scene, {"impactor.v0": (0.1, 10, 20000)})
    assert list(frame.index[:3]) == [0, 1, 2]
    # the CSV's numbers read back round-trip: the same floats as the JSON's
    assert frame["restitution"].tolist() == [r["result"]["restitution"] for r in want]
    assert frame["impactor.v0"].tolist() == [r["value"] for r in want]
    csv = cli("impact", "sweep", scene, "--vary", vary, "--format", "csv", "--quiet")
    assert csv.splitlines()[0].split(",") == [*frame.columns, "index"]


def test_series_is_the_command_lines_exact_terms():
    want = json.loads(
        cli("impact", "series", "--order", "2", "--at", "alpha=-3,gamma=5/2,v0=1,a8=7,a9=1/3", "--format", "json")
    )
    assert ic.series(2, at={"alpha": "-3", "gamma": "5/2", "v0": 1, "a8": 7, "a9": "1/3"}) == want
    assert ic.series(1, viscous="zz") == json.loads(
        cli("impact", "series", "--order", "1", "--viscous", "zz", "--format", "json")
    )
    with pytest.raises(ic.ImpactcheckError, match="too large"):
        ic.series(9)


def test_audit_and_init_of_the_test_paper_are_the_command_lines():
    paper = "tests/papers/spring_dashpot/paper.tex"
    units = "tests/papers/spring_dashpot/claims.toml"
    want = json.loads(cli("verify", "audit", paper, "--units", units, "--format", "json"))
    got = ic.audit(ROOT / paper, units=ROOT / units)
    assert dict(got) == want
    frame = got.to_frame()
    assert len(frame) == len(want["relations"]) > 0
    assert list(frame["status"]) == [r["status"] for r in want["relations"]]
    # from its words alone
    words = "tests/papers/words/paper.tex"
    assert dict(ic.audit(ROOT / words)) == json.loads(cli("verify", "audit", words, "--format", "json"))
    text = cli("verify", "init", str(ROOT / paper), "--units", str(ROOT / units), "--paper", "sd")
    claims = ic.init(ROOT / paper, "sd", units=ROOT / units)
    assert claims == text
    # its claims and symbols as frames: counted from the text's own tables and lines
    frame = claims.to_frame()
    assert len(frame) == text.count("[[claim]]") > 0
    assert all(i.startswith("sd.") for i in frame["id"])
    symbols = claims.to_frame("symbols")
    assert set(symbols["symbol"]) == {
        line.split(" = ")[0]
        for line in text.split("[symbols]")[1].split("[[claim]]")[0].splitlines()
        if " = " in line
    }
    assert dict(zip(symbols["symbol"], symbols["unit"]))["k"] == "N/m"
    with pytest.raises(ic.ImpactcheckError, match="reading the paper"):
        ic.audit(ROOT / "no" / "paper.tex")


def shelf_rows(frame):
    """The frame of ``audit_many`` as the rows of ``verify audit FOLDER --format json``."""
    return [
        {k: v for k, v in r.items() if not (k == "error" and v is None)}
        for r in frame.reset_index().to_dict("records")
    ]


def test_audit_many_of_the_test_papers_is_the_command_lines_row_by_row(monkeypatch):
    # the folder as the command is given it, from the same place
    monkeypatch.chdir(ROOT)
    want = json.loads(cli("verify", "audit", "tests/papers", "--format", "json"))
    frame = ic.audit_many("tests/papers")
    assert frame.index.name == "paper"
    # the command's keys (its JSON sorts them), `error` a column even where no paper has one
    assert {"paper", *frame.columns} == {*want["papers"][0], "error"}
    assert len(frame) == len(want["papers"]) > 1
    assert shelf_rows(frame) == want["papers"]
    assert frame.attrs["total"] == want["total"]


def test_audit_many_gives_a_paper_it_cannot_read_its_error_as_the_command_does(tmp_path):
    paper = "\\documentclass{article}\n\\begin{document}\n$$E = m c^2$$\n\\end{document}\n"
    for name in ("a.tex", "b/c.tex"):
        (tmp_path / name).parent.mkdir(exist_ok=True)
        (tmp_path / name).write_text(paper)
    units = str(tmp_path / "no-units.toml")
    want = json.loads(cli("verify", "audit", str(tmp_path), "--units", units, "--format", "json"))
    frame = ic.audit_many(tmp_path, units=units)
    assert [r.get("error") for r in want["papers"]] == list(frame["error"])
    assert all(frame["error"]) and (frame["relations"] == 0).all()
    assert shelf_rows(frame) == want["papers"]
    assert frame.attrs["total"] == want["total"]
    (tmp_path / "empty").mkdir()
    with pytest.raises(ic.ImpactcheckError, match="no paper"):
        ic.audit_many(tmp_path / "empty")


def test_verify_gives_the_command_lines_verdicts():
    want = json.loads(cli("verify", "--only", "classics", "--format", "json"))
    got = ic.verify(only="classics")
    assert [c["id"] for c in got["claims"]] == [c["id"] for c in want["claims"]]
    assert [(c["verdict"], c["detail"]) for c in got["claims"]] == [
        (c["verdict"], c["detail"]) for c in want["claims"]
    ]


@pytest.mark.parametrize(
    "call, says",
    [
        (lambda: ic.run("no/such/scene.toml"), "cannot read"),
        (
            lambda: ic.run({"model": "hertz", "impactor": {"mass": "1 kg", "v0": 1.0}, "contact": {"k": 1.0}}),
            "impactor.mass",
        ),
        (lambda: ic.sweep_rows(str(ROOT / "scenes" / "hertz.toml"), {"impactor.v00": (1, 2, 3)}), "v00"),
        (lambda: ic.run({"not": "a scene"}), "model"),
        (lambda: ic.run(42), "a scene is a path"),
        (lambda: ic.verify(claims="no/such/claims.toml"), "cannot read"),
    ],
)
def test_bad_input_raises_naming_it_and_the_interpreter_lives_on(call, says):
    with pytest.raises(ic.ImpactcheckError) as e:
        call()
    assert says in str(e.value)
    # the interpreter goes on: a good call after the bad one
    assert ic.describe("hertz")["name"] == "hertz"


OSCILLATOR = (ROOT / "scenes" / "oscillator_wall.toml").read_text()


@pytest.mark.parametrize(
    "text, says",
    [
        # a bad unit: named, with the nearest known one
        (OSCILLATOR.replace('w = "Hz"', 'w = "Hzz"'), ["units.w", "Hzz", "Hz"]),
        # a TOML slip: its line and a caret, the scene named as given
        (OSCILLATOR.replace("x0 = 0.01", "x0 = = 0.01"), ["the scene text", "line", "^"]),
        # a key that is not the model's
        (OSCILLATOR.replace("[solve]", "[solve]\nrtoll = 1e-9"), ["rtoll"]),
    ],
)
def test_a_bad_scene_text_raises_the_command_lines_message(text, says, tmp_path):
    with pytest.raises(ic.ImpactcheckError) as e:
        ic.run(text)
    message = str(e.value)
    for word in says:
        assert word in message, (word, message)
    assert "impactcheck-" not in message  # not the temporary file's name
    # the same message as `impact run` on the same text in a file, the file's name aside
    scene = tmp_path / "scene.toml"
    scene.write_text(text)
    out = subprocess.run(
        [str(BIN / "impact"), "run", str(scene)], cwd=ROOT, capture_output=True, text=True
    )
    assert out.returncode != 0
    cli_message = out.stderr.strip().removeprefix("impact: error: ")
    assert cli_message.replace(str(scene), "the scene text") == message


def _bits(a):
    import numpy as np

    return np.asarray(a, dtype=np.float64).view(np.uint64).tolist()


@pytest.mark.parametrize(
    "scene",
    [
        "hertz.toml",
        "oscillator_wall.toml",
        "cone_plate.toml",
        "hertz_ode.toml",
        "pendulum_on_wall.toml",
        "rigid_impact.toml",
    ],
)
def test_run_arrays_are_the_command_lines_trace_to_the_bit(scene, tmp_path):
    """`run` against `impact run --format json --trace FILE`: the outcome equal, every step and
    event equal to the bit, in the JSON trace and in the CSV one (read back round-trip)."""
    import pandas as pd

    path = str(ROOT / "scenes" / scene)
    r = ic.run(path)
    assert dict(r) == json.loads(cli("impact", "run", path, "--format", "json"))
    traced = json.loads(
        cli("impact", "run", path, "--format", "json", "--trace", str(tmp_path / "t.json"))
    )
    assert dict(r) == traced  # the traced run's outcome is the untraced one's
    tr = json.loads((tmp_path / "t.json").read_text())
    var = tr["variable"]
    assert r.traced and r.variable == f"{var['name']} ({var['unit']})" and len(r.time) > 10
    assert _bits(r.time) == _bits(tr["variable"]["values"])
    for col in tr["states"]:
        heading = col["name"] if col["unit"] == "1" else f"{col['name']} ({col['unit']})"
        assert _bits(r.states[heading]) == _bits(col["values"])
    assert list(r.events["event"]) == [e["name"] for e in tr["events"]]
    assert _bits(r.events[r.variable]) == _bits([e["at"] for e in tr["events"]])
    cli("impact", "run", path, "--trace", str(tmp_path / "t.csv"))
    csv = pd.read_csv(tmp_path / "t.csv", keep_default_na=False)
    steps = csv[csv["event"] == ""]
    assert _bits(steps[r.variable]) == _bits(r.time)
    frame = r.to_frame()
    for h in r.states:
        assert _bits(steps[h]) == _bits(frame[h])
    assert list(csv[csv["event"] != ""]["event"]) == list(r.events["event"])


def test_a_hertz_trace_conserves_energy_and_peaks_where_hertz_says():
    """Independent of the command line: the undamped Hertz impact (m = k = v0 = 1) keeps
    m v^2/2 + (2/5) k z^(5/2) = m v0^2/2 along every recorded step, and its "max indentation"
    event sits at Hertz's closed form z_max = (5 m v0^2 / (4 k))^(2/5) with v = 0."""
    r = ic.run(ROOT / "scenes" / "hertz.toml")
    assert r.units == {"t": "s", "z": "m", "dz/dt": "m/s"}
    z, v = r.states["z (m)"], r.states["dz/dt (m/s)"]
    energy = 0.5 * v**2 + 0.4 * abs(z) ** 2.5 * (z > 0)
    assert abs(energy - 0.5).max() < 1e-7
    (i,) = [k for k, name in enumerate(r.events["event"]) if name == "max indentation"]
    assert math.isclose(r.events["z (m)"][i], 1.25**0.4, rel_tol=1e-8)
    assert abs(r.events["dz/dt (m/s)"][i]) < 1e-8
    assert r.events["event"][-1] == "contact end"
    assert math.isclose(r.events["t (s)"][-1], r["contact"]["duration"], rel_tol=0, abs_tol=0)


def test_a_model_without_a_path_has_empty_arrays_and_the_cli_says_why(tmp_path):
    path = str(ROOT / "scenes" / "disk_friction.toml")
    r = ic.run(path)
    assert not r.traced and len(r.time) == 0 and r.states == {}
    assert "integrates no path" in r.no_path
    assert dict(r) == json.loads(cli("impact", "run", path, "--format", "json"))
    out = subprocess.run(
        [str(BIN / "impact"), "run", path, "--trace", str(tmp_path / "t.json")],
        cwd=ROOT, capture_output=True, text=True,
    )
    assert out.returncode == 2 and "integrates no path" in out.stderr
    assert not (tmp_path / "t.json").exists()


def test_a_panic_becomes_impactcheck_error_and_the_interpreter_lives():
    from impactcheck import _impactcheck

    with pytest.raises(ic.ImpactcheckError, match="internal error.*boom"):
        _impactcheck._panic_for_test("boom")
    # Exception, not BaseException: a notebook's `except Exception` catches it
    assert issubclass(ic.ImpactcheckError, Exception)
    assert ic.run(ROOT / "scenes" / "hertz.toml")["model"] == "hertz"


def test_the_dask_submodule_is_there_after_importing_the_package_alone():
    # a fresh interpreter, so that no other test has imported impactcheck.dask first
    # nor is the submodule, or Dask, imported until it is used
    code = (
        "import sys, impactcheck as ic; "
        "print([m for m in ('impactcheck.dask', 'dask', 'distributed') if m in sys.modules]); "
        "print(ic.dask.sweep.__name__, ic.dask.audit_many.__name__); ic.nothing"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.splitlines() == ["[]", "sweep audit_many"], out.stderr
    assert "AttributeError: module 'impactcheck' has no attribute 'nothing'" in out.stderr
