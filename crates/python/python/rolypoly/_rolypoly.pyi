"""Types of the compiled module; `rolypoly/__init__.py` re-exports them."""

from os import PathLike
from typing import Any, Dict, Iterator, List, Literal, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

Point = Tuple[float, float, float]
Vector = Union[Sequence[float], npt.ArrayLike]
StrPath = Union[str, "PathLike[str]"]
EngineName = Literal["cpu", "gpu"]
QualityName = Literal["high", "medium", "low", "auto"]
DebugView = Literal["contacts", "impulses", "velocities", "grid", "rest", "com"]
FrameViewName = Literal[
    "final", "albedo", "normals", "depth", "shadow-cube", "shadow", "ambient", "diffuse",
    "specular", "bounce", "occlusion", "bloom", "motion", "history", "msaa-edges",
]
EventKind = Literal[
    "ball_surface", "ball_ball", "ball_tumbler", "fireball_surface", "fireball_ball", "fireball_tumbler"
]

MAX_PENDING_EVENTS: int
__version__: str

class DeviceError(RuntimeError):
    """The graphics adapter could not be opened, or failed while it drew or stepped."""

class Scene:
    """A scene read and checked as ``rolypoly --scene FILE`` reads it."""

    @staticmethod
    def default(overrides: Optional[Mapping[str, Any]] = None) -> Scene: ...
    @staticmethod
    def load(path: StrPath, overrides: Optional[Mapping[str, Any]] = None) -> Scene: ...
    @staticmethod
    def parse(text: str, overrides: Optional[Mapping[str, Any]] = None, name: str = "<string>") -> Scene: ...
    @staticmethod
    def keys() -> List[str]: ...
    def get(self, name: str) -> Union[float, int, bool, str, Tuple[float, float, float]]: ...
    def to_toml(self) -> str: ...
    def _repr_html_(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def ball_count(self) -> int: ...
    @property
    def tumbler_count(self) -> int: ...
    @property
    def dt(self) -> float: ...
    @property
    def gravity(self) -> float: ...
    @property
    def room_size(self) -> Point: ...
    @property
    def engine(self) -> EngineName: ...
    @property
    def quality(self) -> QualityName: ...
    def __eq__(self, other: object) -> bool: ...

class Energy:
    """Kinetic, potential and total energy (J); unpacks as a tuple."""

    @property
    def kinetic(self) -> float: ...
    @property
    def potential(self) -> float: ...
    @property
    def total(self) -> float: ...
    def __iter__(self) -> Iterator[float]: ...

class Event:
    """One impact, and the colour a ball took on from it."""

    @property
    def kind(self) -> EventKind: ...
    @property
    def step(self) -> int: ...
    @property
    def time(self) -> float: ...
    @property
    def ball(self) -> Optional[int]: ...
    @property
    def a(self) -> Optional[int]: ...
    @property
    def b(self) -> Optional[int]: ...
    @property
    def tumbler(self) -> Optional[int]: ...
    @property
    def sphere(self) -> Optional[int]: ...
    @property
    def surface(self) -> Optional[str]: ...
    @property
    def point(self) -> Point: ...
    @property
    def normal(self) -> Point: ...
    @property
    def speed(self) -> float: ...
    @property
    def color(self) -> Optional[Point]: ...
    def to_dict(self) -> Dict[str, Any]: ...

class Balls:
    """The balls of a world; every read is a fresh copy."""

    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """(N, 3) centres, metres."""
    @positions.setter
    def positions(self, value: npt.ArrayLike) -> None: ...
    @property
    def velocities(self) -> npt.NDArray[np.float64]:
        """(N, 3) velocities, m/s."""
    @velocities.setter
    def velocities(self, value: npt.ArrayLike) -> None: ...
    @property
    def spins(self) -> npt.NDArray[np.float64]:
        """(N, 3) angular velocities, rad/s."""
    @property
    def radii(self) -> npt.NDArray[np.float64]:
        """(N,) radii, metres."""
    @property
    def masses(self) -> npt.NDArray[np.float64]:
        """(N,) masses, kg."""
    @property
    def colors(self) -> npt.NDArray[np.float64]:
        """(N, 3) colours shown, linear RGB 0..1."""
    @property
    def tints(self) -> List[str]: ...
    @property
    def alive(self) -> npt.NDArray[np.bool_]:
        """(N,) whether each ball is in play."""
    def __len__(self) -> int: ...

class Tumblers:
    """The tumblers of a world; every read is a fresh copy."""

    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """(T, 3) centres of mass, metres."""
    @property
    def orientations(self) -> npt.NDArray[np.float64]:
        """(T, 4) unit quaternions (x, y, z, w)."""
    @property
    def velocities(self) -> npt.NDArray[np.float64]:
        """(T, 3) velocities of the centres of mass, m/s."""
    @property
    def angular_velocities(self) -> npt.NDArray[np.float64]:
        """(T, 3) angular velocities, rad/s."""
    @property
    def bottom_centers(self) -> npt.NDArray[np.float64]:
        """(T, 3) centres of the round bottoms, metres."""
    @property
    def tilts(self) -> npt.NDArray[np.float64]:
        """(T,) tilts of the axes from the vertical, radians."""
    @property
    def sliding(self) -> npt.NDArray[np.bool_]:
        """(T,) whether each slides rather than rolls."""
    def __len__(self) -> int: ...

class Fireball:
    """The fireball as it flies, copied when read."""

    @property
    def position(self) -> Point: ...
    @property
    def velocity(self) -> Point: ...
    @property
    def radius(self) -> float: ...
    @property
    def speed(self) -> float: ...
    @property
    def mass(self) -> float: ...

class Snapshot:
    """A world's whole state, for World.restore; pickles as its bytes."""

    @property
    def time(self) -> float: ...
    @property
    def steps(self) -> int: ...
    @property
    def seed(self) -> int: ...
    @property
    def engine(self) -> EngineName: ...
    def to_bytes(self) -> bytes: ...
    @staticmethod
    def from_bytes(data: bytes) -> Snapshot: ...

class World:
    """A scene's world, stepped as the program steps it."""

    def __init__(self, scene: Optional[Scene] = None, seed: int = 1, engine: Optional[EngineName] = None) -> None: ...
    def step(self, n: int = 1, progress: Optional[bool] = None) -> None: ...
    def steps_for(self, seconds: float) -> int: ...
    @property
    def time(self) -> float: ...
    @property
    def steps(self) -> int: ...
    @property
    def dt(self) -> float: ...
    @property
    def seed(self) -> int: ...
    @property
    def engine(self) -> EngineName: ...
    @property
    def scene(self) -> Scene: ...
    @property
    def room(self) -> Tuple[Point, Point]: ...
    @property
    def balls(self) -> Balls: ...
    @property
    def tumblers(self) -> Tumblers: ...
    @property
    def fireball(self) -> Optional[Fireball]: ...
    def energy(self) -> Energy: ...
    def events(self) -> List[Event]: ...
    def throw_ball(self, position: Vector, velocity: Vector) -> int: ...
    def launch_fireball(self, position: Optional[Vector] = None, direction: Optional[Vector] = None) -> None: ...
    def remove_fireball(self) -> None: ...
    def snapshot(self) -> Snapshot: ...
    def restore(self, snapshot: Snapshot) -> None: ...
    def write_trace(self, path: StrPath, steps: int, every: int = 1) -> None: ...
    def series(self, steps: int, every: int = 1, frame: bool = False) -> Any: ...
    def _repr_png_(self) -> Optional[bytes]: ...

def render(
    world: World,
    size: Tuple[int, int] = (640, 360),
    camera: Optional[Tuple[Vector, Vector]] = None,
    quality: Optional[QualityName] = None,
    show: Optional[Union[str, Sequence[DebugView]]] = None,
    view: Optional[FrameViewName] = None,
) -> npt.NDArray[np.uint8]:
    """An (H, W, 4) uint8 RGBA frame, as `rolypoly render` draws it (`view`: as `--view`)."""

def overview_camera(world: World) -> Tuple[Point, Point]: ...

def frame_views() -> List[Tuple[str, str]]:
    """Every view of the frame's passes `render` takes: (name, what it shows)."""

def record(
    world: World,
    path: StrPath,
    seconds: float = 3.0,
    fps: int = 30,
    size: Tuple[int, int] = (640, 360),
    camera: Optional[Tuple[Vector, Vector]] = None,
    quality: Optional[QualityName] = None,
    show: Optional[Union[str, Sequence[DebugView]]] = None,
    view: Optional[FrameViewName] = None,
) -> int:
    """Steps the world on and writes a clip (.gif, .mp4 or DIR/) as `rolypoly record`; the frame count."""

def sound(
    world: World,
    seconds: float,
    camera: Optional[Tuple[Vector, Vector]] = None,
) -> npt.NDArray[np.float32]:
    """Steps the world on and returns its sound, (frames, 2) float32 at 48 kHz, as `rolypoly sound`."""

def angle_of_repose(
    positions: npt.ArrayLike, radius: float, axis: Tuple[float, float] = (0.0, 0.0)
) -> Optional[float]:
    """The heap's angle of repose in degrees, as the physics crate measures it; None without a flank."""
