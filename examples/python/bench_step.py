"""How much Python costs: world.step(600) of a 10 000-ball pit through
Python against the same 600 steps in the program (`rolypoly simulate`),
600 calls of step(1) against one of step(600), and reading a million
balls' state into NumPy.

Run: python examples/python/bench_step.py
The program is $ROLYPOLY_BIN, else target/release/rolypoly (build it with
`cargo build --release -p rolypoly --bin rolypoly`); without it that row
is left out. Build the module with `maturin develop --release` too: a
debug build steps many times slower.
"""

import argparse
import os
import re
import statistics
import subprocess
import time
from pathlib import Path

import rolypoly

ROOT = Path(__file__).resolve().parents[2]
PIT = ROOT / "scenes" / "ballpit-10k.toml"
MILLION = ROOT / "scenes" / "ballpit-1m.toml"
STEPS = 600
SEED = 1


def timed(work):
    started = time.perf_counter()
    work()
    return time.perf_counter() - started


def program():
    path = Path(os.environ.get("ROLYPOLY_BIN", ROOT / "target" / "release" / "rolypoly"))
    return path if path.is_file() else None


def program_seconds(path):
    """The wall time `rolypoly simulate` reports for its steps alone (its
    start-up and the scene's building left out)."""
    out = subprocess.run(
        [str(path), "--scene", str(PIT), "--seed", str(SEED), "--engine", "cpu",
         "simulate", "--steps", str(STEPS)],
        capture_output=True, text=True, check=True,
    ).stdout
    return float(re.search(r"in ([0-9.]+) s of wall time", out).group(1))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3,
                        help="rounds of each timing, taken in turn; the best is shown (default 3)")
    rounds = max(1, parser.parse_args().rounds)
    print(f"{os.cpu_count()} CPUs; rolypoly module at {Path(rolypoly.__file__).parent}")
    scene = rolypoly.Scene.load(PIT)
    path = program()

    def python_once():
        world = rolypoly.World(scene, seed=SEED, engine="cpu")
        return timed(lambda: world.step(STEPS))

    def python_each():
        world = rolypoly.World(scene, seed=SEED, engine="cpu")

        def one_by_one():
            for _ in range(STEPS):
                world.step(1)

        return timed(one_by_one)

    timings = {"once": [], "each": [], "rust": []}
    # In turn, so that a busy moment of the machine falls on each alike.
    for _ in range(rounds):
        timings["once"].append(python_once())
        timings["each"].append(python_each())
        if path:
            timings["rust"].append(program_seconds(path))
    rows = [
        (f"World.step({STEPS}), 10 000 balls", min(timings["once"])),
        (f"{STEPS} x World.step(1), 10 000 balls", min(timings["each"])),
    ]
    if path:
        rows.append((f"rolypoly simulate --steps {STEPS} (the same steps in Rust)", min(timings["rust"])))

    print(f"\nbest of {rounds} rounds")
    print(f"{'what':<58} {'seconds':>9} {'ms/step':>9}")
    for what, seconds in rows:
        print(f"{what:<58} {seconds:>9.3f} {1000 * seconds / STEPS:>9.3f}")
    if path:
        rust = rows[2][1]
        print(f"Python over Rust: {rows[0][1] / rust:.3f} (step({STEPS})), "
              f"{rows[1][1] / rust:.3f} ({STEPS} x step(1))")
    else:
        print("(no rolypoly binary: build it, or set ROLYPOLY_BIN, for the Rust row)")

    # The first array of a process loads NumPy's C API, once.
    first = timed(lambda: rolypoly.World(rolypoly.Scene.default({"balls.count": 1})).balls.positions)
    started = time.perf_counter()
    world = rolypoly.World(rolypoly.Scene.load(MILLION), seed=SEED, engine="cpu")
    print(f"\nThe first array of the process (NumPy's C API loaded): {1000 * first:.1f} ms")
    print(f"A million balls: made in {time.perf_counter() - started:.2f} s; reading the state, "
          "median of 7 reads (the first read is also shown):")
    print(f"{'array':<12} {'shape':<14} {'first ms':>9} {'median ms':>10} {'MB':>6}")
    for name in ("positions", "velocities", "spins", "radii", "masses", "colors", "alive"):
        times = []
        for _ in range(7):
            started = time.perf_counter()
            array = getattr(world.balls, name)
            times.append(time.perf_counter() - started)
        print(f"{name:<12} {str(array.shape):<14} {1000 * times[0]:>9.1f} "
              f"{1000 * statistics.median(times):>10.1f} {array.nbytes / 1e6:>6.1f}")


if __name__ == "__main__":
    main()
