"""Parameter sweeps of a scene on Dask distributed (docs/python.md, "Sweeps").

``sweep(scene, grid)`` runs the scene once per row of ``grid`` (every combination of a dict of
lists, or the rows of a DataFrame or a list of dicts), each row's parameters set by their table
ids (docs/parameters.md) before the run, and returns a pandas DataFrame with one row per run:
its parameters, then its outcome: ``error`` (None, or the one-line message of a run that
failed: the sweep goes on), ``time`` (s) and ``steps`` reached, ``wall_time`` (s), and for
each body (columns prefixed ``NAME.`` when the scene has several) the final ``volume`` (m³),
``height`` (its vertical extent, m), ``top`` (its highest point, m), ``total_energy`` and
``kinetic_energy`` (J) and ``max_speed`` (m/s).

The runs go to a Dask ``Client``: the one given, one connected to a scheduler address, or a
``LocalCluster`` of ``workers`` processes (one thread each, at most one per core this process
may use) started for the sweep and closed after it. ``workers=0`` runs them one after another in
this process, without Dask. Every run steps on one thread, so a run does the same arithmetic
wherever it runs: a sweep's table does not depend on where or in what order its runs went (a
world stepped on several threads may differ from it by rounding).

A grid entry's values are a list, range, numpy array or pandas Series; anything else (a number,
a name, a tuple ``(x, y, z)`` for a vector parameter) is one value. A parameter key is a table
id of a world or body parameter: a world parameter (``dt``, ``gravity``…) sets the world's, a
body parameter (``stiffness``, ``gas.nrt``…) every body's; ``NAME:id`` sets body NAME's only.
The scene and every key are checked before any run; ``ground`` is set before the other
``ground.*`` keys.

A run that fails — a bad value, a blow-up, a worker that died — is a row with its ``error``;
the other rows are kept. Interrupting the sweep (Ctrl+C) cancels the runs not finished.
"""

from __future__ import annotations

import itertools
import os
import re
import shutil
import time
from typing import Any, Iterable, Mapping

from ._core import World, scene_files

#: Statistics rows kept per run when ``out`` is given (at equal steps, both ends included).
STATS_ROWS = 101


def _values(v: Any) -> list:
    """A grid entry's values: a list, range, numpy array or Series is several; anything else
    (a number, a name, a tuple for a vector) is one."""
    if isinstance(v, (list, range)):
        return list(v)
    if not isinstance(v, tuple) and getattr(v, "ndim", 0) >= 1 and hasattr(v, "tolist"):
        return v.tolist()
    return [v]


def rows_of(grid: Any) -> list[dict]:
    """The runs of a grid: every combination of a dict of values (in key order, the last key
    varying fastest), the rows of a DataFrame, or a list of dicts as given."""
    if hasattr(grid, "to_dict") and hasattr(grid, "columns"):
        return [dict(r) for r in grid.to_dict(orient="records")]
    if isinstance(grid, Mapping):
        keys = list(grid)
        values = [_values(grid[k]) for k in keys]
        return [dict(zip(keys, combo)) for combo in itertools.product(*values)]
    return [dict(r) for r in grid]


def _plain(v: Any) -> Any:
    """numpy scalars (from a DataFrame) as Python numbers; lists as tuples."""
    if hasattr(v, "item") and not isinstance(v, (list, tuple)):
        return v.item()
    if isinstance(v, list):
        return tuple(v)
    return v


def check_keys(keys: Iterable[str], names: list) -> None:
    """Refuse, before any run, a key that is no world or body parameter or names no body."""
    table = {p["id"]: p["scope"] for p in _table()}
    for key in keys:
        name, _, pid = key.rpartition(":")
        if pid not in table:
            raise ValueError(f"{key}: no such parameter (see docs/parameters.md)")
        if table[pid] not in ("world", "body"):
            raise ValueError(f"{key}: is set in a scene file, not on a world")
        if name and name not in names:
            raise ValueError(f"{key}: there is no body '{name}' (the scene's bodies: {', '.join(names)})")
        if name and table[pid] != "body":
            raise ValueError(f"{key}: a world parameter is the world's, not one body's")


