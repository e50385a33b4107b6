"""What a notebook shows of a run: a clip that plays inline.

>>> clip = rolypoly.clip(world, seconds=2, fps=15)   # doctest: +SKIP
>>> clip                                               # plays in Jupyter

A :class:`Clip` holds an animated GIF made by :func:`rolypoly.record`, in
memory: no file is needed to show it, and :meth:`Clip.save` writes it.
"""

import base64
import os
import tempfile

from ._rolypoly import record


class Clip:
    """An animated GIF of a run, held in memory; shown inline by Jupyter."""

    def __init__(self, gif: bytes, frames: int, fps: int):
        self.gif = gif
        self.frames = frames
        self.fps = fps

    def _repr_html_(self) -> str:
        data = base64.b64encode(self.gif).decode("ascii")
        return f'<img src="data:image/gif;base64,{data}" alt="a rolypoly clip of {self.frames} frames">'

    def save(self, path) -> None:
        """Writes the GIF to ``path``."""
        with open(path, "wb") as f:
            f.write(self.gif)

    def __repr__(self) -> str:
        return f"<rolypoly.Clip: {self.frames} frames at {self.fps} a second, {len(self.gif)} bytes of GIF>"


def clip(world, seconds=2.0, fps=15, size=(480, 270), camera=None, quality=None, show=None) -> Clip:
    """Steps ``world`` on for ``seconds`` and gives the run as a :class:`Clip`,
    drawn as :func:`rolypoly.record` draws a ``.gif`` (the same arguments)."""
    folder = tempfile.mkdtemp(prefix="rolypoly-clip-")
    path = os.path.join(folder, "clip.gif")
    try:
        frames = record(world, path, seconds=seconds, fps=fps, size=size, camera=camera, quality=quality, show=show)
        with open(path, "rb") as f:
            gif = f.read()
    finally:
        if os.path.exists(path):
            os.remove(path)
        os.rmdir(folder)
    return Clip(gif, frames, fps)
