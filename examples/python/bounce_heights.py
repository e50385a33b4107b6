"""A ball dropped on the floor of a room of restitution e: each bounce
reaches e² of the height before (requirement P4), for three e.

Writes docs/python/bounce_heights.png. Run: python examples/python/bounce_heights.py
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rolypoly

OUT = Path(__file__).resolve().parents[2] / "docs" / "python"
DROP = 2.0  # metres, from the ball's bottom to the floor
RADIUS = 0.12


def drop(e, seconds=6.0):
    """The ball's height over time, and the top of each flight (the start,
    then after each bounce from its height and upward speed)."""
    scene = rolypoly.Scene.default({
        "balls.count": 0,
        "tumblers.placement": [],
        "room.restitution": e,
        "room.friction": 0.0,
        "room.rolling_resistance": 0.0,
        "balls.placement": [{"position": [0.0, DROP + RADIUS, 0.0], "radius": RADIUS}],
    })
    world = rolypoly.World(scene)
    g = scene.gravity
    times, heights, tops = [0.0], [DROP], [DROP]
    falling = False
    for _ in range(world.steps_for(seconds)):
        world.step()
        y, vy = world.balls.positions[0, 1] - RADIUS, world.balls.velocities[0, 1]
        if falling and vy > 0:
            tops.append(y + vy * vy / (2 * g))
        falling = vy < 0
        times.append(world.time)
        heights.append(y)
    return np.array(times), np.array(heights), np.array(tops)


def main():
    fig, (path, ratio) = plt.subplots(1, 2, figsize=(11, 4.2))
    for e, color in zip((0.5, 0.7, 0.9), ("tab:red", "tab:green", "tab:blue")):
        t, h, tops = drop(e)
        path.plot(t, h, color=color, lw=1.2, label=f"e = {e}")
        n = np.arange(len(tops))
        shown = tops > 1e-3
        ratio.semilogy(n[shown], tops[shown], "o", color=color, label=f"measured, e = {e}")
        ratio.semilogy(n[shown], DROP * (e * e) ** n[shown], "-", color=color, lw=0.8,
                       label=f"$h_0 e^{{2n}}$")
        print(f"e = {e}: tops {np.round(tops[:5], 4).tolist()} m, "
              f"ratios {np.round(tops[1:5] / tops[:4], 6).tolist()} (e² = {e * e:.4f})")
    path.set(xlabel="time (s)", ylabel="height of the ball's bottom (m)",
             title="A ball dropped from 2 m")
    path.legend()
    ratio.set(xlabel="bounce n", ylabel="top of flight n (m)",
              title="Each bounce reaches e² of the last")
    ratio.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "bounce_heights.png", dpi=110)
    print(f"wrote {OUT / 'bounce_heights.png'}")


if __name__ == "__main__":
    main()
