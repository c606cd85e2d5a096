"""Sweeps on a Dask cluster (issue 55): the grid split into shards (``impact sweep --shard K/N``,
the mechanism the command line's batch jobs use), each shard a task on the client's workers, the
rows joined in index order. A shard is deterministic, so a task lost with its worker is rerun by
Dask's scheduler and gives the same rows: the result is complete or the call raises.

With ``dask-jobqueue`` the same call runs on a Slurm cluster::

    from dask_jobqueue import SLURMCluster
    from distributed import Client
    cluster = SLURMCluster(cores=32, memory="16GB", walltime="01:00:00")
    cluster.scale(jobs=8)
    frame = impactcheck.dask.sweep("scenes/hertz.toml", {"impactor.v0": (1e-6, 10, 10**7)}, Client(cluster))

A folder of papers is audited the same way (``audit_many``): each paper a task, the rows joined in
the papers' order.
"""

from __future__ import annotations

import io
import json
import os
from typing import Any, Mapping, Optional, Sequence, Union

from . import _ScenePath, _paths, _shelf_frame, _vary_spec, papers_in, sweep_text

__all__ = ["audit_many", "sweep", "sweep_rows"]


def _shard_text(scene_text: str, vary: str, log: bool, shard: str, fmt: str) -> str:
    # runs on a worker: the scene travels as text, written to the worker's own temporary file
    from . import _ScenePath as _Path

    with _Path(scene_text) as path:
        return sweep_text(path, vary, fmt, log, shard)


def _scene_text(scene) -> str:
    with _ScenePath(scene) as path:
        with open(path, encoding="utf-8") as f:
            return f.read()


def _shards(client, scene, vary, log, shards, fmt):
    text = _scene_text(scene)
    spec = _vary_spec(vary)
    n = shards or max(1, 2 * len(client.scheduler_info().get("workers", {})))
    futures = [
        client.submit(_shard_text, text, spec, log, f"{k}/{n}", fmt, pure=False, retries=2)
        for k in range(n)
    ]
    return client.gather(futures), spec


def sweep_rows(
    scene, vary, client, log: bool = False, shards: Optional[int] = None
) -> list:
    """The runs of :func:`impactcheck.sweep_rows`, computed in ``shards`` tasks (default: two per
    worker) on ``client``'s cluster, in index order."""
    import json

    texts, _ = _shards(client, scene, vary, log, shards, "json")
    rows = [r for t in texts for r in json.loads(t)["runs"]]
    rows.sort(key=lambda r: r["index"])
    return rows


def sweep(scene, vary, client, log: bool = False, shards: Optional[int] = None):
    """:func:`impactcheck.sweep` (a ``pandas.DataFrame``, one row per point, in index order),
    computed in ``shards`` tasks on ``client``'s cluster."""
    import pandas as pd

    texts, _ = _shards(client, scene, vary, log, shards, "csv")
    frames = [pd.read_csv(io.StringIO(t), index_col="index") for t in texts]
    return pd.concat(frames).sort_index()


def _row_text(folder: str, paper: str, options: tuple) -> str:
    # runs on a worker: one paper's row of `verify audit FOLDER --format json`
    from . import audit_row_json

    return audit_row_json(folder, paper, *options)


def audit_many(folder, client, units=None, preamble=(), vocabulary=()):
    """:func:`impactcheck.audit_many` (a ``pandas.DataFrame``, one row per paper under
    ``folder``, the totals in ``attrs["total"]``), each paper a task on ``client``'s cluster, the
    rows in the papers' order. The workers read the papers from the same paths as the caller (a
    shared file system): the folder and the files named are given to them as absolute paths, and
    a paper that cannot be read says so in its ``error`` with that path."""
    folder = os.path.abspath(folder)
    options = (
        None if units is None else os.path.abspath(units),
        [os.path.abspath(f) for f in _paths(preamble)],
        [os.path.abspath(f) for f in _paths(vocabulary)],
    )
    # an audit is deterministic: a task lost with its worker is rerun and gives the same row
    futures = [
        client.submit(_row_text, folder, p, options, pure=False, retries=2)
        for p in papers_in(folder)
    ]
    return _shelf_frame([json.loads(t) for t in client.gather(futures)])