def apply(world: World, params: Mapping[str, Any]) -> None:
    """Set a run's parameters on ``world`` (see the module's documentation for the keys)."""
    names = world.names
    table = {p["id"]: p["scope"] for p in _table()}
    # `ground` first: the ground's other keys need one.
    for key, value in sorted(params.items(), key=lambda kv: kv[0].rpartition(":")[2] != "ground"):
        value = _plain(value)
        name, _, pid = key.rpartition(":")
        if pid not in table:
            raise ValueError(f"{key}: no such parameter (see docs/parameters.md)")
        if name:
            if name not in names:
                raise ValueError(f"{key}: there is no body '{name}' (the scene's bodies: {', '.join(names)})")
            world.set_param(pid, value, names.index(name))
        elif table[pid] == "body":
            for i in range(len(names)):
                world.set_param(pid, value, i)
        else:
            world.set_param(pid, value)


_TABLE: list | None = None


def _table() -> list:
    global _TABLE
    if _TABLE is None:
        from ._core import parameters

        _TABLE = parameters()
    return _TABLE


def outcome(world: World) -> dict:
    """A run's summary columns (see the module's documentation)."""
    row: dict = {"time": world.time, "steps": world.steps}
    several = len(world.names) > 1
    for i, name in enumerate(world.names):
        s = world.stats(i)
        y = world.bodies[i].positions[:, 1]
        prefix = f"{name}." if several else ""
        row.update({
            f"{prefix}volume": world.bodies[i].volume,
            f"{prefix}height": float(y.max() - y.min()),
            f"{prefix}top": float(y.max()),
            f"{prefix}total_energy": s["total_energy"],
            f"{prefix}kinetic_energy": s["kinetic_energy"],
            f"{prefix}max_speed": s["max_speed"],
        })
    return row


def _head(index: int, params: Mapping[str, Any]) -> dict:
    """A row's first columns: the run's index and its parameters as plain values."""
    row: dict = {"run": index}
    for k, v in params.items():
        try:
            row[k] = _plain(v)
        except Exception:
            row[k] = repr(v)
    row["error"] = None
    return row


def _failed(e: BaseException) -> str:
    return f"{type(e).__name__}: {e}"


def run_one(index: int, text: str, files: dict, params: dict, out: str | None = None, frames: int | None = None) -> dict:
    """One run of a sweep: a row with its parameters and outcome, or its error. Never raises
    for a run's own failure (a bad parameter, a blow-up, a panic in the engine): that is the
    row's ``error``."""
    row = _head(index, params)
    start = time.perf_counter()
    world = None
    try:
        world = World.from_scene_text(text, files)
        world.threads = 1  # one core per run: the workers share the machine's
        apply(world, params)
        folder = os.path.join(out, f"run_{index:04d}") if out else None
        if folder is None:
            world.run()
        else:
            _run_recording(world, folder, frames)
        row.update(outcome(world))
    except (KeyboardInterrupt, SystemExit):
        raise
    except BaseException as e:  # a run's failure is its row, not the sweep's (a panic too)
        row["error"] = _failed(e)
        if world is not None:
            row.update({"time": world.time, "steps": world.steps})
    row["wall_time"] = time.perf_counter() - start
    return row


def _run_recording(world: World, folder: str, frames: int | None) -> None:
    """Run to the end keeping STATS_ROWS statistics rows (``stats.parquet``), ``frames`` OBJ
    frames per body (``frames/NAME_0000.obj``…) and the final OBJ per body."""
    import pandas as pd

    total = max(1, round(world.duration / world.dt))
    marks = {round(k * total / (STATS_ROWS - 1)) for k in range(STATS_ROWS)}
    # step -> frame number (the frames at equal steps, both ends included)
    shots = {s: f for f, s in enumerate(sorted({round(k * total / (frames - 1)) for k in range(frames)}))} if frames and frames >= 2 else {}
    os.makedirs(os.path.join(folder, "frames") if shots else folder, exist_ok=True)
    rows = []

    def take() -> None:
        if world.steps in marks:
            for i, name in enumerate(world.names):
                s = world.stats(i)
                rows.append({"body": name, **{k: v for k, v in s.items() if not isinstance(v, (list, dict))},
                             **{f"center_of_mass_{a}": c for a, c in zip("xyz", s["center_of_mass"])}})
        if world.steps in shots:
            for i, name in enumerate(world.names):
                _write(os.path.join(folder, "frames", f"{name}_{shots[world.steps]:04d}.obj"), world.obj(i, f"softsculpt sweep: t = {world.time} s"))

    try:
        take()
        while world.time < world.duration - 0.5 * world.dt:
            world.step(1)
            take()
    finally:  # a run that failed keeps the statistics up to its failure
        pd.DataFrame(rows).to_parquet(os.path.join(folder, "stats.parquet"))
    for i, name in enumerate(world.names):
        _write(os.path.join(folder, f"{name}.obj"), world.obj(i, f"softsculpt sweep: t = {world.time} s"))


