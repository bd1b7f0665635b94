#!/usr/bin/env python3
"""Run `softsculpt bench` and the reference C++ loop (shared/bench/peer_cpp.cpp) side by side.

Both run the standard workload (see crates/softsculpt/src/workload.rs) on the same icospheres,
alternating per level and per round so that machine noise hits both alike. Reports the best
time of each and the ratio, and checks that both end at the same volume (same physics).
With --baseline BIN, a second softsculpt binary (e.g. a build of main) runs in the same
rotation, for before/after ratios measured under the same machine load. With --cpu, each
softsculpt run also reports its CPU time per step (the process's user + system time for the
steps, less that of a one-step run: the setup), which other processes on the machine disturb
less than the wall time; meaningful on one thread (on several, idle threads spin).

usage: scripts/bench_compare.py [--levels 4,5,6,7] [--steps 1000] [--rounds 3] [--threads N]
                                [--baseline BIN] [--cpu] [--shared DIR]
"""
import argparse
import json
import os
import re
import resource
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--levels", default="4,5,6,7")
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=0, help="threads for softsculpt (0: every core)")
    ap.add_argument("--baseline", help="another softsculpt binary to time in the same rotation")
    ap.add_argument("--cpu", action="store_true", help="also report CPU ms per step (best of the rounds)")
    ap.add_argument("--shared", default=os.path.join(ROOT, "..", "shared"))
    a = ap.parse_args()
    if a.cpu and a.steps < 2:
        # CPU per step is (CPU of the run − CPU of a one-step run) / (steps − 1).
        sys.exit("error: --cpu needs --steps 2 or more (it subtracts a one-step run's setup)")
    levels = [int(x) for x in a.levels.split(",")]
    bench = os.path.join(a.shared, "bench")
    if not os.path.isfile(os.path.join(bench, "peer_cpp.cpp")):
        sys.exit("error: %s/peer_cpp.cpp not found (pass --shared DIR)" % bench)
    work = os.path.join(ROOT, "target", "bench-peer")
    os.makedirs(work, exist_ok=True)
    subprocess.run([sys.executable, os.path.join(bench, "gen_icosphere.py"), os.path.join(work, "ico")] + [str(l) for l in levels],
                   check=True, stdout=subprocess.DEVNULL)
    peer = os.path.join(work, "peer_cpp")
    subprocess.run(["g++", "-O3", "-march=native", "-std=c++17", "-I" + bench, os.path.join(bench, "peer_cpp.cpp"), "-o", peer], check=True)
    subprocess.run(["cargo", "build", "--release", "-q", "-p", "softsculpt-cli"], check=True, cwd=ROOT)
    ours_bin = os.path.join(ROOT, "target", "release", "softsculpt")

    base_col = " %14s" % "baseline ms" if a.baseline else ""
    cpu_col = " %12s%s" % ("ours CPU ms", " %12s" % "base CPU ms" if a.baseline else "") if a.cpu else ""
    print("%9s %14s %14s %9s %16s %16s%s%s" % ("vertices", "ours ms/step", "C++ ms/step", "C++/ours", "our volume", "C++ volume", base_col, cpu_col))

    def run(binary, level, steps):
        """The bench's JSON row and the CPU seconds the child used."""
        # getrusage's child times are in µs (os.times counts 10 ms clock ticks).
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        out = subprocess.run([binary, "bench", "--levels", str(level), "--steps", str(steps), "--reps", "1", "--json", "--threads", str(a.threads)],
                             check=True, capture_output=True, text=True).stdout
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        return json.loads(out.strip().splitlines()[-1]), cpu

    def ours(binary, level):
        r, cpu = run(binary, level, a.steps)
        if a.cpu and a.steps > 1:
            _, setup = run(binary, level, 1)
            r["cpu_ms_per_step"] = (cpu - setup) * 1e3 / (a.steps - 1)
        return r

    rows = []
    for level in levels:
        best_ours, best_peer, best_base = float("inf"), float("inf"), float("inf")
        cpu_ours, cpu_base = float("inf"), float("inf")
        vol_ours = vol_peer = None
        nv = None
        for _ in range(a.rounds):
            r = ours(ours_bin, level)
            best_ours = min(best_ours, r["ms_per_step"])
            cpu_ours = min(cpu_ours, r.get("cpu_ms_per_step", float("inf")))
            vol_ours, nv = r["volume"], r["vertices"]
            out = subprocess.run([peer, os.path.join(work, "ico", "icosphere_L%d.obj" % level), "--steps", str(a.steps), "--reps", "1"],
                                 check=True, capture_output=True, text=True).stdout
            m = re.search(r"ms_per_step=([0-9.eE+-]+) .*volume=([0-9.eE+-]+)", out)
            best_peer = min(best_peer, float(m.group(1)))
            vol_peer = float(m.group(2))
            if a.baseline:
                rb = ours(a.baseline, level)
                best_base = min(best_base, rb["ms_per_step"])
                cpu_base = min(cpu_base, rb.get("cpu_ms_per_step", float("inf")))
        rel = abs(vol_ours - vol_peer) / abs(vol_peer)
        row = {"vertices": nv, "threads": a.threads, "ours_ms": best_ours, "cpp_ms": best_peer, "ratio": best_peer / best_ours, "volume_rel_diff": rel}
        if a.baseline:
            row["baseline_ms"] = best_base
        if a.cpu:
            row["ours_cpu_ms"] = cpu_ours
            if a.baseline:
                row["baseline_cpu_ms"] = cpu_base
        rows.append(row)
        cpu_txt = " %12.4f%s" % (cpu_ours, " %12.4f" % cpu_base if a.baseline else "") if a.cpu else ""
        print("%9d %14.4f %14.4f %9.2f %16.9f %16.9f%s%s%s" % (nv, best_ours, best_peer, best_peer / best_ours, vol_ours, vol_peer,
                                                               " %14.4f" % best_base if a.baseline else "", cpu_txt,
                                                               "" if rel < 1e-8 else "  VOLUMES DIFFER"), flush=True)
    json.dump(rows, open(os.path.join(work, "last.json"), "w"), indent=1)


if __name__ == "__main__":
    main()
