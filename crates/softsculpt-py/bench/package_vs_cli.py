"""The Python package stepping the standard workload against `softsculpt bench`, in one run
(BENCHMARKS.md, "The Python package"). Alternates the two, `reps` times each, best of each:

    target/py-venv/bin/python crates/softsculpt-py/bench/package_vs_cli.py [LEVELS] [STEPS] [REPS]
"""

import json
import subprocess
import sys
import time
from pathlib import Path

import softsculpt

root = Path(__file__).resolve().parents[3]
levels = [int(x) for x in (sys.argv[1] if len(sys.argv) > 1 else "5,6").split(",")]
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
reps = int(sys.argv[3]) if len(sys.argv) > 3 else 3
cli = str(root / "target" / "release" / "softsculpt")

for level in levels:
    py_best = cli_best = float("inf")
    for _ in range(reps):
        w = softsculpt.World.workload(level)
        w.threads = 0  # every core, as the CLI bench without --threads
        t0 = time.perf_counter()
        w.step(steps)
        py_best = min(py_best, (time.perf_counter() - t0) * 1e3 / steps)
        out = subprocess.run([cli, "bench", "--levels", str(level), "--steps", str(steps), "--reps", "1", "--json"], check=True, capture_output=True, text=True).stdout
        cli_best = min(cli_best, json.loads(out)["ms_per_step"])
    print(json.dumps({"level": level, "vertices": w.bodies[0].vertex_count, "package_ms_per_step": round(py_best, 4), "cli_ms_per_step": round(cli_best, 4), "ratio": round(py_best / cli_best, 3)}))
