"""The Python package against the engine it binds: the same steps as the CLI, bit for bit;
snapshots and pickles that step identically; the table's checks as ValueError; arrays checked
before anything changes; and physics seen through the binding."""

import json
import os
import pickle
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import softsculpt
from softsculpt import SimulationError, World

DATA = Path(__file__).parent / "data"
SCENE = DATA / "drop.toml"


def cli() -> str:
    """The softsculpt command to compare with (SOFTSCULPT_CLI, else the workspace's build)."""
    path = os.environ.get("SOFTSCULPT_CLI")
    if path:
        return path
    root = Path(__file__).resolve().parents[3]
    for profile in ("debug", "release"):
        p = root / "target" / profile / "softsculpt"
        if p.exists():
            return str(p)
    pytest.skip("no softsculpt binary built (cargo build -p softsculpt-cli)")


def vertex_lines(obj_text: str) -> list:
    return [l for l in obj_text.splitlines() if l.startswith("v ")]


def test_a_scene_steps_bit_for_bit_like_softsculpt_run(tmp_path):
    # Same core, same arithmetic: equal to the last bit (OBJ and JSON print shortest
    # round-trip decimals, so equal text is equal doubles).
    subprocess.run([cli(), "run", str(SCENE), "--out", str(tmp_path / "out"), "--threads", "1"], check=True, capture_output=True)
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    w = World.from_scene(SCENE)
    w.threads = 1
    steps = w.run()
    assert steps == summary["steps"] == 300
    assert w.time == summary["time"]
    for i, name in enumerate(w.names):
        assert w.stats(i) == summary["bodies"][name]
        assert vertex_lines(w.obj(i)) == vertex_lines((tmp_path / "out" / f"{name}.obj").read_text())


def test_a_snapshot_round_trip_steps_identically():
    w = World.from_scene(SCENE)
    w.step(50)  # before the event at 0.1 s: it is pending in the snapshot
    copy = World.restore(w.snapshot())
    pickled = pickle.loads(pickle.dumps(w))
    for x in (w, copy, pickled):
        x.step(150)  # through the force event
    for i in range(2):
        ref = w.bodies[i]
        for other in (copy.bodies[i], pickled.bodies[i]):
            assert np.array_equal(ref.positions, other.positions)
            assert np.array_equal(ref.velocities, other.velocities)
    assert pickled.names == w.names and pickled.duration == w.duration


def test_bad_parameters_raise_value_error_with_the_cli_message(tmp_path):
    bad = tmp_path / "bad.toml"
    shutil.copy(DATA / "ball.obj", tmp_path / "ball.obj")
    bad.write_text(SCENE.read_text().replace("stiffness = 100.0       # N/m", "stiffness = -1.0"))
    r = subprocess.run([cli(), "run", str(bad), "--out", str(tmp_path / "out")], capture_output=True, text=True)
    assert r.returncode == 1
    cli_message = r.stderr.strip().removeprefix("error: ")
    with pytest.raises(ValueError) as e:
        World.from_scene(bad)
    assert str(e.value) == cli_message
    w = World.from_mesh("builtin:sphere")
    with pytest.raises(ValueError) as e:
        w.set_param("stiffness", -1.0)
    # The table's own check (the scene's validator words the same rule its own way: issue #39).
    assert str(e.value) == "stiffness: must be ≥ 0 N/m, got -1"
    assert w.param("stiffness") == 100.0  # unchanged
    with pytest.raises(ValueError, match="no such parameter"):
        w.set_param("stiffnes", 1.0)
    with pytest.raises(ValueError, match="one of"):
        w.set_param("integrator", "leapfrog")
    with pytest.raises(TypeError, match="stiffness"):
        w.set_param("stiffness", "stiff")
    with pytest.raises(ValueError, match="stiffness"):
        World.from_mesh("builtin:sphere", stiffness=-3.0)


def test_arrays_of_the_wrong_shape_or_with_nan_are_refused_and_change_nothing():
    w = World.from_mesh("builtin:sphere")
    b = w.bodies[0]
    before = b.positions
    for bad in (np.zeros((3, 3)), np.zeros((before.shape[0], 2)), before.ravel(), "nonsense"):
        with pytest.raises(ValueError):
            b.positions = bad
    nan = before.copy()
    nan[7, 1] = np.nan
    with pytest.raises(ValueError, match="row 7"):
        b.positions = nan
    inf = b.velocities
    inf[3, 0] = np.inf
    with pytest.raises(ValueError, match="row 3"):
        b.velocities = inf
    assert np.array_equal(b.positions, before)
    assert not b.velocities.any()
    with pytest.raises(ValueError, match="triangles"):
        World.from_mesh(before, [[0, 1, before.shape[0]]])


def test_a_translated_body_moves_its_centre_of_mass_by_the_translation():
    # Centre of mass Σ m x / Σ m: a shift s of every x shifts it by s, up to rounding of a
    # sum of ~642 terms of size ~1 (relative 1e-15 each): 1e-12 m.
    w = World.from_mesh("builtin:sphere")
    b = w.bodies[0]
    c0 = np.array(w.stats()["center_of_mass"])
    b.positions = b.positions + [0.5, 1.0, -2.0]
    c1 = np.array(w.stats()["center_of_mass"])
    assert np.allclose(c1 - c0, [0.5, 1.0, -2.0], atol=1e-12, rtol=0)


