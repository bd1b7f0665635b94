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
``LocalCluster`` of ``workers`` processes (one thread each) started for the sweep and closed
after it. ``workers=0`` runs them one after another in this process, without Dask. A run does
the same arithmetic wherever it runs (each on one thread), so a sweep's table does not depend
on where or in what order its runs went.

A parameter key is a table id: a world parameter (``dt``, ``gravity``…) sets the world's, a
body parameter (``stiffness``, ``gas.nrt``…) every body's; ``NAME:id`` sets body NAME's only.
"""

from __future__ import annotations

import itertools
import os
import time
from typing import Any, Iterable, Mapping

from ._core import World, scene_files

#: Statistics rows kept per run when ``out`` is given (at equal steps, both ends included).
STATS_ROWS = 101


def rows_of(grid: Any) -> list[dict]:
    """The runs of a grid: every combination of a dict of lists (in key order, the last key
    varying fastest), the rows of a DataFrame, or a list of dicts as given."""
    if hasattr(grid, "to_dict") and hasattr(grid, "columns"):
        return [dict(r) for r in grid.to_dict(orient="records")]
    if isinstance(grid, Mapping):
        keys = list(grid)
        values = [v if isinstance(v, (list, tuple)) else [v] for v in (grid[k] for k in keys)]
        return [dict(zip(keys, combo)) for combo in itertools.product(*values)]
    return [dict(r) for r in grid]


def _plain(v: Any) -> Any:
    """numpy scalars (from a DataFrame) as Python numbers; lists as tuples."""
    if hasattr(v, "item") and not isinstance(v, (list, tuple)):
        return v.item()
    if isinstance(v, list):
        return tuple(v)
    return v


def apply(world: World, params: Mapping[str, Any]) -> None:
    """Set a run's parameters on ``world`` (see the module's documentation for the keys)."""
    names = world.names
    table = {p["id"]: p["scope"] for p in _table()}
    for key, value in params.items():
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


def run_one(index: int, text: str, files: dict, params: dict, out: str | None = None, frames: int | None = None) -> dict:
    """One run of a sweep: a row with its parameters and outcome, or its error. Never raises
    for a run's own failure (a bad parameter, a blow-up): that is the row's ``error``."""
    row: dict = {"run": index, **{k: _plain(v) for k, v in params.items()}, "error": None}
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
    except Exception as e:  # a run's failure is its row, not the sweep's
        row["error"] = f"{type(e).__name__}: {e}"
        if world is not None:
            row.update({"time": world.time, "steps": world.steps})
    row["wall_time"] = time.perf_counter() - start
    return row


def _run_recording(world: World, folder: str, frames: int | None) -> None:
    """Run to the end keeping STATS_ROWS statistics rows (``stats.parquet``), ``frames`` OBJ
    frames per body (``frames/NAME_0000.obj``…) and the final OBJ per body."""
    import pandas as pd

    total = max(1, round(world.duration / world.dt))
    marks = sorted({round(k * total / (STATS_ROWS - 1)) for k in range(STATS_ROWS)})
    shots = sorted({round(k * total / (frames - 1)) for k in range(frames)}) if frames and frames >= 2 else []
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
                _write(os.path.join(folder, "frames", f"{name}_{shots.index(world.steps):04d}.obj"), world.obj(i, f"softsculpt sweep: t = {world.time} s"))

    take()
    while world.time < world.duration - 0.5 * world.dt:
        world.step(1)
        take()
    pd.DataFrame(rows).to_parquet(os.path.join(folder, "stats.parquet"))
    for i, name in enumerate(world.names):
        _write(os.path.join(folder, f"{name}.obj"), world.obj(i, f"softsculpt sweep: t = {world.time} s"))


def _write(path: str, text: str) -> None:
    """Write a file whole or not at all (a temporary beside it, renamed)."""
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def sweep(scene: str | os.PathLike, grid: Any, client: Any = None, *, workers: int | None = None,
          out: str | os.PathLike | None = None, frames: int | None = None):
    """Run ``scene`` once per row of ``grid`` and return a pandas DataFrame of the runs (see
    the module's documentation). ``client``: a ``dask.distributed.Client``, a scheduler
    address, or None for a ``LocalCluster`` of ``workers`` processes (default: the machine's
    cores); ``workers=0`` runs serially here. ``out``: a folder for ``sweep.parquet`` (the
    table) and each run's ``run_NNNN/`` (``stats.parquet``, final OBJ, ``frames`` OBJ frames)."""
    import pandas as pd

    text, files = scene_files(os.fspath(scene))
    rows = rows_of(grid)
    for r in rows:  # a key that is no parameter fails the sweep before any run, once
        for key in r:
            if key.rpartition(":")[2] not in {p["id"] for p in _table()}:
                raise ValueError(f"{key}: no such parameter (see docs/parameters.md)")
    out = os.fspath(out) if out is not None else None
    if out:
        os.makedirs(out, exist_ok=True)
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
        n = workers or os.cpu_count() or 1
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
        return client.gather(futures)
    finally:
        if own is not None:
            client.close()
            own.close()
