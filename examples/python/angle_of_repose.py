"""Balls poured from a spout (scenes/heap.toml) make a cone; it stands
steeper the more friction there is, and the more the balls resist rolling
on one another and on the floor. The angle is the physics crate's own
measure of the heap (rolypoly.angle_of_repose).

Writes docs/python/angle_of_repose.png. Run: python examples/python/angle_of_repose.py
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rolypoly

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "docs" / "python"
SECONDS = 18.0  # 3000 balls poured at 200 a second, then a few seconds to settle


def heap(friction, rolling, seed=1):
    """The heap's balls, their radius and its angle, for one friction
    coefficient and one rolling resistance (balls and floor alike)."""
    scene = rolypoly.Scene.load(ROOT / "scenes" / "heap.toml", {
        "balls.friction": friction, "room.friction": friction,
        "balls.rolling_resistance": rolling, "room.rolling_resistance": rolling,
    })
    world = rolypoly.World(scene, seed=seed)
    world.step(world.steps_for(SECONDS))
    balls = world.balls
    positions = balls.positions[balls.alive]
    radius = scene.get("balls.radius")
    return positions, radius, rolypoly.angle_of_repose(positions, radius)


def angle_or_nan(angle):
    return np.nan if angle is None else angle


def main():
    scene = rolypoly.Scene.load(ROOT / "scenes" / "heap.toml")
    base_friction = scene.get("balls.friction")
    base_rolling = scene.get("balls.rolling_resistance")
    frictions = [0.05, 0.1, 0.2, 0.4, 0.8]
    rollings = [0.0, 0.02, 0.05, 0.1, 0.2]
    fig, (profile, by_friction, by_rolling) = plt.subplots(1, 3, figsize=(15, 4.2))
    measured = []
    for friction in frictions:
        positions, radius, angle = heap(friction, base_rolling)
        measured.append(angle_or_nan(angle))
        across = np.hypot(positions[:, 0], positions[:, 2])
        profile.scatter(across, positions[:, 1], s=1, label=f"friction {friction}: {angle:.1f}°")
        print(f"friction {friction}, rolling resistance {base_rolling}: "
              f"angle of repose {angle:.2f}° ({len(positions)} balls)")
    profile.set(xlabel="distance from the spout's axis (m)", ylabel="height (m)",
                title=f"The heaps from the side (rolling resistance {base_rolling})",
                xlim=(0, 1.6), ylim=(0, 0.8))
    profile.legend(fontsize=8, markerscale=6)
    by_friction.plot(frictions, measured, "o-")
    by_friction.set(xlabel="friction coefficient (balls and floor)",
                    ylabel="angle of repose (degrees)",
                    title=f"Against friction (rolling resistance {base_rolling})", xscale="log")
    by_friction.set_xticks(frictions, [str(f) for f in frictions])
    by_friction.minorticks_off()
    measured = []
    for rolling in rollings:
        _, _, angle = heap(base_friction, rolling)
        measured.append(angle_or_nan(angle))
        print(f"friction {base_friction}, rolling resistance {rolling}: angle of repose {angle:.2f}°")
    by_rolling.plot(rollings, measured, "o-", color="tab:orange")
    by_rolling.set(xlabel="rolling resistance (balls and floor)", ylabel="angle of repose (degrees)",
                   title=f"Against rolling resistance (friction {base_friction})")
    fig.suptitle("Angle of repose of a poured heap of 3000 balls (one heap each, so with scatter)")
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "angle_of_repose.png", dpi=100)
    print(f"wrote {OUT / 'angle_of_repose.png'}")


if __name__ == "__main__":
    main()