def test_momentum_changes_by_the_impulse_of_gravity_in_free_fall():
    # Springs, damping and gas are internal: they sum to zero over the body (Newton's third
    # law), so Σ m v changes by M g t exactly up to rounding: M = 1 kg, g = 9.81, t = 0.2 s
    # gives 1.962 kg·m/s; rounding of 200 sums of 642 terms: far below 1e-9.
    w = World.from_mesh("builtin:sphere", gravity=9.81, stiffness=300.0, gas_nrt=20.0)
    w.advance(0.2)
    p = w.stats()["momentum"]
    assert w.steps == 200
    assert p[1] == pytest.approx(-1.0 * 9.81 * 0.2, abs=1e-9)
    assert abs(p[0]) < 1e-9 and abs(p[2]) < 1e-9


def test_a_mesh_given_as_arrays_steps_as_the_same_mesh_read_from_a_file():
    a = World.from_mesh(DATA / "ball.obj", stiffness=200.0)
    b0 = a.bodies[0]
    b = World.from_mesh(b0.positions, b0.triangles, stiffness=200.0)
    a.step(100)
    b.step(100)
    assert np.array_equal(a.bodies[0].positions, b.bodies[0].positions)


def test_a_failed_step_raises_simulation_error_and_keeps_a_sound_world():
    # dt 0.05 s is ~100x the stable explicit step of a stiff sphere: it blows up or collapses.
    w = World.from_mesh("builtin:sphere", preset="stiff_rubber", dt=0.05, gravity=0.0)
    with pytest.raises(SimulationError) as e:
        w.step(16)
    assert "at " in str(e.value)
    assert w.steps == 0 and np.isfinite(w.bodies[0].positions).all()


def test_stats_and_params_carry_the_contract_keys():
    w = World.from_mesh("builtin:sphere")
    keys = ["step", "time", "volume", "pressure", "kinetic_energy", "elastic_energy", "gas_energy", "gravity_energy",
            "total_energy", "momentum", "center_of_mass", "max_speed", "solver_iterations", "plastic_dissipation"]
    assert sorted(w.stats()) == sorted(keys)
    ids = {p["id"] for p in softsculpt.parameters() if p["scope"] in ("world", "body")}
    assert set(w.params()) == ids
    assert w.params()["stiffness"] == w.param("stiffness")


def test_a_missing_or_unreadable_file_is_one_clear_error(tmp_path):
    with pytest.raises(FileNotFoundError, match="nope.obj"):
        World.from_mesh(tmp_path / "nope.obj")
    with pytest.raises(OSError, match="not a regular file"):
        World.from_mesh(tmp_path)
    with pytest.raises(ValueError, match="builtin:teapot"):
        World.from_mesh("builtin:teapot")


def test_more_threads_than_the_machine_runs_are_refused_as_the_cli_refuses_them():
    w = World.from_mesh("builtin:sphere")
    with pytest.raises(ValueError, match="threads at once"):
        w.threads = (os.cpu_count() or 1) + 1000
    w.threads = 1
    assert w.threads == 1


def test_a_simulation_error_pickles_as_itself():
    # Dask and multiprocessing carry exceptions by pickling them.
    e = pickle.loads(pickle.dumps(SimulationError("at 0.04 s: the body collapsed")))
    assert type(e) is SimulationError and str(e) == "at 0.04 s: the body collapsed"


def test_integer_fortran_and_strided_arrays_are_taken_as_positions():
    w = World.from_mesh("builtin:sphere")
    b = w.bodies[0]
    x = b.positions
    for a in (np.asfortranarray(x), np.round(x * 10).astype(np.int64)):
        b.positions = a
        assert np.array_equal(b.positions, np.asarray(a, dtype=np.float64))
    strided = np.zeros((x.shape[0], 6))
    strided[:, ::2] = x
    b.positions = strided[:, ::2]
    assert np.array_equal(b.positions, x)


def test_a_stiff_preset_alone_steps_implicitly_with_a_warning_as_the_cli_does():
    with pytest.warns(UserWarning, match="implicit integrator steps it"):
        w = World.from_mesh("builtin:sphere", preset="stiff_rubber")
    assert w.param("integrator") == "implicit"
    w.step(12)  # the explicit step collapsed here
    assert abs(w.bodies[0].volume / 4.1527 - 1) < 0.05
    assert World.from_mesh("builtin:sphere", preset="stiff_rubber", integrator="symplectic").param("integrator") == "symplectic"


def test_a_world_read_while_it_steps_in_another_thread_says_so():
    # Stepping releases the GIL; the world is then mutably borrowed: a read from another
    # thread is a RuntimeError, never a panic, and the step goes on. (200 steps of the
    # 40,962-vertex workload take ~0.4 s: the main thread gets to read in between.)
    import threading

    w = World.workload(6)
    w.threads = 1
    t = threading.Thread(target=w.step, args=(200,))
    refused = 0
    t.start()
    while t.is_alive():
        try:
            w.bodies[0].positions
        except RuntimeError as e:
            assert "stepping" in str(e)
            refused += 1
    t.join()
    assert refused > 0 and w.steps == 200
