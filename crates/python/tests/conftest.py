"""Shared helpers: where the repository and the `rolypoly` binary are, and
a PNG reader for the binary's frames (no imaging library needed)."""

import os
import struct
import subprocess
import tempfile
import zlib
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[3]
SCENES = REPO / "scenes"

# Mesa's drivers want a runtime folder; a headless CI has none.
os.environ.setdefault("XDG_RUNTIME_DIR", tempfile.mkdtemp(prefix="rolypoly-xdg-"))


def rolypoly_bin() -> Path:
    """The program to compare with: $ROLYPOLY_BIN, else the debug build."""
    path = Path(os.environ.get("ROLYPOLY_BIN", REPO / "target" / "debug" / "rolypoly"))
    if not path.is_file():
        pytest.fail(
            f"the rolypoly binary is not at {path}: build it with "
            "`cargo build -p rolypoly --bin rolypoly` or set ROLYPOLY_BIN"
        )
    return path


def run_bin(*args: str) -> str:
    """Runs the program; its standard output, or a failure with its error."""
    done = subprocess.run(
        [str(rolypoly_bin()), *args], capture_output=True, text=True, timeout=600
    )
    if done.returncode != 0:
        pytest.fail(f"rolypoly {' '.join(args)} failed: {done.stderr.strip()}")
    return done.stdout


def read_png(path: Path) -> np.ndarray:
    """An 8-bit RGBA, non-interlaced PNG (what the program writes) as an
    (H, W, 4) uint8 array."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind = data[pos + 4 : pos + 8]
        body = data[pos + 8 : pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
    width, height, depth, color, _, _, interlace = header
    assert (depth, color, interlace) == (8, 6, 0), "only 8-bit RGBA, not interlaced"
    raw = zlib.decompress(idat)
    stride = width * 4
    out = np.zeros((height, stride), dtype=np.uint8)
    prev = np.zeros(stride, dtype=np.int32)
    for y in range(height):
        start = y * (stride + 1)
        kind = raw[start]
        line = np.frombuffer(raw[start + 1 : start + 1 + stride], dtype=np.uint8).astype(np.int32)
        cur = np.zeros(stride, dtype=np.int32)
        if kind == 0:
            cur = line
        elif kind == 2:
            cur = (line + prev) & 0xFF
        else:
            for x in range(stride):
                left = cur[x - 4] if x >= 4 else 0
                up = prev[x]
                upleft = prev[x - 4] if x >= 4 else 0
                if kind == 1:
                    pred = left
                elif kind == 3:
                    pred = (left + up) // 2
                else:  # Paeth
                    p = left + up - upleft
                    pa, pb, pc = abs(p - left), abs(p - up), abs(p - upleft)
                    pred = left if pa <= pb and pa <= pc else (up if pb <= pc else upleft)
                cur[x] = (line[x] + pred) & 0xFF
        out[y] = cur
        prev = cur
    return out.reshape(height, width, 4)
