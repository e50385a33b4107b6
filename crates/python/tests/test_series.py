"""World.series against `simulate --series`: the same numbers, a DataFrame
where pandas is, and the physics the columns plot."""

import numpy as np
import pandas as pd
import pytest

import rolypoly
from conftest import SCENES, run_bin


@pytest.mark.parametrize("scene_file,seed,steps,every", [
    (None, 1, 40, 1),
    (None, 5, 33, 10),
    ("elastic-gas.toml", 2, 30, 7),
])
def test_the_series_is_the_programs_number_for_number(tmp_path, scene_file, seed, steps, every):
    out = tmp_path / "run.csv"
    args = ["simulate", "--steps", str(steps), "--seed", str(seed),
            "--series", str(out), "--series-every", str(every)]
    scene = rolypoly.Scene.default()
    if scene_file:
        args += ["--scene", str(SCENES / scene_file)]
        scene = rolypoly.Scene.load(SCENES / scene_file)
    run_bin(*args)
    program = pd.read_csv(out)
    series = rolypoly.World(scene, seed=seed).series(steps, every=every)
    assert list(series) == list(program.columns)
    for name, values in series.items():
        assert values.dtype == np.float64
        np.testing.assert_array_equal(values, program[name].to_numpy(dtype=np.float64), err_msg=name)


def test_a_frame_has_the_columns_and_a_row_a_sample():
    frame = rolypoly.World(seed=3).series(20, every=5, frame=True)
    assert isinstance(frame, pd.DataFrame)
    assert list(frame["step"]) == [0, 5, 10, 15, 20]
    assert [c for c in frame.columns if c.endswith("_tilt")] == [f"tumbler_{k}_tilt" for k in range(5)]
    parts = frame["kinetic_translational"] + frame["kinetic_rotational"] + frame["potential"]
    np.testing.assert_allclose(parts, frame["total"], rtol=1e-12)


def test_the_series_total_is_the_worlds_energy():
    world = rolypoly.World(seed=4)
    series = world.series(60)
    assert series["total"][-1] == pytest.approx(world.energy().total, rel=1e-12)
    assert np.all(np.diff(series["total"]) <= 1e-9 * series["total"][0])


@pytest.mark.parametrize("seed", [1, 6])
def test_the_momentum_moves_by_the_impulses_the_series_counts(seed):
    """Newton's second law from the columns alone: a step's change of the
    balls' momentum is the surfaces', tumblers', guard's and gravity's
    impulses of that step (the default room: balls landing on the floor and
    the tumblers)."""
    s = rolypoly.World(seed=seed).series(240)
    momentum = np.stack([s[f"momentum_{a}"] for a in "xyz"], axis=1)
    given = sum(np.stack([s[f"{k}_impulse_{a}"] for a in "xyz"], axis=1)
                for k in ("surface", "tumbler", "guard"))
    given[:, 1] += s["gravity_impulse_y"] + s["poured_momentum_y"]
    gap = np.diff(momentum, axis=0) - given[1:]
    scale = np.abs(given).max()
    assert scale > 0.1
    assert np.abs(gap).max() <= 1e-9 * scale
    assert np.abs(s["tumbler_impulse_x"]).max() > 0


@pytest.mark.parametrize("steps,every", [(-1, 1), (10, 0), (10, -2)])
def test_bad_lengths_are_value_errors(steps, every):
    with pytest.raises(ValueError):
        rolypoly.World().series(steps, every=every)


def test_a_world_shows_its_frame_as_png_and_a_scene_its_keys():
    world = rolypoly.World(seed=2)
    png = world._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    # The frame render() draws, as PNG.
    from conftest import read_png
    import tempfile, pathlib
    with tempfile.TemporaryDirectory() as folder:
        path = pathlib.Path(folder) / "frame.png"
        path.write_bytes(png)
        np.testing.assert_array_equal(read_png(path), rolypoly.render(world))
    html = rolypoly.Scene.default({"balls.count": 7, "gravity": 3.5})._repr_html_()
    assert html.startswith("<table>") and "<code>balls.count</code>" in html and "<code>7</code>" in html
    assert "<code>gravity</code>" in html and "3.5" in html


def test_a_clip_plays_inline_as_a_gif_and_saves(tmp_path):
    clip = rolypoly.clip(rolypoly.World(seed=1), seconds=0.4, fps=5, size=(64, 36))
    assert clip.frames == 2 and clip.gif[:6] == b"GIF89a"
    assert clip._repr_html_().startswith('<img src="data:image/gif;base64,')
    clip.save(tmp_path / "c.gif")
    assert (tmp_path / "c.gif").read_bytes() == clip.gif
