"""Balls poured from a spout (scenes/heap.toml) make a cone; it stands
steeper the more friction there is. The angle is the physics crate's own
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


def heap(friction, seed=1):
    scene = rolypoly.Scene.load(ROOT / "scenes" / "heap.toml",
                                {"balls.friction": friction, "room.friction": friction})
    world = rolypoly.World(scene, seed=seed)
    world.step(world.steps_for(SECONDS))
    balls = world.balls
    positions = balls.positions[balls.alive]
    radius = scene.get("balls.radius")
    return positions, radius, rolypoly.angle_of_repose(positions, radius)


def main():
    frictions = [0.05, 0.1, 0.2, 0.4, 0.8]
    fig, (profile, angles) = plt.subplots(1, 2, figsize=(11, 4.2))
    measured = []
    for friction in frictions:
        positions, radius, angle = heap(friction)
        measured.append(np.nan if angle is None else angle)
        across = np.hypot(positions[:, 0], positions[:, 2])
        profile.scatter(across, positions[:, 1], s=1, label=f"friction {friction}: {angle:.1f}°")
        print(f"friction {friction}: angle of repose {angle:.2f}° ({len(positions)} balls)")
    profile.set(xlabel="distance from the spout's axis (m)", ylabel="height (m)",
                title="The heaps, seen from the side", aspect="equal")
    profile.legend(fontsize=8, markerscale=6)
    angles.plot(frictions, measured, "o-")
    angles.set(xlabel="friction coefficient (balls and floor)", ylabel="angle of repose (degrees)",
               title="Angle of repose against friction (one heap each)", xscale="log")
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "angle_of_repose.png", dpi=110)
    print(f"wrote {OUT / 'angle_of_repose.png'}")


if __name__ == "__main__":
    main()
