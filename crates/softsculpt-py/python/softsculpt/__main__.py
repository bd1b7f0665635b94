"""``python -m softsculpt sweep SCENE --grid GRID.toml [--workers N] [--out DIR] [--frames N]``
(also ``softsculpt sweep``, which runs this): a parameter sweep of a scene on Dask.

GRID.toml lists each parameter's values by its table id, e.g.::

    stiffness = [100.0, 300.0, 1000.0]
    "gas.nrt" = [4.0, 8.0]

Writes DIR/sweep.parquet and DIR/sweep.csv (one row per run) and each run's folder, and prints
one line saying so; exit status 1 if the sweep could not run, 0 otherwise (failed runs are
rows with their error, counted in that line).
"""

import argparse
import os
import sys


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="softsculpt sweep", description="Run a scene over a grid of parameters on Dask distributed.")
    ap.add_argument("scene", help="the scene file (.toml, docs/scenes.md)")
    ap.add_argument("--grid", required=True, help="TOML file: each parameter id = a list of values")
    ap.add_argument("--workers", type=int, default=None, help="LocalCluster worker processes (default: every core; 0: serially, without Dask)")
    ap.add_argument("--scheduler", default=None, help="a Dask scheduler address to run on instead of a LocalCluster")
    ap.add_argument("--out", required=True, help="output folder")
    ap.add_argument("--frames", type=int, default=None, help="also write N OBJ frames of every run")
    a = ap.parse_args(argv)
    try:
        import tomllib
    except ImportError:  # Python < 3.11
        import tomli as tomllib
    from .sweeps import sweep

    try:
        with open(a.grid, "rb") as f:
            grid = tomllib.load(f)
        if a.workers is not None and a.workers < 0:
            raise ValueError(f"--workers: must not be negative, got {a.workers}")
        if a.frames is not None and a.frames < 2:
            raise ValueError("--frames: at least 2 (the first frame is the start, the last the end)")
        table = sweep(a.scene, grid, client=a.scheduler, workers=a.workers, out=a.out, frames=a.frames)
    except (OSError, ValueError, tomllib.TOMLDecodeError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    table.to_csv(os.path.join(a.out, "sweep.csv"), index=False)
    failed = int(table["error"].notna().sum())
    print(f"wrote {a.out}: sweep.parquet, sweep.csv and {len(table)} run folders; {len(table) - failed} runs succeeded, {failed} failed", file=sys.stderr)
    return 0


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "sweep":
        sys.exit(main(sys.argv[2:]))
    print("usage: python -m softsculpt sweep SCENE --grid GRID.toml --out DIR [--workers N]", file=sys.stderr)
    sys.exit(2)
