"""Frames drawn through Python are `rolypoly render`'s frames: the same
renderer, settings and camera give the same pixels on the same adapter
(lavapipe where there is no GPU; no adapter is a loud failure)."""

import numpy as np
import pytest

import rolypoly
from conftest import SCENES, read_png, run_bin


def program_frame(tmp_path, scene_args, seed, time, size, *flags):
    out = tmp_path / "program.png"
    run_bin(*scene_args, "--seed", str(seed), "render", "--time", str(time),
            "--size", f"{size[0]}x{size[1]}", "--out", str(out), *flags)
    return read_png(out)


def python_frame(scene, seed, time, size, fireball=False, engine=None, **options):
    world = rolypoly.World(scene, seed=seed, engine=engine)
    if fireball:
        world.launch_fireball()
    world.step(world.steps_for(time))
    return rolypoly.render(world, size=size, **options)


CASES = [
    # scene file, overrides and flags, seed, time, size, render options, program flags
    (None, None, [], 2, 0.5, (192, 108), {}, []),
    ("tumbler-crowd.toml", None, [], 5, 0.75, (160, 120),
     {"quality": "low", "camera": ((2.0, 2.5, 5.0), (0.0, 0.5, 0.0))},
     ["--quality", "low", "--camera", "2,2.5,5,0,0.5,0"]),
    (None, {"balls.count": 200}, ["--balls", "200"], 3, 0.4, (128, 96),
     {"show": ["velocities", "com", "rest"], "quality": "medium"},
     ["--show", "velocities,com,rest", "--quality", "medium"]),
    # The impacts of the last step marked, as the program marks them.
    (None, {"balls.count": 300}, ["--balls", "300"], 6, 1.0, (200, 112),
     {"show": "contacts,impulses"}, ["--show", "contacts,impulses"]),
    # A view of one of the frame's passes, as the program draws it.
    (None, None, [], 3, 0.5, (160, 90), {"view": "normals"}, ["--view", "normals"]),
    (None, None, [], 4, 0.5, (160, 90), {"view": "specular"}, ["--view", "specular"]),
]


@pytest.mark.parametrize("scene_file, overrides, args, seed, time, size, options, flags", CASES)
def test_a_frame_is_the_programs_pixel_for_pixel(tmp_path, scene_file, overrides, args, seed, time, size, options, flags):
    if scene_file is None:
        scene = rolypoly.Scene.default(overrides)
    else:
        scene = rolypoly.Scene.load(SCENES / scene_file, overrides)
        args = ["--scene", str(SCENES / scene_file), *args]
    ours = python_frame(scene, seed, time, size, **options)
    theirs = program_frame(tmp_path, args, seed, time, size, *flags)
    assert ours.shape == (size[1], size[0], 4) and ours.dtype == np.uint8
    assert ours.std() > 5, "a picture, not a blank"
    assert np.array_equal(ours, theirs)


def test_a_frame_with_the_fireball_flying(tmp_path):
    ours = python_frame(None, 4, 0.3, (160, 90), fireball=True)
    theirs = program_frame(tmp_path, [], 4, 0.3, (160, 90), "--fireball")
    assert np.array_equal(ours, theirs)
    # Not the same frame as without it: the comparison above sees the fireball.
    assert not np.array_equal(ours, python_frame(None, 4, 0.3, (160, 90)))


@pytest.mark.parametrize("seed", [1, 2])
def test_the_last_steps_impacts_are_marked(seed):
    world = rolypoly.World(seed=seed)
    world.step(world.steps_for(1.0))
    plain = rolypoly.render(world, size=(320, 180)).astype(int)
    marked = rolypoly.render(world, size=(320, 180), show=["contacts", "impulses"]).astype(int)
    changed = (np.abs(marked - plain)[..., :3].max(axis=2) > 16).mean()
    assert changed > 0.005, f"{changed:.2%} of the pixels marked"


def test_frames_drawn_again_are_the_same_and_follow_the_world():
    world = rolypoly.World(seed=1)
    first = rolypoly.render(world, size=(96, 54))
    assert np.array_equal(first, rolypoly.render(world, size=(96, 54)))
    world.step(60)
    assert not np.array_equal(first, rolypoly.render(world, size=(96, 54)))


