"""The angle of repose with error bars: heaps poured (scenes/heap.toml)
for every friction coefficient by every rolling resistance, four seeds
each, swept on a Dask cluster by rolypoly.sweep. Each point is the mean
of the four heaps, its bar their standard deviation.

Runs on a LocalCluster of two worker processes on the local machine; give a
scheduler's address to run the same code on a cluster:

    python examples/python/angle_of_repose_sweep.py [tcp://scheduler:8786]

Writes docs/python/angle_of_repose_sweep.png.
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from distributed import Client, LocalCluster

import rolypoly

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "docs" / "python"
SECONDS = 18.0  # 3000 balls poured at 200 a second, then a few seconds to settle
FRICTIONS = [0.1, 0.3, 0.8]
ROLLINGS = [0.0, 0.05, 0.1, 0.2]
SEEDS = [1, 2, 3, 4]


def repose(world):
    """The heap's angle once poured and settled (None where no heap stands)."""
    world.step(world.steps_for(SECONDS), progress=False)
    balls = world.balls
    radius = float(balls.radii[0])
    return rolypoly.angle_of_repose(balls.positions[balls.alive], radius)


def main():
    scene = rolypoly.Scene.load(ROOT / "scenes" / "heap.toml")
    grid = {"balls.friction": FRICTIONS, "balls.rolling_resistance": ROLLINGS}
    if len(sys.argv) > 1:
        client = Client(sys.argv[1])
    else:
        client = Client(LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None))
    with client:
        table = rolypoly.sweep(repose, scene, grid, SEEDS, executor=client.get_executor())
    failed = table[table["error"].notna()]
    if len(failed):
        print(failed)
        raise SystemExit("some heaps failed")
    table["angle"] = table["result"].astype(float)
    stats = table.groupby(["balls.friction", "balls.rolling_resistance"])["angle"].agg(["mean", "std"])
    print(stats.round(2))
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for friction in FRICTIONS:
        rows = stats.loc[friction]
        ax.errorbar(rows.index, rows["mean"], yerr=rows["std"], marker="o", capsize=4,
                    label=f"friction {friction}")
    ax.set(xlabel="rolling resistance between balls",
           ylabel="angle of repose (degrees)",
           title=f"A heap of 3000 balls: mean and spread of {len(SEEDS)} seeds")
    ax.legend()
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "angle_of_repose_sweep.png", dpi=100)
    print(f"wrote {OUT / 'angle_of_repose_sweep.png'}")


if __name__ == "__main__":
    main()
