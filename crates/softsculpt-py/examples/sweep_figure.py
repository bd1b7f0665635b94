"""docs/figures/sweep_height.png: the dropped sphere of Fig. 3 (scenes/fig3_sphere_drop.toml)
swept over gas amount x stiffness on a local Dask cluster, its resting height (vertical extent
after 6 s) against nRT, one line per stiffness. Needs matplotlib besides the sweep's packages:

    target/py-venv/bin/pip install matplotlib
    target/py-venv/bin/python crates/softsculpt-py/examples/sweep_figure.py
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import softsculpt

root = Path(__file__).resolve().parents[3]

if __name__ == "__main__":
    grid = {"stiffness": [50.0, 100.0, 200.0], "gas.nrt": [20.0, 40.0, 60.0, 80.0, 100.0, 120.0]}
    table = softsculpt.sweep(root / "scenes" / "fig3_sphere_drop.toml", grid, workers=2)
    assert table["error"].isna().all(), table["error"].dropna().tolist()
    fig, ax = plt.subplots(figsize=(6, 4), dpi=120)
    for k, runs in table.groupby("stiffness"):
        ax.plot(runs["gas.nrt"], runs["height"], "o-", label=f"k = {k:g} N/m")
    ax.axhline(2.0, color="grey", lw=0.8, ls="--")
    ax.text(grid["gas.nrt"][0], 2.0, " undeformed diameter 2 m", va="bottom", fontsize=8, color="grey")
    ax.set_xlabel("gas nRT (J)")
    ax.set_ylabel("height after 6 s (m)")
    ax.set_title("A 1 kg sphere dropped on the ground, after 6 s")
    ax.legend()
    fig.tight_layout()
    out = root / "docs" / "figures" / "sweep_height.png"
    fig.savefig(out)
    print(table[["stiffness", "gas.nrt", "height", "volume", "wall_time"]].to_string(index=False))
    print(f"wrote {out}")
