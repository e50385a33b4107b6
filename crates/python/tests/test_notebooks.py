"""The notebooks in examples/notebooks run from top to bottom, each
showing the room (a frame or a clip) and asserting its law; one with its
law broken fails."""

import os
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

from conftest import REPO

NOTEBOOKS = sorted((REPO / "examples" / "notebooks").glob("*.ipynb"))


def run(notebook):
    # Matplotlib draws into the notebook, not onto a display.
    os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"
    NotebookClient(notebook, timeout=600, kernel_name="python3",
                   resources={"metadata": {"path": str(REPO)}}).execute()
    return notebook


def test_there_are_notebooks():
    assert {p.name for p in NOTEBOOKS} >= {"bounce_heights.ipynb", "tumbler_period.ipynb", "pit_energy.ipynb"}


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_each_notebook_runs_and_shows_the_room(path):
    notebook = run(nbformat.read(path, as_version=4))
    kinds = {kind for cell in notebook.cells if cell.cell_type == "code"
             for output in cell.outputs for kind in output.get("data", {})}
    # A frame of the room (a World's PNG) or a clip (HTML with a GIF).
    assert "image/png" in kinds or "text/html" in kinds, kinds
    shown = [output["data"] for cell in notebook.cells if cell.cell_type == "code"
             for output in cell.outputs if "data" in output]
    assert any("data:image/gif;base64" in d.get("text/html", "") or "image/png" in d for d in shown)


def test_a_notebook_whose_law_is_broken_fails():
    notebook = nbformat.read(REPO / "examples" / "notebooks" / "bounce_heights.ipynb", as_version=4)
    asserting = [c for c in notebook.cells if c.cell_type == "code" and "assert np.allclose(ratios, e * e" in c.source]
    assert len(asserting) == 1
    # e in place of e²: the room still follows e², so the notebook must fail.
    asserting[0].source = asserting[0].source.replace("assert np.allclose(ratios, e * e", "assert np.allclose(ratios, e")
    with pytest.raises(CellExecutionError):
        run(notebook)
