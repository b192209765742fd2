"""A Webots world with a supervisor e-puck, a static wall and a movable box, and its
supervisor prepared as ``mazesim webots run`` prepares it: what the tests of a supervisor that
moves and resets the world's Solids share (#33)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from mazesim.webots import controller, import_wbt, prepare
from mazesim.webots.lockstep import run_world
from mazesim.webots.scene import read_scene

#: The tests' Webots project of worlds of several robots.
SWARM = Path(__file__).resolve().parent / "data" / "webots-swarm"

#: An e-puck supervisor at the origin facing +x; a static wall (GATE) 0.1 m ahead; a light box
#: with physics (BOX, a movable body) off to the side, inside a Pose.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 2 2 }
DEF GATE Solid {
  translation 0.1 0 0.05
  children [ Shape { geometry DEF GATE_BOX Box { size 0.02 0.3 0.1 } } ]
  name "gate"
  boundingObject USE GATE_BOX
}
DEF PLACE Pose {
  translation 0.3 0.3 0
  children [
    DEF BOX Solid {
      translation 0 0 0.02
      children [ Shape { geometry DEF BOX_SHAPE Box { size 0.04 0.04 0.04 } } ]
      name "box"
      boundingObject USE BOX_SHAPE
      physics Physics { density -1 mass 0.05 }
    }
  ]
}
DEF EPUCK E-puck { translation 0 0 0 supervisor TRUE controller "<extern>" }
"""


#: A controller that notes its front light sensor's reading (ls0, 4095 in the dark) at every
#: step, and writes them to ``readings.json`` in its folder at its end.
LIGHT_WATCHER = """import json

from controller import Robot

robot = Robot()
ls0 = robot.getDevice("ls0")
ls0.enable(32)
readings = []
while robot.step(32) != -1:
    readings.append(ls0.getValue())
with open("readings.json", "w") as out:
    json.dump(readings, out)
"""


def cruising_controller(speed: float, steps: int | None = None) -> str:
    """The source of a Python controller that drives both wheels at ``speed`` rad/s under
    velocity control, for ``steps`` steps then returns (None: until the run's end)."""
    loop = (
        "while robot.step(int(robot.getBasicTimeStep())) != -1:\n    pass\n"
        if steps is None
        else f"for _ in range({steps}):\n    robot.step(int(robot.getBasicTimeStep()))\n"
    )
    return (
        "import math\n\nfrom controller import Robot\n\nrobot = Robot()\n"
        'for name in ("left wheel motor", "right wheel motor"):\n'
        "    wheel = robot.getDevice(name)\n"
        "    wheel.setPosition(math.inf)\n"
        f"    wheel.setVelocity({speed})\n" + loop
    )


def project_of(tmp_path: Path, world_file: str, text: str, controllers: dict[str, str]) -> Path:
    """A Webots project in ``tmp_path``: a world file named ``world_file`` holding ``text`` in
    its ``worlds`` folder and a Python controller of each name in ``controllers`` (its source);
    the world file."""
    for name, source in controllers.items():
        folder = tmp_path / "controllers" / name
        folder.mkdir(parents=True)
        (folder / f"{name}.py").write_text(source)
    world = tmp_path / "worlds" / world_file
    world.parent.mkdir()
    world.write_text(text)
    return world


def supervisor_of(tmp_path: Path, noise: bool = False, seed: int = 0) -> controller.Supervisor:
    """The e-puck's supervisor in ``WORLD``, as ``mazesim webots run`` prepares it."""
    path = tmp_path / "solids.wbt"
    path.write_text(WORLD)
    world, report = import_wbt(str(path))
    scene = read_scene(WORLD, report["robot_model"], report["robot_line"])
    prepare(world, seconds=60.0, noise=noise, seed=seed, report=report, scene=scene)
    controller.Robot.created = None
    return controller.Supervisor()


def supervisor_in(
    tmp_path: Path, text: str = WORLD, noise: bool = False, robot: str | None = None
) -> controller.Supervisor:
    """The e-puck's supervisor in the world ``text`` (with ``robot``, the robot whose node
    starts with the first line holding it), as ``mazesim webots run`` prepares it (the import
    report's ``path`` is the world file's)."""
    path = tmp_path / "spawn.wbt"
    path.write_text(text)
    line = None if robot is None else text.count("\n", 0, text.index(robot)) + 1
    world, report = import_wbt(str(path), robot_line=line)
    report = dict(report, path=str(path))
    scene = read_scene(text, report["robot_model"], report["robot_line"])
    prepare(world, seconds=60.0, noise=noise, seed=3, report=report, scene=scene)
    controller.Robot.created = None
    return controller.Supervisor()


def slot_readings(
    tmp_path: Path, sensors: str, names: list[str], floor: str = "1 1 1", scenery: str = ""
) -> list[float]:
    """What the DistanceSensors ``sensors`` of an R2025a supervisor E-puck's
    ``groundSensorsSlot`` (3 cm ahead of its centre, 0.3 mm up; named ``names``) read after one
    step, on a floor of colour ``floor`` and roughness 0, beside ``scenery``, noise-free."""
    text = (
        "#VRML_SIM R2025a utf8\nWorldInfo { basicTimeStep 16 }\n"
        "RectangleArena { floorSize 2 2\n"
        f"  floorAppearance PBRAppearance {{ baseColor {floor} roughness 0 metalness 0 }} }}\n"
        f"{scenery}"
        f'E-puck {{ supervisor TRUE controller "<extern>" groundSensorsSlot [ {sensors} ] }}\n'
    )
    robot = supervisor_in(tmp_path, text, noise=False)
    devices = [robot.getDevice(name) for name in names]
    for device in devices:
        device.enable(16)
    robot.step(16)
    return [device.getValue() for device in devices]


def drive(supervisor: controller.Supervisor, speed: float, steps: int) -> None:
    """Turns both wheels at ``speed`` rad/s for ``steps`` steps."""
    for name in ("left wheel motor", "right wheel motor"):
        motor = supervisor.getDevice(name)
        motor.setPosition(math.inf)
        motor.setVelocity(speed)
    for _ in range(steps):
        assert supervisor.step(32) != -1


def front(supervisor: controller.Supervisor) -> float:
    """The sum of the e-puck's two front proximity readings after one step."""
    sensors = [supervisor.getDevice(name) for name in ("ps0", "ps7")]
    for sensor in sensors:
        sensor.enable(32)
    supervisor.step(32)
    return float(sum(sensor.getValue() for sensor in sensors))


def colour_share(camera: Any, colour: tuple[int, int, int]) -> float:
    """The share of ``camera``'s image (BGRA bytes) whose pixels are ``colour`` (red, green,
    blue, 0-255)."""
    image: Any = camera.getImage()
    pixels = [tuple(image[i : i + 3][::-1]) for i in range(0, len(image), 4)]
    return sum(1 for p in pixels if p == colour) / len(pixels)


def run_test_world(name: str, log: Path, monkeypatch: Any) -> list[Any]:
    """Runs the tests' Webots world ``name`` for 3 s, its controllers logging into ``log``
    (``monkeypatch``: pytest's, which sets ``SWARM_LOG``): what each robot did, every
    controller having ended well."""
    monkeypatch.setenv("SWARM_LOG", str(log))
    robots = run_world(str(SWARM / "worlds" / name), seconds=3.0).robots
    assert [r.exit_status for r in robots] == [0] * len(robots)
    return list(robots)
