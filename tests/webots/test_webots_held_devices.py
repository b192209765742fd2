"""A robot answers only for the devices its node holds, as Webots' ``getDevice`` does: a custom
robot mazesim takes for an e-puck (a plain ``Robot`` with the e-puck's wheel motors) has no
``ps0`` or ``camera`` unless its node has one, and an E-puck without its ground sensors module
has no ``gs0``..``gs2`` (the import's ``missing_devices``)."""

from __future__ import annotations

from pathlib import Path

import pytest

from mazesim.webots.importer import import_wbt_text
from mazesim_process import mazesim_command
from native_controllers import NEEDS_COMPILERS, write_source

#: A custom robot: the e-puck's two wheel motors, one LED and a distance sensor of its own.
CUSTOM_ROBOT = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 16 }
RectangleArena { floorSize 1 1 }
Robot {
  children [
    HingeJoint {
      jointParameters HingeJointParameters { axis 0 1 0 anchor 0 0.026 0.02 }
      device [ RotationalMotor { name "left wheel motor" } ]
      endPoint Solid { translation 0 0.026 0.02 }
    }
    HingeJoint {
      jointParameters HingeJointParameters { axis 0 1 0 anchor 0 -0.026 0.02 }
      device [ RotationalMotor { name "right wheel motor" } ]
      endPoint Solid { translation 0 -0.026 0.02 name "right wheel" }
    }
    LED { name "led0" }
    DistanceSensor { translation 0.03 0 0.03 name "ds0" }
  ]
  controller "probe"
}
"""

PYTHON_PROBE = """from controller import Robot
robot = Robot()
print("name", robot.getName(), "model", repr(robot.getModel()))
print("devices", [robot.getDeviceByIndex(i).getName() for i in range(robot.getNumberOfDevices())])
for name in ("ps0", "left wheel sensor", "camera", "left wheel motor", "ds0"):
    print(name, robot.getDevice(name) is not None)
