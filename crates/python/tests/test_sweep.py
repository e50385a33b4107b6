"""Work that travels: scenes and events pickle, and a sweep runs on any
executor (a process pool, Dask's) with the same bits as in-process, each
failure in its own row."""

import hashlib
import os
import pickle
import re
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

import pytest

import rolypoly
from conftest import REPO, SCENES


def test_the_version_is_the_workspaces():
    text = (REPO / "Cargo.toml").read_text()
    version = re.search(r'^version = "([^"]+)"', text, re.M).group(1)
    assert rolypoly.__version__ == version


@pytest.mark.parametrize(
    "make",
    [
        lambda: rolypoly.Scene.default(),
        lambda: rolypoly.Scene.default({"balls.count": 12, "balls.friction": 0.7, "gravity": 3.5}),
        lambda: rolypoly.Scene.load(SCENES / "newtons-cradle.toml"),
        lambda: rolypoly.Scene.load(SCENES / "billiards-break.toml", {"balls.restitution": 0.5}),
    ],
)
def test_a_pickled_scene_is_the_same_scene_and_makes_the_same_world(make):
    scene = make()
    again = pickle.loads(pickle.dumps(scene))
    assert again == scene
    assert again.name == scene.name
    assert again.to_toml() == scene.to_toml()
    a, b = rolypoly.World(scene, seed=5), rolypoly.World(again, seed=5)
    a.step(90)
    b.step(90)
    assert a.balls.positions.tobytes() == b.balls.positions.tobytes()
    assert a.balls.velocities.tobytes() == b.balls.velocities.tobytes()


def test_events_pickle_with_every_field():
    world = rolypoly.World(rolypoly.Scene.default({"balls.count": 60}), seed=3)
    world.launch_fireball()
    world.step(240)
    events = world.events()
    kinds = {e.kind for e in events}
    assert {"ball_surface", "ball_ball"} <= kinds, kinds
    again = pickle.loads(pickle.dumps(events))
    assert again == events
    assert [e.to_dict() for e in again] == [e.to_dict() for e in events]


def trace_hash(world):
    """The SHA-256 of the run's trace over 0.5 s: the run, bit for bit."""
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "run.jsonl")
        world.write_trace(path, steps=60, every=6)
        with open(path, "rb") as f:
            return hashlib.sha256(f.read()).hexdigest()


@pytest.mark.parametrize("count, seed, steps", [(30, 2, 150), (400, 5, 90), (1500, 9, 200)])
def test_a_snapshot_pickles_and_a_world_of_the_scene_steps_on_from_it_to_the_same_bits(count, seed, steps):
    scene = rolypoly.Scene.default({"balls.count": count})
    world = rolypoly.World(scene, seed=seed)
    world.launch_fireball()
    world.step(steps)
    snap = world.snapshot()
    data = pickle.dumps(snap)
    again = pickle.loads(data)
    assert (again.steps, again.time, again.seed, again.engine) == (snap.steps, snap.time, seed, "cpu")
    assert again.to_bytes() == snap.to_bytes()
    assert rolypoly.Snapshot.from_bytes(snap.to_bytes()).to_bytes() == snap.to_bytes()
    # A world made elsewhere, of another seed, takes it on.
    other = rolypoly.World(seed=seed + 40)
    other.restore(again)
    assert other.seed == seed and other.scene == scene and other.steps == steps
    assert [e.to_dict() for e in other.events()] == [e.to_dict() for e in world.events()]
    assert trace_hash(other) == trace_hash(world)


@pytest.mark.parametrize("count, seed", [(30, 3), (700, 6)])
def test_a_world_pickles_as_scene_seed_and_snapshot_and_steps_on_to_the_same_bits(count, seed):
    world = rolypoly.World(rolypoly.Scene.default({"balls.count": count, "balls.friction": 0.4}), seed=seed)
    world.launch_fireball()
    world.step(120)
    again = pickle.loads(pickle.dumps(world))
    assert (again.seed, again.steps, again.engine) == (seed, 120, "cpu")
    assert again.scene == world.scene and again.scene.name == world.scene.name
    assert again.balls.positions.tobytes() == world.balls.positions.tobytes()
    assert trace_hash(again) == trace_hash(world)


def test_a_world_sent_to_another_process_steps_on_there_to_the_same_bits():
    from concurrent.futures import ProcessPoolExecutor

    world = rolypoly.World(rolypoly.Scene.default({"balls.count": 200}), seed=4)
    world.step(100)
    with ProcessPoolExecutor(max_workers=1) as pool:
        there = pool.submit(trace_hash, world).result()
    assert there == trace_hash(world)


