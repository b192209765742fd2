"""What a newcomer meets first in a notebook or a shell: ``mazesim.<Tab>`` offers the API, and a
world or a simulator left as a cell's last line is drawn."""

from __future__ import annotations

import importlib
import io

import pytest

import mazesim


@pytest.mark.parametrize(
    "name", ["mazesim", "mazesim.envs", "mazesim.learn", "mazesim.controllers"]
)
def test_tab_completion_offers_the_api_not_the_modules_own_imports(name: str) -> None:
    module = importlib.import_module(name)
    listed = dir(module)
    assert set(module.__all__) <= set(listed)
    for own_import in ("annotations", "os", "importlib", "sys"):
        assert own_import not in listed, f"dir({name}) offers {own_import}"
    assert listed == sorted(listed)


def test_tab_completion_offers_the_imported_submodules() -> None:
    import mazesim.envs  # noqa: F401

    assert "envs" in dir(mazesim) and "errors" in dir(mazesim)
    assert "__version__" in dir(mazesim) and "__doc__" in dir(mazesim)


def _picture(obj: object) -> tuple[int, int, bytes]:
    from PIL import Image

    ipython = pytest.importorskip("IPython.core.interactiveshell")
    shell = ipython.InteractiveShell.instance()
    shown, _ = shell.display_formatter.format(obj)
    data = shown["image/png"]
    with Image.open(io.BytesIO(data)) as image:
        return image.width, image.height, image.convert("RGB").tobytes()


def test_a_notebook_draws_a_world_and_a_simulator_not_their_repr() -> None:
    world = mazesim.load_world("seed-maze")
    width, height, drawn = _picture(world)
    assert (width, height) == (400, 400)
    sim = mazesim.Simulator(world, robot="e-puck", seed=0)
    at_start = _picture(sim)[2]
    for _ in range(100):
        sim.step(5.0, 5.0)
    moved = _picture(sim)[2]
    assert len({drawn, at_start, moved}) == 3  # the robot is drawn where it is
    assert repr(world).startswith("World(") and "\n" not in repr(world)
