"""``run_controller`` in one process, as a notebook or a script of runs uses it: each run gets
its own controller's helper modules, as each Webots controller gets a process of its own."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

import mazesim
from mazesim.errors import MazesimIOError
from mazesim.webots import run_controller

#: A controller that reads its speed from a helper module beside it.
USES_SETTINGS = """from controller import Robot
import settings

robot = Robot()
print("speed", settings.SPEED)
robot.step(32)
"""


def test_each_run_imports_its_own_controllers_helper_modules(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    world = mazesim.load_world("arena")
    for name, speed in (("first", 1.0), ("second", 2.0)):
        folder = tmp_path / name
        folder.mkdir()
        (folder / "settings.py").write_text(f"SPEED = {speed}\n")
        (folder / "controller.py").write_text(USES_SETTINGS)
    first = run_controller(tmp_path / "first" / "controller.py", world, seconds=1.0)
    second = run_controller(tmp_path / "second" / "controller.py", world, seconds=1.0)
    assert (first.exit_status, second.exit_status) == (0, 0), first.error + second.error
    out = capsys.readouterr().out
    assert out.splitlines() == ["speed 1.0", "speed 2.0"]
    assert "settings" not in sys.modules


def test_a_helper_edited_between_two_runs_is_read_again(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    world = mazesim.load_world("arena")
    (tmp_path / "controller.py").write_text(USES_SETTINGS)
    for speed in (1.0, 3.25):
        (tmp_path / "settings.py").write_text(f"SPEED = {speed}\n")
        run = run_controller(tmp_path / "controller.py", world, seconds=1.0)
        assert run.exit_status == 0, run.error
    assert capsys.readouterr().out.splitlines() == ["speed 1.0", "speed 3.25"]


def test_modules_of_a_folder_the_controller_puts_on_its_path_are_forgotten_too(
    tmp_path: Path,
) -> None:
    library = tmp_path / "libraries" / "shared"
    library.mkdir(parents=True)
    (library / "epuck_helpers.py").write_text("WHEEL_RADIUS = 0.0205\n")
    folder = tmp_path / "controllers" / "uses_library"
    folder.mkdir(parents=True)
    controller = folder / "uses_library.py"
    controller.write_text(
        "import os, sys\n"
        "sys.path.append(os.path.join('..', '..', 'libraries', 'shared'))\n"
        "import epuck_helpers\n"
        "import json\n"
        "from controller import Robot\n"
        "Robot().step(32)\n"
    )
    run = run_controller(controller, mazesim.load_world("arena"), seconds=1.0)
    assert run.exit_status == 0, run.error
    assert "epuck_helpers" not in sys.modules
    assert "json" in sys.modules, "a module of the interpreter's own path stays loaded"


def test_a_package_of_a_folder_the_controller_puts_on_its_path_is_not_called_missing(
    tmp_path: Path,
) -> None:
    """A controller that puts ``..`` (its project's ``controllers/``) on ``sys.path`` imports
    another controller's folder as a package: that is its own code, not an uninstalled package;
    a package installed nowhere still is."""
    from mazesim.webots.requirements import missing_packages, path_additions

    controllers = tmp_path / "controllers"
    (controllers / "coach").mkdir(parents=True)
    (controllers / "coach" / "settings.py").write_text("import json\n")
    agent = controllers / "agent"
    agent.mkdir()
    (agent / "agent.py").write_text(
        "import sys, os\n"
        "sys.path.append('..')\n"
        "sys.path.insert(0, os.path.join('..', 'coach'))\n"
        "from coach.settings import json\n"
        "import settings\n"
        "import no_such_package_anywhere\n"
    )
    assert path_additions(str(agent / "agent.py")) == [str(controllers), str(controllers / "coach")]
    assert missing_packages(str(agent / "agent.py")) == ["no_such_package_anywhere"]


def test_a_module_on_a_path_made_from_the_controllers_own_file_is_its_own(
    tmp_path: Path,
) -> None:
    """A controller that finds its project's ``controllers/`` from its own ``__file__``
    (``Path(__file__).resolve().parent.parent``, through names, or ``os.path`` calls) and puts
    it on ``sys.path`` imports a module kept there: its own code, not an uninstalled package
    (#33)."""
    from mazesim.webots.requirements import missing_packages, path_additions

    controllers = tmp_path / "controllers"
    (controllers / "member").mkdir(parents=True)
    (controllers / "team_common.py").write_text("import math\n")
    member = controllers / "member" / "member.py"
    member.write_text(
        "import os, sys\n"
        "from pathlib import Path\n"
        "CURRENT_DIR = Path(__file__).resolve().parent\n"
        "CONTROLLERS_DIR = CURRENT_DIR.parent\n"
        "if str(CONTROLLERS_DIR) not in sys.path:\n"
        "    sys.path.insert(0, str(CONTROLLERS_DIR))\n"
        "sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'lib'))\n"
        "sys.path.append(str(Path(__file__).parents[2] / 'libraries'))\n"
        "from team_common import math\n"
        "import no_such_package_anywhere\n"
    )
    assert path_additions(str(member)) == [
        str(controllers),
        str(controllers / "lib"),
        str(tmp_path / "libraries"),
    ]
    assert missing_packages(str(member)) == ["no_such_package_anywhere"]


def test_a_webots_controller_folder_runs_the_file_named_after_it(tmp_path: Path) -> None:
    folder = tmp_path / "controllers" / "wanderer"
    folder.mkdir(parents=True)
    (folder / "settings.py").write_text("SPEED = 1.5\n")
    (folder / "wanderer.py").write_text(USES_SETTINGS)
    run = run_controller(folder, mazesim.load_world("arena"), seconds=1.0)
    assert run.exit_status == 0, run.error
    assert run.controller == str(folder / "wanderer.py")
    empty = tmp_path / "controllers" / "empty"
    empty.mkdir()
    with pytest.raises(MazesimIOError, match="holding empty.py"):
        run_controller(empty, mazesim.load_world("arena"), seconds=1.0)


def test_the_pythonpath_of_a_runtime_ini_beside_the_controller_is_on_its_path(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """Webots sets the ``[environment variables with paths]`` of a controller folder's
    ``runtime.ini`` in the controller's environment (``:``-separated paths relative to the
    folder, ``$(NAME)`` the environment's): a module of another controller's folder that its
    ``PYTHONPATH`` names is imported, and not called a missing package."""
    controllers = tmp_path / "controllers"
    (controllers / "driver").mkdir(parents=True)
    (controllers / "driver" / "shared_words.py").write_text("WORD = 'from the driver'\n")
    slave = controllers / "slave"
    slave.mkdir()
    (slave / "slave.py").write_text(
        "from controller import Robot\n"
        "from shared_words import WORD\n"
        "print(WORD)\n"
        "Robot().step(32)\n"
    )
    monkeypatch.setenv("SHARED_LIBRARIES", str(tmp_path / "libraries"))
    monkeypatch.delenv("NOT_SET_ANYWHERE", raising=False)
    (slave / "runtime.ini").write_bytes(
        b"; Webots runtime.ini\r\n[environment variables with paths]\r\n"
        b"PYTHONPATH=$(NOT_SET_ANYWHERE)/lib:../driver/:$(SHARED_LIBRARIES)\r\n"
    )
    run = run_controller(slave / "slave.py", mazesim.load_world("arena"), seconds=1.0)
    assert run.exit_status == 0, run.error
    assert capsys.readouterr().out.splitlines() == ["from the driver"]
    assert "shared_words" not in sys.modules
    assert str(controllers / "driver") not in sys.path
    from mazesim.webots.requirements import missing_packages, runtime_python_paths

    assert missing_packages(str(slave / "slave.py")) == []
    assert runtime_python_paths(str(slave / "slave.py")) == [
        str(controllers / "driver"),
        str(tmp_path / "libraries"),
    ]
