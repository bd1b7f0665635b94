"""Sweeps on Dask distributed: the same runs wherever they run, failures as rows."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import softsculpt
from softsculpt.sweeps import rows_of

SCENE = Path(__file__).parent / "data" / "drop.toml"
GRID = {"stiffness": [60.0, 100.0, 150.0, 250.0], "gas.nrt": [20.0, 40.0]}


@pytest.fixture(scope="module")
def client():
    """A 2-worker LocalCluster's client (its scheduler's address: client.scheduler.address)."""
    from dask.distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


def outcome(table: pd.DataFrame) -> pd.DataFrame:
    return table.drop(columns=["wall_time"]).sort_values("run").reset_index(drop=True)


def test_eight_runs_on_two_workers_equal_the_same_runs_done_serially(client):
    on_dask = softsculpt.sweep(SCENE, GRID, client=client)
    serial = softsculpt.sweep(SCENE, GRID, workers=0)
    assert len(on_dask) == 8 and on_dask["error"].isna().all()
    # Bit for bit: every float column equal exactly (each run on one thread, the same code).
    pd.testing.assert_frame_equal(outcome(on_dask), outcome(serial), check_exact=True)
    # The grid's rows, in order, the last key fastest.
    assert list(on_dask["stiffness"][:2]) == [60.0, 60.0] and list(on_dask["gas.nrt"][:2]) == [20.0, 40.0]
    # And the physics moves the way it should: more gas, a taller resting ball (same stiffness).
    for k in (60.0, 250.0):
        rows = serial[serial["stiffness"] == k].set_index("gas.nrt")
        assert rows.loc[40.0, "ball.volume"] > rows.loc[20.0, "ball.volume"]


def test_a_run_that_blows_up_is_reported_and_the_others_complete(client, tmp_path):
    grid = [{"dt": 0.001}, {"dt": 0.01}, {"dt": 0.001, "sphere:stiffness": 80.0}, {"stiffness": -1.0}]
    table = softsculpt.sweep(SCENE, grid, client=client, out=tmp_path)
    table = table.sort_values("run")
    errors = list(table["error"])
    assert table["error"].isna().tolist() == [True, False, True, False]
    assert errors[1].startswith("SimulationError") and errors[3].startswith("ValueError: stiffness")
    assert (tmp_path / "sweep.parquet").exists()
    stats = pd.read_parquet(tmp_path / "run_0000" / "stats.parquet")
    assert set(stats["body"]) == {"ball", "sphere"} and stats["step"].max() == 300
    assert (tmp_path / "run_0000" / "ball.obj").read_text().count("\nv ") == 146
    back = pd.read_parquet(tmp_path / "sweep.parquet")
    assert len(back) == 4


def test_grids_expand_to_every_combination_in_order():
    assert rows_of({"a": [1, 2], "b": [3, 4, 5]})[:4] == [{"a": 1, "b": 3}, {"a": 1, "b": 4}, {"a": 1, "b": 5}, {"a": 2, "b": 3}]
    assert rows_of(pd.DataFrame({"a": [1.0, 2.0]})) == [{"a": 1.0}, {"a": 2.0}]
    with pytest.raises(ValueError, match="stifness"):
        softsculpt.sweep(SCENE, {"stifness": [1.0]}, workers=0)


def test_the_command_line_sweep_writes_its_table(tmp_path):
    cli = os.environ.get("SOFTSCULPT_CLI")
    if not cli:
        pytest.skip("SOFTSCULPT_CLI not set")
    grid = tmp_path / "grid.toml"
    grid.write_text('stiffness = [80.0, 120.0]\ngas.nrt = [30.0]\n')  # a dotted key, unquoted
    env = {**os.environ, "SOFTSCULPT_PYTHON": sys.executable}
    r = subprocess.run([cli, "sweep", str(SCENE), "--grid", str(grid), "--workers", "0", "--out", str(tmp_path / "o"), "--frames", "3"],
                       capture_output=True, text=True, env=env)
    assert r.returncode == 0, r.stderr
    assert "2 runs succeeded, 0 failed" in r.stderr
    table = pd.read_csv(tmp_path / "o" / "sweep.csv")
    assert list(table["stiffness"]) == [80.0, 120.0]
    assert sorted(os.listdir(tmp_path / "o" / "run_0001" / "frames")) == [f"{n}_{i:04d}.obj" for n in ("ball", "sphere") for i in range(3)]
    bad = subprocess.run([cli, "sweep", str(SCENE), "--grid", str(tmp_path / "none.toml"), "--out", str(tmp_path / "p")], capture_output=True, text=True, env=env)
    assert bad.returncode == 1 and bad.stderr.startswith("error:") and len(bad.stderr.strip().splitlines()) == 1


def test_a_scheduler_address_runs_the_sweep_on_that_cluster(client):
    table = softsculpt.sweep(SCENE, {"stiffness": [100.0, 150.0]}, client=client.scheduler.address)
    assert list(table["error"].isna()) == [True, True]


def test_array_values_expand_and_a_tuple_is_one_vector_value():
    rows = rows_of({"stiffness": np.linspace(50.0, 200.0, 4), "wind": (1.0, 0.0, 0.0)})
    assert [r["stiffness"] for r in rows] == [50.0, 100.0, 150.0, 200.0]
    assert all(r["wind"] == (1.0, 0.0, 0.0) for r in rows)
    table = softsculpt.sweep(SCENE, {"stiffness": np.array([80.0, 120.0]), "wind": (0.5, 0.0, 0.0)}, workers=0)
    assert table["error"].isna().all() and list(table["stiffness"]) == [80.0, 120.0]


def test_bad_keys_an_empty_grid_and_too_many_workers_fail_before_any_run(tmp_path):
    for grid, says in [({"duration": [1.0]}, "scene file"), ({"nobody:stiffness": [1.0]}, "no body 'nobody'"),
                       ({"ball:dt": [0.001]}, "world parameter"), ({"stiffness": []}, "no runs")]:
        with pytest.raises(ValueError, match=says):
            softsculpt.sweep(SCENE, grid, workers=0, out=tmp_path / "never")
        assert not (tmp_path / "never").exists()
    with pytest.raises(ValueError, match="processes at once"):
        softsculpt.sweep(SCENE, {"stiffness": [1.0]}, workers=10_000)


def test_a_failed_run_keeps_its_statistics_and_outputs_are_not_mixed(tmp_path):
    table = softsculpt.sweep(SCENE, [{"dt": 0.01}], workers=0, out=tmp_path)
    assert table["error"][0].startswith("SimulationError")
    stats = pd.read_parquet(tmp_path / "run_0000" / "stats.parquet")
    assert stats["step"].min() == 0 and len(stats) >= 2  # the rows up to the failure
    assert pd.read_parquet(tmp_path / "sweep.parquet")["error"][0] == table["error"][0]
    with pytest.raises(ValueError, match="earlier sweep"):
        softsculpt.sweep(SCENE, [{"dt": 0.001}], workers=0, out=tmp_path)
    softsculpt.sweep(SCENE, [{"dt": 0.001}], workers=0, out=tmp_path, overwrite=True)
    assert pd.read_parquet(tmp_path / "sweep.parquet")["error"].isna().all()
    (tmp_path / "notes.txt").write_text("mine")
    with pytest.raises(ValueError, match="other files"):
        softsculpt.sweep(SCENE, [{"dt": 0.001}], workers=0, out=tmp_path, overwrite=True)
    assert (tmp_path / "notes.txt").read_text() == "mine"