robot.step(16)
"""

C_PROBE = """#include <stdio.h>
#include <webots/robot.h>
int main() {
  wb_robot_init();
  printf("name %s\\n", wb_robot_get_name());
  printf("count %d\\n", wb_robot_get_number_of_devices());
  printf("ps0 %d\\n", (int)wb_robot_get_device("ps0"));
  printf("motor %d\\n", wb_robot_get_device("left wheel motor") != 0);
  wb_robot_step(16);
  wb_robot_cleanup();
  return 0;
}
"""


def run_project(project: Path, world_text: str) -> str:
    """Runs the project's world (``worlds/world.wbt``) for 0.1 s; what it printed, both
    streams."""
    (project / "worlds").mkdir(exist_ok=True)
    (project / "worlds" / "world.wbt").write_text(world_text)
    result = mazesim_command(
        *("webots", "run", "worlds/world.wbt", "--seconds", "0.1", "--out", "out"),
        "--no-progress",
        cwd=project,
    )
    assert result.returncode == 0, result.stderr
    return result.stdout + result.stderr


def test_the_import_lists_the_e_puck_devices_a_custom_robot_lacks() -> None:
    _, report = import_wbt_text(CUSTOM_ROBOT, "custom.wbt")
    lacked = set(report["missing_devices"])
    assert {"ps0", "ps7", "gs0", "ls0", "camera", "left wheel sensor", "speaker"} <= lacked
    assert not {"left wheel motor", "right wheel motor", "led0"} & lacked
    _, report = import_wbt_text(
        "#VRML_SIM R2023b utf8\nE-puck { groundSensorsSlot [ E-puckGroundSensors { } ] }\n",
        "e-puck.wbt",
    )
    assert report["missing_devices"] == []


def test_a_custom_robot_answers_only_for_the_devices_its_node_holds(tmp_path: Path) -> None:
    (tmp_path / "controllers" / "probe").mkdir(parents=True)
    (tmp_path / "controllers" / "probe" / "probe.py").write_text(PYTHON_PROBE)
    out = run_project(tmp_path, CUSTOM_ROBOT)
    assert "name robot model ''\n" in out, "a plain Robot's default name and model"
    assert "devices ['left wheel motor', 'right wheel motor', 'led0', 'ds0']\n" in out
    for name, found in [
        ("ps0", False),
        ("left wheel sensor", False),
        ("camera", False),
        ("left wheel motor", True),
        ("ds0", True),
    ]:
        assert f"{name} {found}\n" in out
    assert 'Device "ps0" was not found on robot "robot"' in out
    assert out.count("holds no device 'ps0'") == 1


@NEEDS_COMPILERS
def test_a_c_controller_finds_no_device_the_node_lacks(tmp_path: Path) -> None:
    write_source(tmp_path / "controllers", "probe", C_PROBE)
    out = run_project(tmp_path, CUSTOM_ROBOT)
    assert "name robot\ncount 4\n" in out
    assert 'Warning: "ps0" device not found.\n' in out and "ps0 0\n" in out
    assert "motor 1\n" in out


@pytest.mark.parametrize("slot", ["", "groundSensorsSlot [ E-puckGroundSensors { } ]"])
def test_an_e_puck_has_ground_sensors_only_with_their_module(tmp_path: Path, slot: str) -> None:
    (tmp_path / "controllers" / "probe").mkdir(parents=True)
    (tmp_path / "controllers" / "probe" / "probe.py").write_text(
        "from controller import Robot\nrobot = Robot()\n"
        "print('found', [robot.getDevice(f'gs{i}') is not None for i in range(3)])\n"
        "print('ps0', robot.getDevice('ps0') is not None)\nrobot.step(16)\n"
    )
    world = f'#VRML_SIM R2023b utf8\nRectangleArena {{ }}\nE-puck {{ controller "probe" {slot} }}\n'
    out = run_project(tmp_path, world)
    assert f"found {[bool(slot)] * 3}\n" in out
    assert "ps0 True\n" in out
    assert out.count("has no ground sensors module") == (0 if slot else 1)


#: A project's own robot PROTO: a plain Robot with the e-puck's wheel motors and one ps0.
PROJECT_PROTO = """#VRML_SIM R2023b utf8
PROTO MyBot [
  field SFVec3f translation 0 0 0
  field SFRotation rotation 0 0 1 0
  field SFString name "mybot"
  field SFString controller "probe"
  field SFString model "my model"
  field SFString customData "from the PROTO"
]
{
  Robot {
    translation IS translation
    rotation IS rotation
    name IS name
    model IS model
    controller IS controller
    customData IS customData
    children [
      HingeJoint { device [ RotationalMotor { name "left wheel motor" } ] endPoint Solid { } }
      HingeJoint {
        device [ RotationalMotor { name "right wheel motor" } ] endPoint Solid { name "r" }
      }
      DistanceSensor { name "ps0" lookupTable [ 0 0 0, 0.1 1000 0 ] }
    ]
  }
}
"""


#: A world of the project holding that PROTO, before its robot's node.
PROTO_WORLD = '#VRML_SIM R2023b utf8\nEXTERNPROTO "../protos/MyBot.proto"\nRectangleArena { }\n'


def run_proto_robot(project: Path, probe: str, robot_node: str) -> str:
    """Runs ``probe`` as the controller of ``robot_node`` (a MyBot instance) in a project
    holding :data:`PROJECT_PROTO`; what it printed."""
    (project / "protos").mkdir(exist_ok=True)
    (project / "protos" / "MyBot.proto").write_text(PROJECT_PROTO)
    (project / "controllers" / "probe").mkdir(parents=True, exist_ok=True)
    (project / "controllers" / "probe" / "probe.py").write_text(
        "from controller import Robot\nrobot = Robot()\n" + probe
    )
    return run_project(project, PROTO_WORLD + robot_node)


def test_a_project_robot_proto_is_read_as_its_proto_builds_it(tmp_path: Path) -> None:
    # Named, modelled and equipped as the PROTO declares and builds it (its own ps0 reading
    # through the table the PROTO gives it, its customData the PROTO's default), though the
    # robot's node in the file is only ``MyBot { }``.
    probe = (
        "print('name', robot.getName(), 'model', robot.getModel())\n"
        "print('ps1', robot.getDevice('ps1') is not None)\n"
        "ps0 = robot.getDevice('ps0')\nps0.enable(32)\nrobot.step(32)\n"
        "print('table', ps0.getLookupTable(), 'max', ps0.getMaxValue())\n"
        "print('data', robot.getCustomData())\n"
    )
    out = run_proto_robot(tmp_path, probe, "MyBot { }\n")
    assert "name mybot model my model\n" in out, "the PROTO's declared defaults"
    assert "ps1 False\n" in out and "holds no device 'ps1'" in out
    assert "table [0.0, 0.0, 0.0, 0.1, 1000.0, 0.0] max 1000.0\n" in out
    assert "data from the PROTO\n" in out
    out = run_proto_robot(tmp_path, probe, 'MyBot { name "rover" model "mk2" }\n')
    assert "name rover model mk2\n" in out
