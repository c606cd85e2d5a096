"""impactcheck from Python (issue 55): the tool's jobs as functions.

Each function calls the same library code as its command-line twin (``impact run``, ``impact
sweep``, ``impact describe``, ``verify --format json``) and returns what that command prints, as
Python objects: dicts for outcomes and verdicts, NumPy arrays named with their units for a run's
path (``Run``: the twin of ``impact run --trace``), a ``pandas.DataFrame`` for a sweep (one row per
point, the outcome's numbers as columns), frames of an audit's relations and of a claims file's
claims (``Audit``, ``Claims``), and a frame of every paper under a folder audited
(``audit_many``: one row per paper, the twin of ``verify audit FOLDER``; on a Dask cluster,
``impactcheck.dask.audit_many``). Bad input raises ``ImpactcheckError`` with the command line's
message (the file, the line, the key); so does a panic of the library, which would be a bug.

A scene is a path, a TOML text or a dict of the same tables (SI units, as in ``scenes/``).
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path
from typing import Any, Mapping, Optional, Sequence, Union

from ._impactcheck import (
    audit_json,
    audit_row_json,
    papers_in,
    init_text,
    ImpactcheckError,
    describe_json,
    run_traced_json,
    series_json,
    sweep_text,
    toml_of_json,
    verify_json,
)

__all__ = [
    "Audit",
    "Claims",
    "ImpactcheckError",
    "Run",
    "audit",
    "audit_many",
    "describe",
    "init",
    "run",
    "series",
    "sweep",
    "sweep_rows",
    "verify",
]

Scene = Union[str, os.PathLike, Mapping[str, Any]]


def __getattr__(name: str) -> Any:
    """``impactcheck.dask`` on first use (PEP 562): ``import impactcheck as ic; ic.dask.sweep(...)``
    works without importing the submodule by name, and Dask is imported only when it is used."""
    if name == "dask":
        import importlib

        return importlib.import_module(".dask", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


class _ScenePath:
    """The scene as a file: the path given, or a temporary file holding a TOML text or a dict."""

    def __init__(self, scene: Scene):
        self._tmp: Optional[tempfile.TemporaryDirectory] = None
        self._what = "the scene text"
        if isinstance(scene, Mapping):
            text = toml_of_json(json.dumps(scene))
            self._what = "the scene dict"
            self.path = self._write(text)
        elif isinstance(scene, os.PathLike) or (
            isinstance(scene, str) and "\n" not in scene and "=" not in scene
        ):
            self.path = str(scene)
        elif isinstance(scene, str):
            self.path = self._write(scene)
        else:
            raise ImpactcheckError(
                f"a scene is a path, a TOML text or a dict, not {type(scene).__name__}"
            )

    def _write(self, text: str) -> str:
        self._tmp = tempfile.TemporaryDirectory(prefix="impactcheck-")
        p = Path(self._tmp.name) / "scene.toml"
        p.write_text(text, encoding="utf-8")
        return str(p)

    def __enter__(self) -> str:
        return self.path

    def __exit__(self, kind, exc, tb) -> None:
        if self._tmp is not None:
            self._tmp.cleanup()
            # a message names the scene as the user gave it, not the temporary file
            if isinstance(exc, ImpactcheckError) and self.path in str(exc):
                raise ImpactcheckError(str(exc).replace(self.path, self._what)) from None


class Audit(dict):
    """A paper's audit as ``verify audit --format json`` prints it (``relations``, ``symbols``),
    with each list as a ``pandas.DataFrame`` at hand."""

    def to_frame(self, what: str = "relations"):
        """``relations`` (one row per relation: number, status, why, ...) or ``symbols``."""
        import pandas as pd

        return pd.DataFrame(self[what])


def _paths(files) -> list:
    if files is None:
        return []
    if isinstance(files, (str, os.PathLike)):
        return [str(files)]
    return [str(f) for f in files]


def audit(paper, units=None, preamble=None, vocabulary=None) -> Audit:
    """The units of every relation of ``paper`` (its LaTeX, or a text with display math):
    ``verify audit PAPER --format json``. ``units`` is a TOML file of symbols and units (a claims
    file serves); without it the units come from the paper's words."""
    return Audit(
        json.loads(
            audit_json(str(paper), None if units is None else str(units), _paths(preamble), _paths(vocabulary))
        )
    )


# The counts of a row of ``verify audit FOLDER --format json``, after its ``paper``; ``error``,
# which the command writes only for a paper that could not be read, is the last column.
_SHELF_COUNTS = (
    "relations",
    "read",
    "consistent_in_a_unit",
    "consistent_pure",
    "inconsistent",
    "undetermined",
)


