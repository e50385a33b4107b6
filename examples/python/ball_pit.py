"""A pit of 10 000 balls (scenes/ballpit-10k.toml) stepped to 1 s and drawn
off-screen by the program's renderer, the frame `rolypoly render --time 1`
draws, with how the balls' heights and speeds are spread.

Writes docs/python/ball_pit.png. Run: python examples/python/ball_pit.py
(it draws on the GPU, or on Mesa's lavapipe where there is none).
"""

import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rolypoly

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "docs" / "python"


def main():
    world = rolypoly.World(rolypoly.Scene.load(ROOT / "scenes" / "ballpit-10k.toml"), seed=1, engine="cpu")
    started = time.perf_counter()
    world.step(world.steps_for(1.0))
    stepped = time.perf_counter() - started
    started = time.perf_counter()
    frame = rolypoly.render(world, size=(960, 540))
    drawn = time.perf_counter() - started
    print(f"{world}: {stepped:.2f} s to step, {drawn:.2f} s to draw")

    balls = world.balls
    heights = balls.positions[:, 1]
    speeds = np.linalg.norm(balls.velocities, axis=1)
    fig = plt.figure(figsize=(11, 4.6))
    picture = fig.add_axes([0.0, 0.0, 0.64, 1.0])
    picture.imshow(frame)
    picture.set_axis_off()
    picture.set_title(f"10 000 balls at t = {world.time:.2f} s (rolypoly.render)", fontsize=10)
    spread = fig.add_axes([0.71, 0.57, 0.27, 0.33])
    spread.hist(heights, bins=60, color="tab:brown")
    spread.set(xlabel="height of centre (m)", ylabel="balls")
    moving = fig.add_axes([0.71, 0.12, 0.27, 0.33])
    moving.hist(speeds, bins=60, color="tab:blue", log=True)
    moving.set(xlabel="speed (m/s)", ylabel="balls")
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "ball_pit.png", dpi=110)
    print(f"wrote {OUT / 'ball_pit.png'}")


if __name__ == "__main__":
    main()
