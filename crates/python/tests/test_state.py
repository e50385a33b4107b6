"""The state as NumPy arrays (shapes, dtypes, copies), the checked setters
refusing bad input with a message that names the ball, energy, events,
snapshots, reprs and the GIL released while stepping."""

import sys
import threading
import time

import numpy as np
import pytest

import rolypoly
from conftest import SCENES


@pytest.fixture
def world():
    w = rolypoly.World(seed=1)
    w.step(240)
    return w


SCENES_AND_COUNTS = [
    (None, 30, 5),
    ({"balls.count": 0, "tumblers.placement": []}, 0, 0),
    ({"balls.count": 1, "tumblers.placement": [{"x": 0, "z": 0}]}, 1, 1),
    ({"balls.count": 777}, 777, 5),
]


@pytest.mark.parametrize("overrides, n, t", SCENES_AND_COUNTS)
def test_every_array_has_its_documented_shape_and_dtype(overrides, n, t):
    w = rolypoly.World(rolypoly.Scene.default(overrides), seed=3)
    w.step(3)
    b, tu = w.balls, w.tumblers
    expected = {
        "positions": ((n, 3), np.float64), "velocities": ((n, 3), np.float64),
        "spins": ((n, 3), np.float64), "radii": ((n,), np.float64),
        "masses": ((n,), np.float64), "colors": ((n, 3), np.float64), "alive": ((n,), np.bool_),
    }
    for name, (shape, dtype) in expected.items():
        a = getattr(b, name)
        assert isinstance(a, np.ndarray) and a.shape == shape and a.dtype == dtype, name
        assert a.flags.c_contiguous and a.flags.writeable, name
    expected = {
        "positions": ((t, 3), np.float64), "orientations": ((t, 4), np.float64),
        "velocities": ((t, 3), np.float64), "angular_velocities": ((t, 3), np.float64),
        "bottom_centers": ((t, 3), np.float64), "tilts": ((t,), np.float64), "sliding": ((t,), np.bool_),
    }
    for name, (shape, dtype) in expected.items():
        a = getattr(tu, name)
        assert isinstance(a, np.ndarray) and a.shape == shape and a.dtype == dtype, name
    assert len(b) == n and len(tu) == t
    assert len(b.tints) == n
    if t:
        # Quaternions are (x, y, z, w) and of unit length.
        assert np.allclose(np.linalg.norm(tu.orientations, axis=1), 1.0)


def test_arrays_are_copies(world):
    p = world.balls.positions
    p[:] = 0.0
    assert not (world.balls.positions == 0.0).all()


def test_the_state_follows_the_scene(world):
    scene = world.scene
    assert np.all(world.balls.radii == scene.get("balls.radius"))
    assert np.all(world.balls.masses == scene.get("balls.mass"))
    lo, hi = np.array(world.room[0]), np.array(world.room[1])
    r = world.balls.radii[:, None]
    assert np.all(world.balls.positions >= lo + r - 1e-9)
    assert np.all(world.balls.positions <= hi - r + 1e-9)
    assert world.time == pytest.approx(240 * world.dt) and world.steps == 240
    assert world.steps_for(1.0) == 120 and world.steps_for(0.5 / 120) == 1


def test_positions_and_velocities_written_are_read_back(world):
    p, v = world.balls.positions, world.balls.velocities
    spins = world.balls.spins
    p[0] = [0.0, 2.0, 0.0]
    v[0] = [1.0, -2.0, 0.5]
    world.balls.positions = p
    world.balls.velocities = v.tolist()
    assert (world.balls.positions == p).all()
    assert (world.balls.velocities == v).all()
    # A ball moved keeps its spin.
    assert (world.balls.spins == spins).all()


def test_a_pile_read_and_written_back_whole_is_taken_as_it_is():
    w = rolypoly.World(rolypoly.Scene.load(SCENES / "heap.toml"), seed=2)
    w.step(360)
    before = w.balls.positions
    w.balls.positions = before
    w.balls.velocities = w.balls.velocities
    assert (w.balls.positions == before).all()