def _shelf_frame(rows: list):
    """The rows of ``verify audit FOLDER --format json`` (dicts, in the papers' order) as a frame
    indexed by ``paper``, with the command's ``total`` in ``attrs["total"]``."""
    import pandas as pd

    frame = pd.DataFrame(
        [{**r, "error": r.get("error")} for r in rows],
        columns=["paper", *_SHELF_COUNTS, "error"],
    ).set_index("paper")
    frame.attrs["total"] = {
        "paper": f"all ({len(rows)} papers)",
        **{k: sum(r[k] for r in rows) for k in _SHELF_COUNTS},
    }
    return frame


def audit_many(folder, units=None, preamble=(), vocabulary=()):
    """Every paper under ``folder`` audited (``verify audit FOLDER --format json``), as a
    ``pandas.DataFrame``: one row per paper in the command's order, indexed by ``paper`` (its path
    under the folder), with the command's counts as columns (``relations``, ``read``,
    ``consistent_in_a_unit``, ``consistent_pure``, ``inconsistent``, ``undetermined``) and
    ``error`` (why a paper could not be read, else ``None``). ``frame.attrs["total"]`` is the
    command's ``total`` as a dict. The papers are audited on a thread per core, as the command
    audits them; ``units``, ``preamble`` and ``vocabulary`` apply to every paper."""
    from concurrent.futures import ThreadPoolExecutor

    folder = str(folder)
    options = (None if units is None else str(units), _paths(preamble), _paths(vocabulary))
    papers = papers_in(folder)
    # each audit releases the interpreter, so the threads run at once
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        texts = list(pool.map(lambda p: audit_row_json(folder, p, *options), papers))
    return _shelf_frame([json.loads(t) for t in texts])


class Claims(str):
    """A claims file as ``verify init`` prints it (this string: save it beside the paper), with
    its contents at hand: ``claims`` (one dict per ``[[claim]]``: id, equation, reading, kind,
    ...), ``symbols`` (one dict per symbol: ``symbol``, ``unit``), and ``to_frame()`` /
    ``to_frame("symbols")`` as ``pandas.DataFrame``s."""

    @property
    def _parsed(self) -> dict:
        import tomllib

        return tomllib.loads(str(self))

    @property
    def claims(self) -> list:
        return self._parsed.get("claim", [])

    @property
    def symbols(self) -> list:
        return [{"symbol": k, "unit": v} for k, v in self._parsed.get("symbols", {}).items()]

    def to_frame(self, what: str = "claims"):
        """``claims`` (one row per claim) or ``symbols`` (one row per symbol and its unit)."""
        import pandas as pd

        if what not in ("claims", "symbols"):
            raise ImpactcheckError(f"to_frame({what!r}): 'claims' or 'symbols'")
        return pd.DataFrame(self.claims if what == "claims" else self.symbols)


def init(paper, id: str, units=None, preamble=None, vocabulary=None) -> Claims:
    """The claims file to start from for ``paper``, its claims' ids starting ``id``:
    ``verify init PAPER --paper ID``, as text (save it beside the paper) with its claims and
    symbols as dicts and frames (``Claims``)."""
    return Claims(
        init_text(
            str(paper), id, None if units is None else str(units), _paths(preamble), _paths(vocabulary)
        )
    )


def describe(model: Optional[str] = None) -> Any:
    """Every scene key and outcome of ``model`` (unit, range, meaning): ``impact describe``."""
    return json.loads(describe_json(model))


def _heading(name: str, unit: str) -> str:
    """``z (m)``; a pure number (unit ``1``) by its name alone, as the command line heads it."""
    return name if unit in ("", "1") else f"{name} ({unit})"


def _array(values) -> "numpy.ndarray":
    import numpy as np

    # JSON writes a NaN as null
    return np.array([np.nan if v is None else v for v in values], dtype=np.float64)


class Run(dict):
    """One run: the outcome as ``impact run --format json`` prints it (this dict), and the path
    ``impact run --trace FILE.json`` writes, as NumPy arrays whose names carry the SI units:

    - ``time``: the independent variable at every accepted step (``variable`` names it, ``t (s)``);
    - ``states``: ``{"z (m)": array, "dz/dt (m/s)": array, ...}``, each as long as ``time``;
    - ``events``: ``{"event": names, "t (s)": where each fired, "z (m)": ..., ...}``, in the
      order they fired;
    - ``units``: the unit of each quantity by name (``{"t": "s", "z": "m", ...}``).

    A run without a path (``traced`` is false: the model integrates none, or this scene gives
    it none) has empty arrays, and ``no_path`` says why (as ``impact run --trace`` does).
    ``to_frame()`` gives the steps as a ``pandas.DataFrame``, ``to_frame("events")`` the events.
    """

    def __init__(self, outcome: dict, trace: Optional[dict], no_path: Optional[str] = None):
        import numpy as np

        super().__init__(outcome)
        self.traced = trace is not None
        self.no_path = no_path
        if trace is None:
            trace = {"variable": {"name": "t", "unit": "s", "values": []}, "states": [], "events": []}
        var = trace["variable"]
        self.variable = _heading(var["name"], var["unit"])
        self.time = _array(var["values"])
        self.units = {var["name"]: var["unit"]}
        self.states = {}
        for c in trace["states"]:
            self.units[c["name"]] = c["unit"]
            self.states[_heading(c["name"], c["unit"])] = _array(c["values"])
        events = trace["events"]
        self.events = {
            "event": np.array([e["name"] for e in events], dtype=object),
            self.variable: _array([e["at"] for e in events]),
        }
        for i, h in enumerate(self.states):
            self.events[h] = _array([e["state"][i] for e in events])

    def to_frame(self, what: str = "steps"):
        """``steps`` (the variable and the states, one row per accepted step) or ``events``."""
        import pandas as pd

        if what == "events":
            return pd.DataFrame(self.events)
        if what != "steps":
            raise ImpactcheckError(f"to_frame({what!r}): 'steps' or 'events'")
        return pd.DataFrame({self.variable: self.time, **self.states})


