"""The laws a teacher checks, measured through Python over several
sizes, seeds and settings: bounce heights fall by e² (P4), an elastic
room keeps its energy (E1), Newton's cradle passes the impulse along and
keeps momentum (P1, E2)."""

import numpy as np
import pytest

import rolypoly
from conftest import SCENES


def one_ball(e, radius, height, seed):
    scene = rolypoly.Scene.default({
        "balls.count": 0,
        "tumblers.placement": [],
        "room.restitution": e,
        "room.friction": 0.0,
        "room.rolling_resistance": 0.0,
        "balls.placement": [{"position": [0.3, height + radius, -0.2], "radius": radius}],
    })
    return rolypoly.World(scene, seed=seed)


def apexes(world, count):
    """Heights of the ball's bottom at the top of each flight: the start,
    then after each bounce, from its height and upward speed just after it."""
    g = world.scene.gravity
    r = world.balls.radii[0]
    found = [world.balls.positions[0, 1] - r]
    sampled = [found[0]]
    falling, top = False, found[0]
    for _ in range(int(20 / world.dt)):
        world.step()
        y, vy = world.balls.positions[0, 1], world.balls.velocities[0, 1]
        if falling and vy > 0:
            found.append(y - r + vy * vy / (2 * g))
            sampled.append(top)
            top = -np.inf
        top = max(top, y - r)
        falling = vy < 0
        if len(found) > count:
            break
    return np.array(found), np.array(sampled[1:])


@pytest.mark.parametrize("e", [0.5, 0.7, 0.9])
@pytest.mark.parametrize("radius, height, seed", [(0.05, 1.0, 1), (0.12, 2.0, 2), (0.3, 3.0, 3)])
def test_each_bounce_reaches_e_squared_of_the_last(e, radius, height, seed):
    heights, sampled = apexes(one_ball(e, radius, height, seed), 4)
    assert len(heights) == 5
    assert np.allclose(heights[1:] / heights[:-1], e * e, rtol=1e-9, atol=0)
    # The highest point sampled step by step agrees, to what a step can
    # miss the top by (g dt² / 8 either side).
    dt = 1 / 120
    assert np.allclose(sampled[1:], heights[1:-1], rtol=0, atol=9.81 * dt * dt)


@pytest.mark.parametrize(
    "count, seed, gravity, tolerance",
    # E1: 0.1 % over 10 s without gravity, 0.5 % with it.
    [(50, 1, 0.0, 1e-3), (200, 2, 0.0, 1e-3), (400, 3, 0.0, 1e-3), (120, 4, 9.81, 5e-3), (400, 5, 9.81, 5e-3)],
)
def test_an_elastic_room_keeps_its_energy(count, seed, gravity, tolerance):
    scene = rolypoly.Scene.load(SCENES / "elastic-gas.toml", {"balls.count": count, "gravity": gravity})
    world = rolypoly.World(scene, seed=seed)
    start = world.energy().total
    assert start > 0
    totals = []
    for _ in range(10):
        world.step(world.steps_for(1.0))
        totals.append(world.energy().total)
    assert world.time == pytest.approx(10.0)
    kinds = {e.kind for e in world.events()}
    assert {"ball_ball", "ball_surface"} <= kinds, "the balls must have met"
    assert np.max(np.abs(np.array(totals) / start - 1)) < tolerance


def test_friction_takes_energy_out_of_the_same_gas():
    # The check above could not fail if energy were merely read back.
    scene = rolypoly.Scene.load(SCENES / "elastic-gas.toml",
                                {"balls.count": 200, "balls.restitution": 0.8, "room.restitution": 0.8})
    world = rolypoly.World(scene, seed=2)
    start = world.energy().total
    world.step(world.steps_for(5.0))
    assert world.energy().total < 0.8 * start


def momentum(world):
    balls = world.balls
    return (balls.masses[:, None] * balls.velocities * balls.alive[:, None]).sum(axis=0)


def cradle(touching, incoming, radius, speed, seed):
    """A row of `touching` balls at rest and `incoming` balls, touching each
    other, coming at it along +x at `speed`."""
    y, gap = radius, 2 * radius
    placement = [{"position": [i * gap, y, 0.0]} for i in range(touching)]
    start = -1.0 - radius * 4
    placement += [{"position": [start - i * gap, y, 0.0], "velocity": [speed, 0.0, 0.0]}
                  for i in range(incoming)]
    scene = rolypoly.Scene.load(SCENES / "newtons-cradle.toml",
                                {"balls.placement": placement, "balls.radius": radius})
    return rolypoly.World(scene, seed=seed)


@pytest.mark.parametrize("touching, incoming", [(3, 1), (5, 1), (5, 2), (7, 3)])
@pytest.mark.parametrize("radius, speed, seed", [(0.12, 1.0, 1), (0.08, 2.5, 9)])
def test_newtons_cradle_passes_the_impulse_and_keeps_momentum(touching, incoming, radius, speed, seed):
    world = cradle(touching, incoming, radius, speed, seed)
    before = momentum(world)
    # Until the last ball out, moving at `speed`, is at the wall.
    world.step(world.steps_for((1.0 + 4 * radius) / speed + 0.5))
    after = momentum(world)
    assert np.allclose(after, before, rtol=1e-12, atol=1e-12)
    vx = world.balls.velocities[:, 0]
    moving = np.flatnonzero(np.abs(vx) > 1e-9)
    # As many leave the far end as came in, at the speed they came with.
    assert list(moving) == list(range(touching - incoming, touching))
    assert np.allclose(vx[moving], speed, rtol=1e-9)


def test_the_shipped_cradle_keeps_momentum_over_seeds():
    for seed in (1, 2, 3):
        world = rolypoly.World(rolypoly.Scene.load(SCENES / "newtons-cradle.toml"), seed=seed)
        before = momentum(world)
        world.step(world.steps_for(2.0))
        assert np.allclose(momentum(world), before, rtol=1e-12, atol=1e-12)
        assert np.count_nonzero(np.abs(world.balls.velocities[:, 0]) > 0.5) == 6