def refused(world, attribute, value, *needles):
    before = getattr(world.balls, attribute)
    with pytest.raises(ValueError) as caught:
        setattr(world.balls, attribute, value)
    message = str(caught.value)
    assert "\n" not in message
    for needle in needles:
        assert needle in message, message
    assert (getattr(world.balls, attribute) == before).all(), "a refused write changed nothing"
    return message


def test_a_ball_outside_the_room_is_refused_by_name(world):
    p = world.balls.positions
    p[7] = [0.0, 9.0, 0.0]
    refused(world, "positions", p, "ball 7", "inside the room", "with radius 0.12")
    p[7] = [3.95, 1.0, 0.0]
    refused(world, "positions", p, "ball 7", "inside the room")


def test_a_ball_in_another_or_in_a_tumbler_is_refused_by_name(world):
    p = world.balls.positions
    p[3] = p[4] + [0.1, 0.0, 0.0]
    refused(world, "positions", p, "ball 3", "overlaps ball 4")
    p = world.balls.positions
    p[5] = world.tumblers.bottom_centers[2]
    refused(world, "positions", p, "ball 5", "overlaps tumbler 2")


def test_many_balls_moved_are_checked_against_their_neighbours():
    w = rolypoly.World(rolypoly.Scene.default({"balls.count": 200, "tumblers.placement": []}), seed=5)
    # A grid of balls well apart, then one put into its neighbour.
    grid = np.array([[x, y, z] for x in np.linspace(-3.5, 3.5, 8)
                     for y in np.linspace(0.5, 3.5, 5) for z in np.linspace(-3.5, 3.5, 5)])
    w.balls.positions = grid
    assert (w.balls.positions == grid).all()
    moved = grid + [0.01, 0.0, 0.0]
    moved[150] = moved[151] - [0.0, 0.0, 0.2]
    refused(w, "positions", moved, "overlaps ball")
    touching = grid.copy()
    touching[150] = touching[151] - [0.0, 0.0, 2 * 0.12]
    w.balls.positions = touching


def test_bad_arrays_are_refused_with_the_shape_wanted(world):
    p = world.balls.positions
    refused(world, "positions", p[:5], "shape (30, 3)", "got shape (5, 3)")
    refused(world, "positions", p.ravel(), "shape (30, 3)", "got shape (90,)")
    refused(world, "positions", "up", "shape (30, 3)")
    refused(world, "positions", [[1, 2]], "got shape (1, 2)")
    p[2, 1] = np.nan
    refused(world, "positions", p, "ball 2", "not finite")


def test_bad_velocities_are_refused_by_name(world):
    v = world.balls.velocities
    v[9] = [200.0, 0.0, 0.0]
    refused(world, "velocities", v, "ball 9", "speed 200 m/s is out of range", "100")
    v[9] = [0.0, np.inf, 0.0]
    refused(world, "velocities", v, "ball 9", "not finite")


def test_a_ball_the_fireball_caught_cannot_be_moved():
    w = rolypoly.World(rolypoly.Scene.default({"balls.count": 1, "tumblers.placement": []}), seed=1)
    w.balls.positions = [[0.0, 1.0, 0.0]]
    w.balls.velocities = [[0.0, 0.0, 0.0]]
    w.launch_fireball((0.0, 1.0, 0.6), (0.0, 0.0, -1.0))
    for _ in range(200):
        w.step()
        if not w.balls.alive[0]:
            break
    assert not w.balls.alive[0]
    assert any(e.kind == "fireball_ball" and e.ball == 0 for e in w.events())
    refused(w, "positions", [[0.0, 1.0, 0.0]], "ball 0 is out of play")
    refused(w, "velocities", [[0.0, 1.0, 0.0]], "ball 0 is out of play")


