"""The elastic gas (scenes/elastic-gas.toml: restitution 1, no friction,
no gravity) keeps its energy over 10 s (requirement E1); the same gas with
friction between balls and on the walls loses it.

Writes docs/python/elastic_gas_energy.png. Run: python examples/python/elastic_gas_energy.py
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rolypoly

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "docs" / "python"
SECONDS = 10.0


def energy_over_time(overrides, seed=1, every=0.05):
    scene = rolypoly.Scene.load(ROOT / "scenes" / "elastic-gas.toml", overrides)
    world = rolypoly.World(scene, seed=seed)
    times, totals = [0.0], [world.energy().total]
    steps = world.steps_for(every)
    while world.time < SECONDS - 1e-9:
        world.step(steps)
        times.append(world.time)
        totals.append(world.energy().total)
    impacts = len(world.events())
    return np.array(times), np.array(totals), impacts


def main():
    runs = [
        ("elastic, no friction (as shipped)", {}, "tab:blue"),
        ("friction 0.3 between balls and on walls", {"balls.friction": 0.3, "room.friction": 0.3}, "tab:orange"),
        ("friction 1.0", {"balls.friction": 1.0, "room.friction": 1.0}, "tab:red"),
    ]
    fig, (total, drift) = plt.subplots(1, 2, figsize=(11, 4.2))
    for label, overrides, color in runs:
        t, e, impacts = energy_over_time(overrides)
        total.plot(t, e / e[0], color=color, label=label)
        change = e / e[0] - 1
        print(f"{label}: energy after {SECONDS:g} s {100 * change[-1]:+.2e} %, "
              f"largest change {100 * np.abs(change).max():.2e} %, {impacts} impacts")
        if not overrides:
            drift.plot(t, change, color=color, label=f"largest change {np.abs(change).max():.1e}")
            drift.axhspan(-1e-3, 1e-3, color="tab:green", alpha=0.15, label="E1 bound (0.1 %)")
    total.set(xlabel="time (s)", ylabel="total energy / start", title="400 balls, 10 s",
              ylim=(0, 1.05))
    total.legend(fontsize=8)
    drift.set(xlabel="time (s)", ylabel="relative change", title="The elastic gas, magnified",
              ylim=(-2e-3, 2e-3))
    drift.legend(fontsize=8)
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "elastic_gas_energy.png", dpi=110)
    print(f"wrote {OUT / 'elastic_gas_energy.png'}")


if __name__ == "__main__":
    main()
