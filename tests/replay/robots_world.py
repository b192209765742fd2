"""A world of three robots in a walled box, and its demo recorded once for the replay tests."""

from __future__ import annotations

from pathlib import Path

from recorded_demos import record_demo

THREE_ROBOTS = """format = "mazesim-world"
version = 1
name = "three-robots"

[[walls]]
center = [0.0, 0.305]
size = [0.62, 0.01]

[[walls]]
center = [0.0, -0.305]
size = [0.62, 0.01]

[[walls]]
center = [0.305, 0.0]
size = [0.01, 0.62]

[[walls]]
center = [-0.305, 0.0]
size = [0.01, 0.62]

[[robots]]
name = "ann"
x = -0.15
y = -0.15
yaw = 0.7

[[robots]]
name = "bob"
x = 0.15
y = -0.1
yaw = 2.0

[[robots]]
name = "cy"
x = 0.0
y = 0.15
yaw = -1.6
profile = "e-puck2"
"""


def record_three_robots(folder: Path) -> dict[str, Path]:
    """Runs ``mazesim demo`` on the three robots for 4 s with ``--record`` and ``--html``; the
    paths of the world, the run, the page and the output folder."""
    paths = {
        "world": folder / "three.toml",
        "run": folder / "three.json.gz",
        "html": folder / "three.html",
        "out": folder / "demo",
    }
    paths["world"].write_text(THREE_ROBOTS)
    outputs = {key: path for key, path in paths.items() if key != "world"}
    record_demo(["--world", str(paths["world"]), "--seconds", "4"], outputs)
    return paths
