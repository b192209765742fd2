"""``import mazesim`` does not import gymnasium, and the environments are registered once both are
imported, in either order (``mazesim._gym_registration``)."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

#: Modules ``import mazesim`` must not import: the optional heavy ones.
HEAVY = ("gymnasium", "matplotlib", "PIL", "pettingzoo", "stable_baselines3", "torch", "ray")


def _run(script: str) -> str:
    """What a fresh interpreter prints running ``script`` with warnings as errors."""
    done = subprocess.run(
        [sys.executable, "-W", "error", "-c", script], capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_import_mazesim_imports_neither_gymnasium_nor_any_other_heavy_package() -> None:
    modules = json.loads(_run("import sys, json, mazesim\nprint(json.dumps(sorted(sys.modules)))"))
    assert "mazesim" in modules
    assert [m for m in modules if m.split(".")[0] in HEAVY] == []
    assert [m for m in modules if m.startswith(("mazesim.envs", "mazesim.learn"))] == []


@pytest.mark.parametrize(
    "imports",
    [
        "import mazesim\nimport gymnasium",
        "import gymnasium\nimport mazesim",
        "import mazesim\nimport gymnasium.spaces as spaces\nimport gymnasium",
        "import mazesim.envs\nimport gymnasium",
        "from mazesim.envs import EPuckMazeEnv\nimport gymnasium",
    ],
)
def test_the_environments_are_registered_whichever_is_imported_first(imports: str) -> None:
    script = (
        f"{imports}\n"
        "env = gymnasium.make('mazesim/EPuckMaze-v0')\n"
        "observation, _ = env.reset(seed=0)\n"
        "print(observation.shape, 'mazesim/UnseenMaze-v2' in gymnasium.registry)\n"
    )
    assert _run(script).strip() == "(11,) True"


def test_a_second_import_of_mazesim_adds_no_second_hook() -> None:
    script = (
        "import importlib, sys, mazesim\n"
        "hooks = lambda: [f for f in sys.meta_path if type(f).__name__ == '_GymnasiumFinder']\n"
        "mazesim._gym_registration.register_when_gymnasium_is_imported()\n"
        "print(len(hooks()))\n"
        "import gymnasium\n"
        "print(len(hooks()))\n"
    )
    assert _run(script).split() == ["1", "0"]


def test_without_gymnasium_import_mazesim_works_and_import_gymnasium_fails_as_usual() -> None:
    script = (
        "import sys\n"
        "class Absent:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        "        if name.split('.')[0] == 'gymnasium':\n"
        "            raise ModuleNotFoundError(f'No module named {name!r}', name=name)\n"
        "sys.meta_path.insert(0, Absent())\n"
        "import mazesim\n"
        "mazesim.Simulator(mazesim.load_world('seed-maze'), seed=0).step(1.0, 1.0)\n"
        "try:\n"
        "    import gymnasium\n"
        "except ModuleNotFoundError as error:\n"
        "    print(type(error).__name__, error.name)\n"
    )
    assert _run(script).strip() == "ModuleNotFoundError gymnasium"
