"""Scenes through Python: the program's reader, checks and messages, with
overrides of any key; bad texts raise ValueError and never crash."""

import random
import re

import numpy as np
import pytest

import rolypoly
from conftest import SCENES


def message(text, overrides=None, name="test.toml"):
    with pytest.raises(ValueError) as caught:
        rolypoly.Scene.parse(text, overrides, name=name)
    text = str(caught.value)
    assert "\n" not in text
    return text


def test_the_default_scene_is_the_shipped_file():
    assert rolypoly.Scene.default() == rolypoly.Scene.load(SCENES / "default.toml")
    assert rolypoly.Scene.default() == rolypoly.Scene.parse("")
    assert rolypoly.Scene.default().ball_count == 30
    assert rolypoly.Scene.default().tumbler_count == 5


def test_overrides_set_the_scene_files_keys():
    scene = rolypoly.Scene.default({"balls.count": 2000, "balls.friction": 0.5,
                                    "room.size": (10, 5, 10), "light.intensity": 2})
    assert scene.ball_count == 2000 and scene.get("balls.count") == 2000
    assert scene.get("balls.friction") == 0.5
    assert scene.room_size == (10.0, 5.0, 10.0)
    assert scene.get("light.intensity") == 2.0
    # As a scene file saying the same.
    text = "[balls]\ncount = 2000\nfriction = 0.5\n[room]\nsize = [10, 5, 10]\n[light]\nintensity = 2\n"
    assert scene == rolypoly.Scene.parse(text)
    # Lists, tables and NumPy values too.
    scene = rolypoly.Scene.load(SCENES / "newtons-cradle.toml", {
        "balls.placement": [{"position": np.array([0.0, 1.0, 0.0])}],
        "balls.pour": {"rate": 10.0},
        "gravity": np.float32(2.5), "balls.count": np.int64(3),
    })
    assert scene.ball_count == 4 and scene.gravity == 2.5
    assert scene.get("balls.pour.rate") == 10.0
    # The file's own keys stay where not overridden.
    assert scene.get("balls.restitution") == 1.0


def test_overrides_are_the_command_lines_for_its_three_options():
    a = rolypoly.Scene.load(SCENES / "heap.toml", {"balls.count": 12, "gravity": 3.5, "solver.engine": "gpu"})
    assert a.ball_count == 12 and a.gravity == 3.5 and a.engine == "gpu"


def test_a_bad_override_names_itself():
    assert message("", {"balls.count": -1}) == \
        'overrides["balls.count"]: balls.count = -1 is out of range: allowed 0 ..= 1000000'
    assert message("", {"gravity": 1e308}) == \
        'overrides["gravity"]: gravity = 1e308 is out of range: allowed 0 ..= 100'
    assert message("", {"balls.friction": "x"}) == \
        'overrides["balls.friction"]: invalid type: string "x", expected a number'
    assert message("", {"balls.colour": 1}).startswith(
        'overrides["balls.colour"]: unknown key `balls.colour`, expected one of `count`')
    assert message("", {"render.quality": "ultra"}).endswith("expected one of high, medium, low, auto")
    assert message("", {"tumblers.placement": [{"x": 0, "z": 0, "angle": 3}]}).startswith(
        'overrides["tumblers.placement"]: unknown key `tumblers.placement.angle`')
    assert message("", {"balls.pour": {"rate": 10, "spout": [0, 9, 0]}}).startswith(
        'overrides["balls.pour"]: balls.pour.spout = [0, 9, 0] is out of range')
    assert "no place in a scene file" in message("", {"gravity": object()})
    assert "not a dotted key" in message("", {"balls..count": 1})
    assert "not a string" in message("", {3: 1})


def test_a_files_message_keeps_its_line_with_or_without_overrides():
    cases = [
        ("# comment\n[balls]\ncount = 3\nrestitution = 1.5\n",
         "test.toml:4: balls.restitution = 1.5 is out of range: allowed 0 ..= 1"),
        ("[[tumblers.placement]]\nx = 0\nz = 0\n\n[[tumblers.placement]]\nx = 1\nz = 9\n",
         "test.toml:7: tumblers.placement[1].z = 9 is out of range"),
        ("[[balls.placement]]\nposition = [0, 1, 0]\n\n[[balls.placement]]\nposition = [0.1, 1, 0]\n",
         "test.toml:5: balls.placement[1]: ball 1 at [0.1, 1, 0] overlaps ball 0"),
        ("[light]\nbulb_radius = 0.5\ndrop = 3.6\n",
         "test.toml:3: light.drop = 3.6 is out of range: allowed 0 ..= 3.5"),
        ("gravity = 9.81\n[balls\ncount = 3\n", "test.toml:2: "),
        ("[room]\nsize = [1, 2]\n", "test.toml:2: invalid length 2, expected an array of length 3"),
    ]
    for text, start in cases:
        alone = message(text)
        assert alone.startswith(start), alone
        assert message(text, {"gravity": 3.0}) == alone
        assert message(text, {"fireball.consumes_balls": False, "balls.speed_max": 2.0}) == alone


