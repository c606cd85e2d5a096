"""The Python functions against their command-line twins on the same inputs (issue 55): the same
numbers to the bit (the JSON both print, parsed), and bad input raising ImpactcheckError with the
interpreter alive. The binaries are the ones `cargo test --release` built (target/release)."""

import json
import math
import os
import subprocess
from pathlib import Path

import pytest

import impactcheck as ic

ROOT = Path(__file__).resolve().parents[2]
BIN = ROOT / "target" / "release"


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
    assert ic.init(ROOT / paper, "sd", units=ROOT / units) == cli(
        "verify", "init", str(ROOT / paper), "--units", str(ROOT / units), "--paper", "sd"
    )
    with pytest.raises(ic.ImpactcheckError, match="reading the paper"):
        ic.audit(ROOT / "no" / "paper.tex")


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