def test_a_thrown_ball_is_checked_and_numbered(world):
    n = len(world.balls)
    assert world.throw_ball((0.0, 2.0, 0.0), (1.0, 0.0, 0.0)) == n
    assert len(world.balls) == n + 1
    assert world.balls.positions[n].tolist() == [0.0, 2.0, 0.0]
    with pytest.raises(ValueError, match="thrown ball at .* does not lie inside the room"):
        world.throw_ball((0.0, 5.0, 0.0), (0.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="speed .* out of range"):
        world.throw_ball((0.0, 2.0, 0.0), (0.0, 0.0, 101.0))
    with pytest.raises(ValueError, match="not finite"):
        world.throw_ball((0.0, np.nan, 0.0), (0.0, 0.0, 1.0))
    with pytest.raises(ValueError, match="three numbers"):
        world.throw_ball((0.0, 2.0), (0.0, 0.0, 1.0))
    assert len(world.balls) == n + 1


def test_the_fireball_is_launched_checked_and_removed(world):
    assert world.fireball is None
    world.launch_fireball()
    f = world.fireball
    assert f.speed == world.scene.get("fireball.speed")
    assert np.linalg.norm(f.velocity) == pytest.approx(f.speed)
    world.launch_fireball((0.0, 2.0, 0.0), (0.0, 0.0, -2.0))
    assert world.fireball.position == (0.0, 2.0, 0.0)
    assert world.fireball.velocity == pytest.approx((0.0, 0.0, -f.speed))
    with pytest.raises(ValueError, match="the fireball at .* does not lie inside the room"):
        world.launch_fireball((0.0, -1.0, 0.0), (1.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="the fireball at .* overlaps tumbler 0"):
        world.launch_fireball(tuple(world.tumblers.bottom_centers[0]), (1.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="points nowhere"):
        world.launch_fireball((0.0, 2.0, 0.0), (0.0, 0.0, 0.0))
    world.remove_fireball()
    assert world.fireball is None


def test_energy_is_the_physics_and_unpacks(world):
    energy = world.energy()
    kinetic, potential, total = energy
    assert total == kinetic + potential == energy.total
    b, g = world.balls, world.scene.gravity
    # Every body counts: the balls' share, from their own state, is part of it.
    balls_potential = (b.masses * g * b.positions[:, 1]).sum()
    assert 0 < balls_potential < potential


def test_events_come_once_with_the_colour_taken(world):
    events = world.events()
    assert events and world.events() == []
    kinds = {e.kind for e in events}
    assert "ball_surface" in kinds
    steps = [e.step for e in events]
    assert steps == sorted(steps) and 1 <= steps[0] and steps[-1] <= 240
    for e in events:
        d = e.to_dict()
        assert d["kind"] == e.kind and d["speed"] == e.speed > 0
        if e.kind == "ball_surface":
            assert e.surface in ("floor", "ceiling", "left", "right", "back", "front")
            assert e.color is not None and e.tumbler is None
        if e.kind == "ball_ball":
            assert e.a is not None and e.b is not None and e.color is None
    # The colour a ball shows is the colour of its last take.
    last = {}
    for e in events:
        if e.color is not None:
            last[e.ball] = e.color
    colors = world.balls.colors
    for ball, color in last.items():
        assert tuple(colors[ball]) == color


def test_a_snapshot_rewinds_bit_for_bit():
    w = rolypoly.World(rolypoly.Scene.default({"balls.count": 400}), seed=8)
    w.launch_fireball()
    w.step(100)
    w.events()
    snap = w.snapshot()
    assert snap.steps == 100
    w.step(150)
    first = (w.balls.positions, w.balls.velocities, w.tumblers.orientations, w.energy().total, w.events())
    w.restore(snap)
    assert w.steps == 100
    w.step(150)
    again = (w.balls.positions, w.balls.velocities, w.tumblers.orientations, w.energy().total, w.events())
    for a, b in zip(first[:3], again[:3]):
        assert a.tobytes() == b.tobytes()
    assert first[3] == again[3]
    assert [e.to_dict() for e in first[4]] == [e.to_dict() for e in again[4]]
    # Restored into another world, it steps on alike too.
    other = rolypoly.World(seed=99)
    other.restore(snap)
    other.step(150)
    assert other.balls.positions.tobytes() == first[0].tobytes()
    assert other.seed == 8 and other.scene == w.scene


@pytest.mark.parametrize("count, seed", [(300, 3), (1200, 4)])
def test_a_snapshot_on_the_gpu_engine_rewinds_bit_for_bit(count, seed):
    scene = rolypoly.Scene.default({"balls.count": count})
    w = rolypoly.World(scene, seed=seed, engine="gpu")
    w.launch_fireball()
    w.step(60)
    snap = w.snapshot()
    w.step(90)
    first = (w.balls.positions, w.balls.velocities, w.balls.alive, w.tumblers.orientations)
    w.restore(snap)
    assert w.steps == 60
    w.step(90)
    again = (w.balls.positions, w.balls.velocities, w.balls.alive, w.tumblers.orientations)
    for a, b in zip(first, again):
        assert a.tobytes() == b.tobytes()
    # Another world of the same scene takes it; another scene's refuses it.
    other = rolypoly.World(scene, seed=seed + 1, engine="gpu")
    other.restore(snap)
    other.step(90)
    assert other.balls.positions.tobytes() == first[0].tobytes()
    larger = rolypoly.World(rolypoly.Scene.default({"balls.count": count + 1}), seed=seed, engine="gpu")
    with pytest.raises(ValueError, match="another scene"):
        larger.restore(snap)
    assert larger.steps == 0


def test_a_snapshot_goes_back_only_to_its_own_engine():
    scene = rolypoly.Scene.default({"balls.count": 100})
    cpu, gpu = (rolypoly.World(scene, seed=1, engine=e) for e in ("cpu", "gpu"))
    with pytest.raises(ValueError, match="on the gpu engine cannot be put back into a world on the cpu engine"):
        cpu.restore(gpu.snapshot())
    with pytest.raises(ValueError, match="on the cpu engine cannot be put back into a world on the gpu engine"):
        gpu.restore(cpu.snapshot())


def test_the_gpu_engine_takes_checked_positions_and_velocities():
    w = rolypoly.World(rolypoly.Scene.default({"balls.count": 200}), seed=2, engine="gpu")
    w.step(30)
    p, v = w.balls.positions, w.balls.velocities
    # Somewhere high and clear of every ball.
    p[9] = [0.0, 3.5, 0.0]
    assert np.linalg.norm(np.delete(p, 9, axis=0) - p[9], axis=1).min() > 0.5
    v[9] = [1.5, 0.0, 0.0]
    w.balls.positions, w.balls.velocities = p, v
    # Held in single precision on the GPU.
    assert np.allclose(w.balls.positions[9], p[9], atol=1e-6)
    assert np.allclose(w.balls.velocities[9], v[9], atol=1e-6)
    w.step(1)
    assert w.balls.positions[9][0] == pytest.approx(1.5 * w.dt, abs=1e-5), "it flies from there"
    refused(w, "positions", np.where(np.arange(200)[:, None] == 4, [0.0, 9.0, 0.0], w.balls.positions),
            "ball 4", "inside the room")
    p = w.balls.positions
    p[3] = p[9] + [0.05, 0.0, 0.0]
    refused(w, "positions", p, "ball 3", "overlaps ball 9")
    v = w.balls.velocities
    v[2] = [np.nan, 0.0, 0.0]
    refused(w, "velocities", v, "ball 2")


def test_long_steps_show_a_progress_bar_where_tqdm_is(capsys):
    pytest.importorskip("tqdm")
    w = rolypoly.World(rolypoly.Scene.default({"balls.count": 50}), seed=1)
    w.step(120, progress=True)
    bar = capsys.readouterr().err
    assert "120/120" in bar and "step" in bar, bar
    assert w.steps == 120
    # Short steps print nothing: the bar waits a second before it shows.
    w.step(5)
    w.step(30, progress=False)
    assert capsys.readouterr().err == ""
    assert w.steps == 155


def test_without_tqdm_steps_run_barless_unless_a_bar_is_asked_for(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "tqdm", None)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    w = rolypoly.World(rolypoly.Scene.default({"balls.count": 20}), seed=2)
    w.step(40)
    assert w.steps == 40 and capsys.readouterr().err == ""
    with pytest.raises(ImportError, match="pip install tqdm"):
        w.step(10, progress=True)
    assert w.steps == 40, "refused before stepping"


def test_the_gil_is_released_while_stepping():
    # Fewer balls than the physics spreads over threads: the step keeps one
    # core, this thread the other.
    w = rolypoly.World(rolypoly.Scene.default({"balls.count": 1500}), seed=1)
    window = {}

    def step():
        window["start"] = time.perf_counter()
        w.step(600)
        window["end"] = time.perf_counter()

    ticks = []
    thread = threading.Thread(target=step)
    thread.start()
    while thread.is_alive():
        ticks.append(time.perf_counter())
    thread.join()
    start, end = window["start"], window["end"]
    assert end - start > 0.2, "the step must last long enough to tell"
    inside = [t for t in ticks if start < t < end]
    gaps = np.diff([start, *inside, end])
    # Held for the whole call, this thread would not run inside the window
    # at all; held between looks at Ctrl-C (every 50 ms), it would run only
    # in between. Released, it runs throughout, but for the odd moment the
    # system gives its core to another program.
    stalled = gaps[gaps > 0.02].sum()
    assert stalled < 0.25 * (end - start), f"this thread stood still {stalled:.3f} s of {end - start:.3f} s"
    assert len(inside) > 1000


def test_reading_a_world_another_thread_steps_is_an_error_not_a_crash():
    w = rolypoly.World(rolypoly.Scene.default({"balls.count": 3000}), seed=1)
    thread = threading.Thread(target=w.step, args=(300,))
    thread.start()
    errors = 0
    while thread.is_alive():
        try:
            w.balls.positions
        except RuntimeError as e:
            assert "borrow" in str(e)
            errors += 1
    thread.join()
    assert errors > 0
    assert w.steps == 300


def test_bad_arguments_are_value_errors():
    with pytest.raises(ValueError, match="seed = -1"):
        rolypoly.World(seed=-1)
    with pytest.raises(ValueError, match="not an engine"):
        rolypoly.World(engine="quantum")
    w = rolypoly.World()
    with pytest.raises(ValueError, match="cannot be negative"):
        w.step(-1)
    with pytest.raises(ValueError, match="seconds"):
        w.steps_for(-1.0)
    w.step(0)
    assert w.steps == 0


def test_reprs_say_what_a_world_holds(world):
    text = repr(world)
    assert "built-in default scene" in text and "seed 1" in text and "engine cpu" in text
    assert "30 balls" in text and "5 tumblers" in text and "step 240" in text
    assert "30 balls" in repr(world.balls) and "5 tumblers" in repr(world.tumblers)
    assert "balls.count" not in repr(world.scene) and "30 balls" in repr(world.scene)
    assert "kinetic" in repr(world.energy())
    world.launch_fireball()
    assert "Fireball" in repr(world.fireball)
    assert "step 240" in repr(world.snapshot())


def test_help_shows_the_docstrings():
    for thing in (rolypoly.World, rolypoly.World.step, rolypoly.Scene.default, rolypoly.render,
                  rolypoly.Balls, rolypoly.World.write_trace, rolypoly.World.events):
        assert thing.__doc__ and len(thing.__doc__) > 40, thing
    assert "(N, 3)" in rolypoly.Balls.positions.__doc__
    assert "(x, y, z, w)" in rolypoly.Tumblers.orientations.__doc__
