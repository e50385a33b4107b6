"""A trace written through Python is the program's trace, byte for byte
(P10, A3): the same scene and seed, through `World.write_trace` and
through `rolypoly simulate --trace`."""

import pytest

import rolypoly
from conftest import SCENES, run_bin


def python_trace(tmp_path, scene, seed, steps, every, fireball=False, engine=None):
    world = rolypoly.World(scene, seed=seed, engine=engine)
    if fireball:
        world.launch_fireball()
    out = tmp_path / "python.jsonl"
    world.write_trace(out, steps, every)
    return out.read_bytes()


def program_trace(tmp_path, args, seed, steps, every, fireball=False):
    out = tmp_path / "program.jsonl"
    flags = ["--fireball"] if fireball else []
    run_bin(*args, "--seed", str(seed), "simulate", "--steps", str(steps),
            "--every", str(every), "--trace", str(out), *flags)
    return out.read_bytes()


@pytest.mark.parametrize(
    "scene_file, overrides, args, seed, steps, every, fireball",
    [
        (None, None, [], 1, 240, 1, False),
        (None, None, [], 7, 300, 13, True),
        (None, {"balls.count": 120, "gravity": 4.5}, ["--balls", "120", "--gravity", "4.5"], 3, 200, 5, False),
        ("newtons-cradle.toml", None, [], 2, 400, 25, False),
        ("elastic-gas.toml", {"balls.count": 150}, ["--balls", "150"], 11, 150, 10, True),
        ("tumbler-crowd.toml", None, [], 5, 120, 40, False),
    ],
)
def test_trace_is_the_programs_byte_for_byte(tmp_path, scene_file, overrides, args, seed, steps, every, fireball):
    if scene_file is None:
        scene = rolypoly.Scene.default(overrides)
    else:
        scene = rolypoly.Scene.load(SCENES / scene_file, overrides)
        args = ["--scene", str(SCENES / scene_file), *args]
    ours = python_trace(tmp_path, scene, seed, steps, every, fireball)
    theirs = program_trace(tmp_path, args, seed, steps, every, fireball)
    assert ours.count(b"\n") == theirs.count(b"\n") > 2
    assert ours == theirs


def test_a_different_seed_gives_a_different_trace(tmp_path):
    # The comparison above could not fail if seeds were ignored.
    a = python_trace(tmp_path, None, 1, 30, 30)
    b = python_trace(tmp_path, None, 2, 30, 30)
    assert a != b


def test_steps_taken_by_step_and_by_the_trace_agree(tmp_path):
    stepped = rolypoly.World(seed=4)
    stepped.step(90)
    traced = rolypoly.World(seed=4)
    traced.write_trace(tmp_path / "t.jsonl", 90, 90)
    assert traced.steps == stepped.steps == 90
    assert (traced.balls.positions == stepped.balls.positions).all()
    assert (traced.tumblers.orientations == stepped.tumblers.orientations).all()


def test_the_gpu_engine_traces_as_the_program_does(tmp_path):
    scene = rolypoly.Scene.default({"balls.count": 300})
    ours = python_trace(tmp_path, scene, 1, 20, 10, engine="gpu")
    theirs = program_trace(tmp_path, ["--balls", "300", "--engine", "gpu"], 1, 20, 10)
    assert ours == theirs


def test_a_trace_into_a_missing_folder_is_an_os_error(tmp_path):
    world = rolypoly.World()
    with pytest.raises(FileNotFoundError, match="cannot write trace to .*missing"):
        world.write_trace(tmp_path / "missing" / "t.jsonl", 10)
    with pytest.raises(ValueError, match="every = 0"):
        world.write_trace(tmp_path / "t.jsonl", 10, every=0)
    with pytest.raises(ValueError, match="steps = -1"):
        world.write_trace(tmp_path / "t.jsonl", -1)