def test_the_gpu_engine_is_drawn_too():
    world = rolypoly.World(rolypoly.Scene.default({"balls.count": 100}), seed=1, engine="gpu")
    world.step(30)
    frame = rolypoly.render(world, size=(96, 54))
    assert frame.shape == (54, 96, 4) and frame.std() > 5


def test_the_overview_camera_is_the_default():
    world = rolypoly.World(seed=1)
    eye, target = rolypoly.overview_camera(world)
    assert eye[2] > world.room[1][2] and target[2] < eye[2]
    assert np.array_equal(rolypoly.render(world, size=(64, 36)),
                          rolypoly.render(world, size=(64, 36), camera=(eye, target)))


def test_the_frame_views_are_listed_and_each_draws_another_picture():
    views = rolypoly.frame_views()
    names = [name for name, _ in views]
    assert names[0] == "final" and {"normals", "shadow-cube", "msaa-edges"} <= set(names)
    assert all(about for _, about in views)
    world = rolypoly.World(seed=1)
    world.step(world.steps_for(0.3))
    final = rolypoly.render(world, size=(96, 54))
    assert np.array_equal(final, rolypoly.render(world, size=(96, 54), view="final"))
    # The floor's normal is +y: the normals view's floor is (128, 255, 128).
    normals = rolypoly.render(world, size=(96, 54), view="normals").astype(int)
    assert abs(normals[50, 48, :3] - [128, 255, 128]).max() <= 3, normals[50, 48]
    assert not np.array_equal(final, normals)


@pytest.mark.parametrize("options, needle", [
    ({"size": (0, 10)}, "size = (0, 10) is out of range"),
    ({"size": (9000, 10)}, "each side 1 ..= 8192"),
    ({"quality": "ultra"}, "not a quality level: use one of high, medium, low, auto"),
    ({"show": ["nope"]}, "`nope` is not a debug view"),
    ({"show": 3}, "show: give a list"),
    ({"camera": (1, 2, 3)}, "camera: give (eye, target)"),
    ({"view": "nosuch"}, "no frame view is called 'nosuch'; the views are: final, albedo"),
    ({"camera": ((0, 1, 5), (0, 1, 5))}, "the same point"),
    ({"camera": ((0, float("nan"), 5), (0, 1, 0))}, "must be finite"),
])
def test_bad_render_arguments_are_value_errors(options, needle):
    world = rolypoly.World()
    with pytest.raises(ValueError) as caught:
        rolypoly.render(world, **options)
    assert needle in str(caught.value)


@pytest.mark.parametrize("out, fps, seconds", [("frames/", 10, 0.3), ("clip.gif", 12, 0.25)])
def test_a_clip_is_the_programs_byte_for_byte(tmp_path, out, fps, seconds):
    ours, theirs = tmp_path / "ours", tmp_path / "theirs"
    ours.mkdir(), theirs.mkdir()
    run_bin("--seed", "3", "record", "--seconds", str(seconds), "--fps", str(fps),
            "--size", "96x54", "--out", str(theirs / out))
    world = rolypoly.World(seed=3)
    count = rolypoly.record(world, str(ours / out), seconds=seconds, fps=fps, size=(96, 54))
    assert count == round(seconds * fps)
    assert world.steps == world.steps_for((count - 1) / fps)
    theirs_files = sorted(p.relative_to(theirs) for p in theirs.rglob("*") if p.is_file())
    ours_files = sorted(p.relative_to(ours) for p in ours.rglob("*") if p.is_file())
    assert ours_files == theirs_files and ours_files
    for name in ours_files:
        assert (ours / name).read_bytes() == (theirs / name).read_bytes(), name


def test_bad_clip_arguments_are_value_errors(tmp_path):
    world = rolypoly.World()
    for kwargs, needle in [
        ({"path": tmp_path / "x.avi"}, "a clip is an animated GIF"),
        ({"path": tmp_path / "x.gif", "fps": 0}, "fps = 0 is out of range"),
        ({"path": tmp_path / "x.gif", "seconds": 0.0}, "seconds = 0 is out of range"),
        ({"path": tmp_path / "x.gif", "size": (0, 1)}, "is out of range"),
    ]:
        with pytest.raises(ValueError, match=needle):
            rolypoly.record(world, **kwargs)
    assert world.steps == 0
