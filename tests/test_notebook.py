"""A Jupyter user's first notebook, run headless in a real IPython kernel (nbclient): the docs'
quick start prints what the docs show, a pyplot figure and an ``rgb_array`` frame shown as the
docs say show as pictures below their cells, and a progress display draws its bar in the cell's
output (#37)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

nbformat = pytest.importorskip("nbformat", reason="needs the dev tools (make dev-deps)")
nbclient = pytest.importorskip("nbclient", reason="needs the dev tools (make dev-deps)")
pytest.importorskip("ipykernel", reason="needs the dev tools (make dev-deps)")

from docs_blocks import parse_blocks  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
#: A guard against a kernel that hangs, not a speed requirement.
CELL_TIMEOUT_S = 600


def _block(page: str, holding: str) -> tuple[str, str | None]:
    """The Python block of ``docs/page`` holding ``holding``, and the output block after it."""
    path = REPO / "docs" / page
    blocks = parse_blocks(path, path.read_text(encoding="utf-8"), REPO)
    for index, block in enumerate(blocks):
        if block.language == "python" and holding in block.text:
            after = blocks[index + 1] if index + 1 < len(blocks) else None
            return block.text, after.text if after is not None and after.is_output else None
    raise AssertionError(f"no Python block of {page} holds {holding!r}")


def _outputs(cell: Any, kind: str) -> list[Any]:
    return [output for output in cell.outputs if output.output_type == kind]


def _text(cell: Any, name: str) -> str:
    return "".join(o.text for o in _outputs(cell, "stream") if o.name == name)


def _shows_a_picture(cell: Any) -> bool:
    return any(
        "image/png" in output.data
        for output in cell.outputs
        if output.output_type in ("display_data", "execute_result")
    )


@pytest.fixture(scope="module")
def notebook(tmp_path_factory: pytest.TempPathFactory) -> Any:
    quick_start, quick_output = _block("index.md", 'load_world("seed-maze")')
    figure, _ = _block("rl.md", "one maze file a bar")
    frame, _ = _block("watching.md", "Image.fromarray(frame)")
    progress = (
        "from mazesim.cli.progress import ProgressDisplay\n"
        "with ProgressDisplay(unit='steps', bar_delay_s=0.0) as display:\n"
        "    for step in range(1, 201):\n"
        "        display('simulating', step, 200)\n"
    )
    book = nbformat.v4.new_notebook()
    book.cells = [
        nbformat.v4.new_code_cell(code) for code in (quick_start, figure, frame, progress)
    ]
    folder = tmp_path_factory.mktemp("notebook")
    client = nbclient.NotebookClient(
        book,
        timeout=CELL_TIMEOUT_S,
        kernel_name="python3",
        resources={"metadata": {"path": str(folder)}},
    )
    client.execute()
    book.metadata["quick_output"] = quick_output
    return book


def test_the_quick_start_prints_in_a_notebook_what_the_docs_show(notebook: Any) -> None:
    printed = _text(notebook.cells[0], "stdout")
    shown = notebook.metadata["quick_output"]
    assert shown and printed.splitlines() == shown.splitlines(), printed


def test_a_pyplot_figure_shows_below_its_cell(notebook: Any) -> None:
    assert _shows_a_picture(notebook.cells[1]), notebook.cells[1].outputs


def test_an_rgb_array_frame_shows_as_a_picture(notebook: Any) -> None:
    assert _shows_a_picture(notebook.cells[2]), notebook.cells[2].outputs


def test_the_progress_display_draws_its_bar_in_the_cell(notebook: Any) -> None:
    """A kernel's stderr is not a terminal (``isatty()`` is False), yet it redraws a line as
    one: the bar shows, not nothing (a short run's plain-line mode)."""
    drawn = _text(notebook.cells[3], "stderr")
    assert "simulating: 100%|" in drawn and "200/200 steps" in drawn, drawn
