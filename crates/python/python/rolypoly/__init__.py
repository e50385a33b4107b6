"""rolypoly from Python: the physics toy room's scenes, worlds and frames.

>>> import rolypoly
>>> world = rolypoly.World(rolypoly.Scene.default({"balls.count": 100}), seed=1)
>>> world.step(120)
>>> world.balls.positions.shape
(100, 3)

The physics, the scene checks and the renderer are the program's own
(``rolypoly simulate``, ``rolypoly render``): the same scene and seed give
the same world, bit for bit. See ``docs/python.md``.
"""

from ._rolypoly import (
    MAX_PENDING_EVENTS,
    __version__,
    Balls,
    DeviceError,
    Energy,
    Event,
    Fireball,
    Scene,
    Snapshot,
    Tumblers,
    World,
    angle_of_repose,
    frame_views,
    overview_camera,
    record,
    render,
    sound,
)
from .notebook import Clip, clip
from .sweep import sweep

__all__ = [
    "MAX_PENDING_EVENTS",
    "Balls",
    "Clip",
    "DeviceError",
    "Energy",
    "Event",
    "Fireball",
    "Scene",
    "Snapshot",
    "Tumblers",
    "World",
    "angle_of_repose",
    "clip",
    "frame_views",
    "overview_camera",
    "record",
    "render",
    "sound",
    "sweep",
]
