"""``python -m softsculpt sweep SCENE --grid GRID.toml [--workers N] [--out DIR] [--frames N]``
(also ``softsculpt sweep``, which runs this): a parameter sweep of a scene on Dask.

GRID.toml lists each parameter's values by its table id, e.g.::

    stiffness = [100.0, 300.0, 1000.0]
    gas.nrt = [4.0, 8.0]                 # (dotted keys are the table's ids)
    "sphere:stiffness" = [50.0, 80.0]    # body sphere's only

Writes DIR/sweep.parquet and DIR/sweep.csv (one row per run) and each run's folder, and prints
one line saying so; exit status 1 if the sweep could not run, 0 otherwise (failed runs are
rows with their error, counted in that line).
"""

import argparse
import os
import sys


def flatten(table: dict, prefix: str = "") -> dict:
    """TOML's dotted keys as the table's ids: `gas.nrt = [...]` (a table `gas` holding `nrt`)
    is the key "gas.nrt", as `"gas.nrt" = [...]` is."""
    out = {}
    for k, v in table.items():
        if isinstance(v, dict):
            out.update(flatten(v, f"{prefix}{k}."))
        else:
            out[f"{prefix}{k}"] = v
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="softsculpt sweep", description="Run a scene over a grid of parameters on Dask distributed.")
    ap.add_argument("scene", help="the scene file (.toml, docs/scenes.md)")
    ap.add_argument("--grid", required=True, help="TOML file: each parameter id = a list of values")
    ap.add_argument("--workers", type=int, default=None, help="LocalCluster worker processes (default: every core; 0: serially, without Dask)")
    ap.add_argument("--scheduler", default=None, help="a Dask scheduler address to run on instead of a LocalCluster")
    ap.add_argument("--out", required=True, help="output folder")
    ap.add_argument("--frames", type=int, default=None, help="also write N OBJ frames of every run")
    ap.add_argument("--overwrite", action="store_true", help="replace an earlier sweep's outputs in --out")
    a = ap.parse_args(argv)
    try:
        import tomllib
    except ImportError:  # Python < 3.11
        import tomli as tomllib
    from .sweeps import sweep

    try:
        with open(a.grid, "rb") as f:
            grid = flatten(tomllib.load(f))
        if a.workers is not None and a.workers < 0:
            raise ValueError(f"--workers: must not be negative, got {a.workers}")
        if a.frames is not None and a.frames < 2:
            raise ValueError("--frames: at least 2 (the first frame is the start, the last the end)")
        table = sweep(a.scene, grid, client=a.scheduler, workers=a.workers, out=a.out, frames=a.frames, overwrite=a.overwrite)
    except (OSError, ValueError, tomllib.TOMLDecodeError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    table.to_csv(os.path.join(a.out, "sweep.csv"), index=False)  # (sweep.parquet: written by sweep)
    failed = int(table["error"].notna().sum())
    print(f"wrote {a.out}: sweep.parquet, sweep.csv and {len(table)} run folders; {len(table) - failed} runs succeeded, {failed} failed", file=sys.stderr)
    return 0


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "sweep":
        sys.exit(main(sys.argv[2:]))
    print("usage: python -m softsculpt sweep SCENE --grid GRID.toml --out DIR [--workers N]", file=sys.stderr)
    sys.exit(2)
