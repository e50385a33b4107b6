"""The sound from Python: the program's own samples, as a NumPy array."""

import wave

import numpy as np
import pytest

import rolypoly
from conftest import run_bin


def pcm(frames: np.ndarray) -> np.ndarray:
    """Float samples as the program writes them to a WAV: 16-bit, rounded
    half away from zero."""
    y = frames.astype(np.float32) * np.float32(32767.0)
    return (np.sign(y) * np.floor(np.abs(y) + np.float32(0.5))).clip(-32767, 32767).astype(np.int16)


def read_wav(path) -> np.ndarray:
    with wave.open(str(path)) as w:
        assert (w.getnchannels(), w.getframerate(), w.getsampwidth()) == (2, 48000, 2)
        return np.frombuffer(w.readframes(w.getnframes()), dtype="<i2").reshape(-1, 2)


@pytest.mark.parametrize("seed", [2, 6])
def test_the_sound_is_the_programs(tmp_path, seed):
    out = tmp_path / "run.wav"
    run_bin("sound", "--seconds", "0.75", "--seed", str(seed), "--fireball", "--out", str(out))
    world = rolypoly.World(seed=seed)
    world.launch_fireball()
    frames = rolypoly.sound(world, 0.75)
    assert frames.shape == (36000, 2) and frames.dtype == np.float32
    assert np.abs(frames).max() <= 0.891 + 1e-6
    assert np.abs(frames).max() > 0.001, "the room is heard"
    assert np.array_equal(pcm(frames), read_wav(out))
    assert abs(world.time - 0.75) < 1e-9, "the world stepped on"


@pytest.mark.parametrize("seed", [2, 6])
def test_the_gpu_engines_balls_are_heard_as_the_programs(tmp_path, seed):
    out = tmp_path / "gpu.wav"
    run_bin("--engine", "gpu", "sound", "--seconds", "0.75", "--seed", str(seed), "--out", str(out))
    frames = rolypoly.sound(rolypoly.World(seed=seed, engine="gpu"), 0.75)
    assert frames.shape == (36000, 2)
    assert np.abs(frames).max() > 0.001, "the balls are heard"
    assert np.array_equal(pcm(frames), read_wav(out))


def test_sound_keys_and_bad_arguments():
    quiet = rolypoly.World(rolypoly.Scene.default({"sound.enabled": False}))
    assert not rolypoly.sound(quiet, 0.2).any()
    world = rolypoly.World()
    with pytest.raises(ValueError, match="seconds"):
        rolypoly.sound(world, 0.0)
    with pytest.raises(ValueError, match="camera"):
        rolypoly.sound(world, 0.1, camera=((0, 1, 2), (0, 1, 2)))
    with pytest.raises(ValueError, match="sound.balls"):
        rolypoly.Scene.default({"sound.balls": "cheese"})


def test_a_camera_on_the_other_side_swaps_the_channels():
    # A ball dropped by the left wall (x < 0): louder on the left from the
    # overview, on the right from a camera looking the other way.
    scene = rolypoly.Scene.default({"balls.count": 0})
    heard = []
    for camera in [((0, 1.5, 3.5), (0, 1.5, 0)), ((0, 1.5, -3.5), (0, 1.5, 0))]:
        world = rolypoly.World(scene)
        world.throw_ball((-3.0, 1.5, 0.0), (0.0, -2.0, 0.0))
        frames = rolypoly.sound(world, 1.0, camera=camera).astype(np.float64)
        heard.append((frames**2).sum(axis=0))
    (left_a, right_a), (left_b, right_b) = heard
    assert left_a > 4 * right_a and right_b > 4 * left_b
