"""A tumbler let go at a tilt rocks back and forth; its period against the
amplitude, and at small amplitudes the rolling pendulum's
omega0² = g a / (k² + (R - a)²) (requirement P6). R, a, k are the tumbler's own,
read from a trace's scene line.

Writes docs/python/tumbler_period.png. Run: python examples/python/tumbler_period.py
"""

import json
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rolypoly

OUT = Path(__file__).resolve().parents[2] / "docs" / "python"
BASE = {"balls.count": 0, "tumblers.damping": 0.0}


def scene_at(tilt_deg):
    return rolypoly.Scene.default({**BASE, "tumblers.placement": [{"x": 0, "z": 0, "tilt_deg": tilt_deg}]})


def analytic_period(scene):
    """2 pi / omega0, from the shape the trace's scene line gives."""
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "shape.jsonl"
        rolypoly.World(scene).write_trace(path, 0)
        shape = json.loads(path.read_text().splitlines()[0])["tumbler_shape"]
    big_r, a, mass = shape["bottom_radius"], shape["com_offset"], shape["mass"]
    k2 = shape["inertia"][0][0] / mass  # about a horizontal axis through the centre of mass
    omega0 = np.sqrt(scene.gravity * a / (k2 + (big_r - a) ** 2))
    return 2 * np.pi / omega0, (big_r, a, np.sqrt(k2))


def rocking(tilt_deg, seconds=8.0):
    """Times and signed tilts (about x, from the quaternion (x, y, z, w))."""
    world = rolypoly.World(scene_at(tilt_deg))
    times, angles = [], []
    for _ in range(world.steps_for(seconds)):
        world.step()
        x, _, _, w = world.tumblers.orientations[0]
        times.append(world.time)
        angles.append(np.degrees(2 * np.arctan2(x, w)))
    return np.array(times), np.array(angles)


def period(times, angles):
    """The mean time between downward zero crossings, interpolated."""
    k = np.flatnonzero((angles[:-1] > 0) & (angles[1:] <= 0))
    crossings = times[k] + angles[k] / (angles[k] - angles[k + 1]) * (times[1] - times[0])
    return np.diff(crossings).mean()


def main():
    small, (big_r, a, k) = analytic_period(scene_at(1.0))
    amplitudes = [1, 2, 4, 6, 10, 15, 20, 25, 30, 40]
    periods = []
    fig, (swing, curve) = plt.subplots(1, 2, figsize=(11, 4.2))
    for amplitude in amplitudes:
        t, angle = rocking(amplitude)
        periods.append(period(t, angle))
        if amplitude in (4, 20, 40):
            swing.plot(t, angle, label=f"{amplitude}°")
    periods = np.array(periods)
    print(f"R = {big_r} m, a = {a:.4f} m, k = {k:.4f} m: small-amplitude period {small:.4f} s")
    for amplitude, p in zip(amplitudes, periods):
        print(f"  amplitude {amplitude:>2}°: period {p:.4f} s ({100 * (p / small - 1):+.2f} %)")
    swing.set(xlabel="time (s)", ylabel="tilt (degrees)", title="Let go at a tilt")
    swing.legend()
    curve.plot(amplitudes, periods, "o-", label="measured")
    curve.axhline(small, color="k", ls="--", lw=0.8, label=r"$2\pi/\omega_0$, $\omega_0^2 = g a/(k^2+(R-a)^2)$")
    curve.set(xlabel="amplitude (degrees)", ylabel="period (s)", title="Rocking period against amplitude")
    curve.legend(fontsize=8)
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "tumbler_period.png", dpi=110)
    print(f"wrote {OUT / 'tumbler_period.png'}")


if __name__ == "__main__":
    main()
