"""A 16-run sweep on 1 and 2 Dask workers (LocalCluster, one thread each): runs per minute
(BENCHMARKS.md, "The Python package"). The scene is scenes/fig3_sphere_drop.toml (642
vertices, 6 s) stepped by the implicit integrator at dt 4 ms (1,500 steps, ~2.7 s a run on one
core: long enough that Dask's per-task cost, ~ms, does not count); the grid 4 stiffnesses x 4
gas amounts.

    target/py-venv/bin/python crates/softsculpt-py/bench/sweep_workers.py
"""

import json
import tempfile
import time
from pathlib import Path

import softsculpt

fig3 = Path(__file__).resolve().parents[3] / "scenes" / "fig3_sphere_drop.toml"
scene = Path(tempfile.mkdtemp()) / "fig3_implicit.toml"
scene.write_text(fig3.read_text().replace('dt = 0.001 ', 'dt = 0.004 ').replace('integrator = "symplectic"', 'integrator = "implicit"'))
grid = {"stiffness": [80.0, 100.0, 130.0, 160.0], "gas.nrt": [40.0, 50.0, 60.0, 70.0]}

if __name__ == "__main__":
    for workers in (1, 2):
        from dask.distributed import Client, LocalCluster

        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, Client(cluster) as client:
            t0 = time.perf_counter()
            table = softsculpt.sweep(scene, grid, client=client)
            wall = time.perf_counter() - t0
        print(json.dumps({"workers": workers, "runs": len(table), "failed": int(table["error"].notna().sum()), "wall_s": round(wall, 2),
                          "runs_per_minute": round(60 * len(table) / wall, 1), "mean_run_s": round(float(table["wall_time"].mean()), 3)}))