def _write(path: str, text: str) -> None:
    """Write a file whole or not at all (a temporary beside it, renamed)."""
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def cores() -> int:
    """Cores this process may run on (its CPU affinity where the system has one)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


_EARLIER = re.compile(r"^(sweep\.parquet|sweep\.csv|run_\d{4,})$")


def _prepare_out(out: str, overwrite: bool) -> None:
    """An empty (or new) folder for a sweep's outputs; an earlier sweep's removed with
    ``overwrite``; a folder holding anything else refused (nothing of it is removed)."""
    os.makedirs(out, exist_ok=True)
    entries = os.listdir(out)
    others = [e for e in entries if not _EARLIER.match(e)]
    if others:
        raise ValueError(f"{out}: the folder holds other files ({', '.join(sorted(others)[:3])}): give an empty or new folder")
    if entries and not overwrite:
        raise ValueError(f"{out}: the folder holds an earlier sweep's outputs: give an empty or new folder, or overwrite (--overwrite) to replace them")
    for e in entries:
        path = os.path.join(out, e)
        shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)


def sweep(scene: str | os.PathLike, grid: Any, client: Any = None, *, workers: int | None = None,
          out: str | os.PathLike | None = None, frames: int | None = None, overwrite: bool = False):
    """Run ``scene`` once per row of ``grid`` and return a pandas DataFrame of the runs (see
    the module's documentation). ``client``: a ``dask.distributed.Client``, a scheduler
    address, or None for a ``LocalCluster`` of ``workers`` processes (default and most: the
    cores this process may use); ``workers=0`` runs serially here. ``out``: an empty folder (or
    an earlier sweep's, with ``overwrite``) for ``sweep.parquet`` (the table) and each run's
    ``run_NNNN/`` (``stats.parquet``, final OBJ, ``frames`` OBJ frames); with a remote
    scheduler it must be storage the workers share."""
    import pandas as pd

    text, files = scene_files(os.fspath(scene))
    rows = rows_of(grid)
    if not rows:
        raise ValueError("the grid has no runs (a parameter with no values?)")
    names = World.from_scene_text(text, files).names
    check_keys({k for r in rows for k in r}, names)
    if client is None and workers is not None and workers > cores():
        raise ValueError(f"workers: this machine runs {cores()} processes at once: give at most {cores()} (0: one run after another)")
    out = os.fspath(out) if out is not None else None
    if out:
        _prepare_out(out, overwrite)
    args = [(i, text, files, r, out, frames) for i, r in enumerate(rows)]
    if workers == 0 and client is None:
        results = [run_one(*a) for a in args]
    else:
        results = _on_dask(args, client, workers)
    table = pd.DataFrame(results)
    if out:
        table.to_parquet(os.path.join(out, "sweep.parquet"))
    return table


def _on_dask(args: Iterable[tuple], client: Any, workers: int | None) -> list[dict]:
    """Map ``run_one`` over ``args`` on ``client`` (or a LocalCluster made for the call)."""
    from dask.distributed import Client, LocalCluster

    args = list(args)
    own = None
    if client is None:
        n = workers or cores()
        own = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(own)
    elif isinstance(client, str):
        client = own = Client(client)
    try:
        if not args:
            return []
        # The scene is scattered once, not sent with every run.
        text_f, files_f = client.scatter([args[0][1], args[0][2]], broadcast=True)
        futures = [client.submit(run_one, a[0], text_f, files_f, a[3], a[4], a[5], pure=False) for a in args]
        rows = []
        try:
            for a, f in zip(args, futures):
                try:
                    rows.append(f.result())
                except (KeyboardInterrupt, SystemExit):
                    raise
                except BaseException as e:  # the worker died (KilledWorker), the task was lost
                    rows.append({**_head(a[0], a[3]), "error": _failed(e), "wall_time": None})
        except BaseException:
            client.cancel(futures)
            raise
        return rows
    finally:
        if own is not None:
            client.close()
            own.close()
