"""Hostile input at the surfaces a run reaches after it started (issue #15): a supervisor importing
nodes from a file that never ends or has no writer, a multi-robot env given actions of agents it
does not have, pictures of a world whose name no font can draw, under warnings as errors, and a
world run given a second world (``--world``) that it would have left unused.
The supervisor cases run in a child process under the caps of ``hostile.py`` (a FIFO hung the
run)."""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mazesim
from hostile import run_hostile
from mazesim.cli import main
from mazesim.plotting import save_trajectory_png
from mazesim.replay.preview import save_world_preview

TESTS = Path(__file__).resolve().parent

#: A supervisor of ``supervised_world.WORLD`` importing the nodes of ``NODES`` (made by
#: ``MAKE``): the run goes on after Webots' kind of error, printed on stderr and kept in ``said``.
IMPORT_FROM_FILE = f"""
import contextlib, io, os, pathlib, sys, tempfile
sys.path.insert(0, {str(TESTS)!r})
from supervised_world import supervisor_of
folder = pathlib.Path(tempfile.mkdtemp())
supervisor = supervisor_of(folder)
NODES = str(folder / 'nodes.wbo')
MAKE
said = io.StringIO()
with contextlib.redirect_stderr(said):
    supervisor.getRoot().getField('children').importMFNode(-1, NODES)
assert 'importMFNode(): cannot read' in said.getvalue(), said.getvalue()
assert supervisor.step(32) != -1
print('SAID', said.getvalue().strip())
"""

NODE_FILES = {
    "a FIFO no process writes": ("os.mkfifo(NODES)", "FIFO"),
    "an endless device": ("NODES = '/dev/zero'", "regular file"),
    "a folder": ("os.mkdir(NODES)", "folder"),
}


@pytest.mark.parametrize("name", sorted(NODE_FILES))
def test_a_supervisor_importing_nodes_from_no_regular_file_gets_webots_error(name: str) -> None:
    make, says = NODE_FILES[name]
    outcome = run_hostile(IMPORT_FROM_FILE.replace("MAKE", make))
    assert outcome.returncode == 0 and "DONE" in outcome.stdout, outcome.describe()
    assert says in outcome.stdout, outcome.describe()


@pytest.fixture
def swarm() -> Iterator[Any]:
    pytest.importorskip("pettingzoo")
    from mazesim.marl import aggregation_v0

    env = aggregation_v0.parallel_env()
    env.reset(seed=0)
    yield env
    env.close()


def test_an_action_of_an_agent_the_env_does_not_have_is_refused(swarm: Any) -> None:
    actions = {agent: np.zeros(2, np.float32) for agent in swarm.agents}
    actions["epuck_99"] = np.zeros(2, np.float32)
    with pytest.raises(mazesim.InvalidActionError, match=r"unknown agents \['epuck_99'\]"):
        swarm.step(actions)


def test_actions_not_by_agent_name_are_refused_saying_what_they_were(swarm: Any) -> None:
    with pytest.raises(mazesim.InvalidActionError, match="by agent name, found a list"):
        swarm.step([np.zeros(2, np.float32)] * len(swarm.agents))


HEADER = 'format = "mazesim-world"\nversion = 1\n'
WALL = "[[walls]]\ncenter = [0.5, 0.0]\nsize = [0.1, 0.5]\nyaw = 0.0\n"


def test_a_world_named_in_characters_no_font_has_is_drawn_under_warnings_as_errors(
    tmp_path: Path,
) -> None:
    world = mazesim.World.from_toml(f'{HEADER}name = "迷路 미로"\n{WALL}')
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        save_world_preview(world, tmp_path / "preview.png")
        save_trajectory_png(world, [0.0, 0.1], [0.0, 0.0], tmp_path / "path.png")
    assert (tmp_path / "preview.png").stat().st_size > 0
    assert (tmp_path / "path.png").stat().st_size > 0


def test_a_world_run_given_another_world_too_is_refused_naming_both(
    capsys: pytest.CaptureFixture[str],
) -> None:
    wbt = TESTS / "data" / "webots-worlds" / "e-puck.R2023b.wbt"
    assert main(["webots", "run", str(wbt), "--world", "seed-maze", "--seconds", "1"]) == 2
    said = capsys.readouterr().err
    assert "--world chooses the world of a controller's run" in said, said
    assert "'seed-maze'" in said and "e-puck.R2023b.wbt" in said, said