def test_a_snapshot_of_the_gpu_engine_pickles_and_steps_on_to_the_same_bits():
    scene = rolypoly.Scene.default({"balls.count": 500})
    world = rolypoly.World(scene, seed=2, engine="gpu")
    world.launch_fireball()
    world.step(60)
    snap = pickle.loads(pickle.dumps(world.snapshot()))
    assert snap.engine == "gpu"
    other = rolypoly.World(scene, seed=3, engine="gpu")
    other.restore(snap)
    world.step(90)
    other.step(90)
    assert other.balls.positions.tobytes() == world.balls.positions.tobytes()
    assert other.balls.velocities.tobytes() == world.balls.velocities.tobytes()
    moved = pickle.loads(pickle.dumps(world))
    assert moved.engine == "gpu"
    assert trace_hash(moved) == trace_hash(world)
    with pytest.raises(ValueError, match="on the gpu engine cannot be put back into a world on the cpu engine"):
        rolypoly.World(scene).restore(snap)


def test_bytes_that_are_no_snapshot_are_refused_by_name():
    world = rolypoly.World(seed=1)
    world.step(10)
    data = world.snapshot().to_bytes()
    with pytest.raises(ValueError, match="not a rolypoly snapshot"):
        rolypoly.Snapshot.from_bytes(b"GIF89a and so on")
    with pytest.raises(ValueError, match="damaged or cut short"):
        rolypoly.Snapshot.from_bytes(data[: len(data) // 2])
    with pytest.raises(ValueError, match="rolypoly 0.0.1"):
        version = rolypoly.__version__.encode()
        rolypoly.Snapshot.from_bytes(data.replace(bytes([len(version)]) + version, b"\x050.0.1", 1))


GRID = {"balls.count": [8, 20], "balls.restitution": [0.4]}
SEEDS = [1, 7]


def rows_of(table):
    """The sweep's rows as dicts, whether pandas made a table of them or not."""
    return table.to_dict("records") if hasattr(table, "to_dict") else list(table)


def test_a_sweep_runs_every_combination_with_every_seed_in_order():
    rows = rows_of(rolypoly.sweep(trace_hash, rolypoly.Scene.default(), GRID, SEEDS))
    assert [(r["balls.count"], r["balls.restitution"], r["seed"]) for r in rows] == [
        (8, 0.4, 1), (8, 0.4, 7), (20, 0.4, 1), (20, 0.4, 7)
    ]
    assert all(r["error"] is None for r in rows)
    # Each row is the run made by hand, bit for bit.
    for r in rows:
        scene = rolypoly.Scene.default({"balls.count": r["balls.count"], "balls.restitution": 0.4})
        assert r["result"] == trace_hash(rolypoly.World(scene, seed=r["seed"]))
    # Other seeds and sizes, other runs.
    assert len({r["result"] for r in rows}) == 4


def test_a_failing_run_is_its_rows_error_and_the_others_finish():
    grid = {"balls.count": [6, -3, 9]}
    rows = rows_of(rolypoly.sweep(trace_hash, rolypoly.Scene.default(), grid, [2], executor=ThreadPoolExecutor(2)))
    assert [r["balls.count"] for r in rows] == [6, -3, 9]
    bad = rows[1]
    assert isinstance(bad["error"], ValueError), bad
    assert "balls.count" in str(bad["error"])
    assert bad["result"] is None
    for good in (rows[0], rows[2]):
        assert good["error"] is None and len(good["result"]) == 64


def test_a_sweep_on_a_dask_cluster_is_bit_for_bit_the_serial_one():
    distributed = pytest.importorskip("distributed")
    import cloudpickle

    # The workers import rolypoly; this module's functions travel by value.
    cloudpickle.register_pickle_by_value(sys.modules[__name__])
    scene = rolypoly.Scene.default({"balls.friction": 0.3})
    with ThreadPoolExecutor(max_workers=1) as serial:
        expected = rows_of(rolypoly.sweep(trace_hash, scene, GRID, SEEDS, executor=serial))
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            got = rows_of(rolypoly.sweep(trace_hash, scene, GRID, SEEDS, executor=client.get_executor()))
            workers = client.run(os.getpid)
    assert len(workers) == 2 and os.getpid() not in workers.values()
    assert [r["result"] for r in got] == [r["result"] for r in expected]
    assert all(r["error"] is None for r in got)