def run(scene: Scene) -> Run:
    """One run of ``scene`` (``impact run SCENE --format json --trace FILE.json``): the outcome
    as a dict, with the path as NumPy arrays (``time``, ``states``, ``events``; see ``Run``)."""
    with _ScenePath(scene) as path:
        outcome, trace, no_path = run_traced_json(path)
    return Run(json.loads(outcome), None if trace is None else json.loads(trace), no_path)


def series(
    order: int,
    viscous: str = "2zz",
    at: Union[str, Mapping[str, Any], None] = None,
    eval_t: Sequence[float] = (),
) -> dict:
    """The Adomian terms a0..a``order`` of the cone equation (18)-(20) of paper 000, exactly, as
    ``impact series --format json`` prints them; ``at`` gives exact values (``{"alpha": "-3",
    "gamma": "5/2"}`` or ``"alpha=-3,gamma=5/2"``), ``eval_t`` times to evaluate the sum at."""
    if isinstance(at, Mapping):
        at = ",".join(f"{k}={v}" for k, v in at.items())
    times = ",".join(repr(float(t)) for t in eval_t)
    return json.loads(series_json(int(order), viscous, at or "", times))


def _vary_spec(vary: Union[str, Mapping[str, Sequence[float]]]) -> str:
    if isinstance(vary, str):
        return vary
    if not isinstance(vary, Mapping) or len(vary) != 1:
        raise ImpactcheckError(
            "vary is one field and its range: {'impactor.v0': (start, stop, count)} "
            "or 'impactor.v0=start:stop:count'"
        )
    ((key, spec),) = vary.items()
    if isinstance(spec, str):
        return f"{key}={spec}"
    try:
        start, stop, count = spec
    except (TypeError, ValueError):
        raise ImpactcheckError(
            f"vary[{key!r}] is (start, stop, count), not {spec!r}"
        ) from None
    return f"{key}={start!r}:{stop!r}:{int(count)}"


def sweep_rows(
    scene: Scene,
    vary: Union[str, Mapping[str, Sequence[float]]],
    log: bool = False,
    shard: Optional[str] = None,
) -> list:
    """The runs of ``impact sweep --format json``, in index order: dicts with ``index``,
    ``value`` and ``result`` (or ``error``)."""
    with _ScenePath(scene) as path:
        return json.loads(sweep_text(path, _vary_spec(vary), "json", log, shard))["runs"]


def sweep(
    scene: Scene,
    vary: Union[str, Mapping[str, Sequence[float]]],
    log: bool = False,
    shard: Optional[str] = None,
):
    """A sweep as a ``pandas.DataFrame``: one row per point, in index order; the columns of
    ``impact sweep --format csv`` (the swept field, the outcome's numbers with nested keys dotted,
    the warnings and the error of each point), indexed by the point's index. The first call in
    an interpreter also imports pandas (about 0.9 s on a 2-core machine); later calls do not."""
    import io

    import pandas as pd

    with _ScenePath(scene) as path:
        text = sweep_text(path, _vary_spec(vary), "csv", log, shard)
    return pd.read_csv(io.StringIO(text), index_col="index")


def verify(
    claims: Optional[Union[str, os.PathLike]] = None,
    only: Optional[str] = None,
    power: bool = False,
) -> dict:
    """The verdicts of a claims file or folder (default: the repository's ``verify/``), as
    ``verify --claims PATH --format json`` prints them; nothing is written."""
    return json.loads(verify_json(None if claims is None else str(claims), only, power))


def __getattr__(name: str) -> Any:
    """``impactcheck.dask`` without an ``import impactcheck.dask`` first: the submodule is loaded
    on first use (it imports nothing of Dask until a sweep runs)."""
    if name == "dask":
        import importlib

        return importlib.import_module(f"{__name__}.dask")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