def test_an_override_can_mend_or_break_a_file_through_the_ranges_that_depend_on_it():
    text = "[[tumblers.placement]]\nx = 0\nz = 0\n\n[[tumblers.placement]]\nx = 1\nz = 9\n"
    assert rolypoly.Scene.parse(text, {"room.size": [20, 4, 20]}).tumbler_count == 2
    # The value the file wrote is named at its line, the room by its override.
    text = "[light]\ndrop = 3\n"
    assert message(text, {"room.size": [8, 3, 8]}).startswith(
        "test.toml:2: light.drop = 3 is out of range: allowed 0 ..= 2.91")
    assert message(text, {"balls.restitution": 1.5}) == \
        'overrides["balls.restitution"]: balls.restitution = 1.5 is out of range: allowed 0 ..= 1'


def test_files_that_cannot_be_read_are_os_errors(tmp_path):
    for overrides in (None, {"gravity": 1.0}):
        with pytest.raises(FileNotFoundError, match="cannot read scene file `.*nope.toml`: No such file"):
            rolypoly.Scene.load(tmp_path / "nope.toml", overrides)
        with pytest.raises(IsADirectoryError, match="cannot read scene file"):
            rolypoly.Scene.load(tmp_path, overrides)


def test_a_scene_saves_and_loads_back():
    scene = rolypoly.Scene.load(SCENES / "newtons-cradle.toml", {"gravity": 4.0})
    assert rolypoly.Scene.parse(scene.to_toml()) == scene
    assert "gravity = 4.0" in scene.to_toml()


def test_keys_and_get():
    keys = rolypoly.Scene.keys()
    assert keys[0] == "gravity" and "balls.count" in keys and "light.color" in keys
    scene = rolypoly.Scene.default()
    for key in keys:
        try:
            scene.get(key)
        except ValueError as e:
            assert "holds a list" in str(e), key
    assert scene.get("light.color") == (1.0, 0.95, 0.85) or len(scene.get("light.color")) == 3
    with pytest.raises(ValueError, match="unknown key `balls.colour`"):
        scene.get("balls.colour")


# Edits of shipped scene files, as the program's own fuzz tests make them
# (crates/rolypoly/tests/scene_fuzz.rs, tests/text_edits.rs).
NUMBERS = ["nan", "-inf", "1e400", "0", "-0.0", "[]", "true", '"x"', "-1", "2_000_000", "0.5", "1e-300", "7"]
TOKENS = ["\n[balls]\n", "\n[[balls.placement]]\nposition = [0, 1, 0]\n",
          "\n[[tumblers.placement]]\nx = 0\nz = 0\n", "count = 3\n", "]", "=", '"', "#",
          "\n[lighting]\n", "balls.count = 5\n", "\x00", "é", "\n[[balls]]\n"]


def edit(text, rng):
    lines = text.splitlines()
    kind = rng.randrange(7)
    if kind == 0 and lines:
        del lines[rng.randrange(len(lines))]
    elif kind == 1 and lines:
        k = rng.randrange(len(lines))
        lines.insert(k, lines[k])
    elif kind == 2 and lines:
        a, b = rng.randrange(len(lines)), rng.randrange(len(lines))
        lines[a], lines[b] = lines[b], lines[a]
    elif kind == 3:
        spans = [m.span() for m in re.finditer(r"-?[0-9][0-9_.eE+-]*", text)]
        if spans:
            start, end = rng.choice(spans)
            return text[:start] + rng.choice(NUMBERS) + text[end:]
    elif kind == 4 and text:
        at = rng.randrange(len(text))
        return text[:at] + chr(rng.randrange(32, 0x2FF)) + text[at + 1:]
    elif kind == 5:
        return text[: rng.randrange(len(text) + 1)]
    else:
        at = rng.randrange(len(text) + 1)
        return text[:at] + rng.choice(TOKENS) + text[at:]
    return "\n".join(lines) + "\n"


def same_place(a, b):
    """Two messages that name the same place and key; a number may be
    written differently once TOML has read it (`1e400` is `inf`)."""
    pattern = r" = .*? is out of range"
    return re.sub(pattern, " = ? is out of range", a) == re.sub(pattern, " = ? is out of range", b)


@pytest.mark.parametrize("seed", range(4))
def test_edited_scene_files_give_a_scene_or_one_clear_error(seed):
    rng = random.Random(seed)
    files = sorted(SCENES.glob("*.toml"))
    outcomes = {"scene": 0, "error": 0}
    for case in range(150):
        path = rng.choice(files)
        text = path.read_text()
        for _ in range(rng.randrange(1, 4)):
            text = edit(text, rng)
        try:
            scene = rolypoly.Scene.parse(text, name="fuzz.toml")
        except ValueError as e:
            alone = str(e)
            assert alone.startswith("fuzz.toml") and "\n" not in alone, alone
            outcomes["error"] += 1
            if "consumes_balls" not in text:
                try:
                    rolypoly.Scene.parse(text, {"fireball.consumes_balls": True}, name="fuzz.toml")
                    # Only a file whose value it sets could pass with it.
                    assert "fireball" in alone, alone
                except ValueError as e2:
                    assert same_place(str(e2), alone), (str(e2), alone, text)
            continue
        outcomes["scene"] += 1
        assert rolypoly.Scene.parse(scene.to_toml()) == scene
        if scene.ball_count <= 2000:
            try:
                world = rolypoly.World(scene, seed=case, engine="cpu")
                world.step(2)
            except ValueError as e:
                assert "\n" not in str(e)
    assert outcomes["scene"] > 10 and outcomes["error"] > 10, outcomes
