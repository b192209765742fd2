"""A robot whose own frame is not the world file's up convention, stood upright by its
``rotation`` (a Z-up E-puck in a file from R2022a on that keeps ``coordinateSystem "NUE"``;
a body built Y-up in a Z-up file), reads its orientation as Webots gives it: its node's rotation
is ``Rz(heading) T``, T the turn that stands it up (``frames.body_turn``), so ``getOrientation``,
the ``rotation`` field and a rotation a supervisor sets agree with the file; in an NUE file the
compass finds north along the file's x and the InertialUnit reads its attitude in the NUE frame
(Webots' reference manual, InertialUnit: "For the NUE coordinate system, ... the x-z-y
extrinsic sequence; it corresponds to the composition of elemental rotations denoted by YZX";
WorldInfo: NUE is x north, y up, z east) (#32)."""

from __future__ import annotations

import math

import pytest

from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.frames import axis_angle, rotation_matrix
from mazesim.webots.importer import import_wbt_text
from mazesim.webots.scene import read_scene

pytestmark = pytest.mark.usefixtures("fresh_robot")

#: A Z-up E-puck stood up in a later file of the NUE convention: it faces the file's x (north).
NUE_WORLD = """#VRML_SIM R2023b utf8
WorldInfo {
  coordinateSystem "NUE"
}
DEF BOT E-puck {
  rotation 1 0 0 -1.5707963267948966
  supervisor TRUE
  turretSlot [
    Compass {
    }
    InertialUnit {
      name "level"
    }
    InertialUnit {
      rotation 1 0 0 1.5707963267948966
      name "rolled"
    }
  ]
}
"""

#: A body built Y-up (forward its local -z, up its local y) stood up in a Z-up file: it
#: faces +y.
Y_UP_WORLD = """#VRML_SIM R2023b utf8
DEF BOT Robot {
  rotation 1 0 0 1.5707963267948966
  supervisor TRUE
  children [
    HingeJoint {
      jointParameters HingeJointParameters {
        axis -1 0 0
        anchor -0.026 0.02 0
      }
      device [
        RotationalMotor {
          name "left wheel motor"
        }
      ]
      endPoint Solid {
        translation -0.026 0.02 0
      }
    }
    HingeJoint {
      jointParameters HingeJointParameters {
        axis -1 0 0
        anchor 0.026 0.02 0
      }
      device [
        RotationalMotor {
          name "right wheel motor"
        }
      ]
      endPoint Solid {
        translation 0.026 0.02 0
        name "solid(1)"
      }
    }
  ]
  boundingObject Transform {
    translation 0 0.025 0
    rotation 1 0 0 -1.5707963267948966
    children [
      Cylinder {
        height 0.045
        radius 0.035
      }
    ]
  }
  physics Physics {
  }
}
"""

QUARTER = math.pi / 2


def _robot(text: str) -> controller.Supervisor:
    world, report = import_wbt_text(text, "upright.wbt")
    (robot,) = report["robots"]
    scene = read_scene(text, robot.get("model"), robot["line"], robot.get("y_up"))
    prepare(world, seconds=2.0, noise=False, report=report, scene=scene)
    controller.Robot.created = None
    return controller.Supervisor()


def _rows(*angles: tuple[tuple[float, float, float], float]) -> list[float]:
    """The product of axis-angle rotations, row after row."""
    product = rotation_matrix(0.0, 0.0, 1.0, 0.0)
    for (ax, ay, az), angle in angles:
        turn = rotation_matrix(ax, ay, az, angle)
        product = [
            sum(product[3 * i + k] * turn[3 * k + j] for k in range(3))
            for i in range(3)
            for j in range(3)
        ]
    return product


def test_a_z_up_e_puck_in_an_nue_file_reads_its_file_rotation_and_north_along_x() -> None:
    robot = _robot(NUE_WORLD)
    compass = robot.getDevice("compass")
    level, rolled = robot.getDevice("level"), robot.getDevice("rolled")
    for device in (compass, level, rolled):
        device.enable(32)
    # It faces the file's x, which the import turns to -y.
    assert simulations.current().simulator.pose[2] == pytest.approx(-QUARTER, abs=1e-6)
    robot.step(32)
    assert compass.getValues() == pytest.approx([1.0, 0.0, 0.0], abs=1e-6)
    # Rx(-pi/2) in the NUE frame: roll -pi/2; the unit rolled back on the robot reads none.
    assert level.getRollPitchYaw() == pytest.approx([-QUARTER, 0.0, 0.0], abs=1e-6)
    assert rolled.getRollPitchYaw() == pytest.approx([0.0, 0.0, 0.0], abs=1e-6)
    me = robot.getSelf()
    standing = _rows(((1.0, 0.0, 0.0), -QUARTER))
    assert me.getOrientation() == pytest.approx(standing, abs=1e-6)
    ax, ay, az, angle = me.getField("rotation").getSFRotation()
    assert rotation_matrix(ax, ay, az, angle) == pytest.approx(standing, abs=1e-6)


def test_turned_left_it_reads_the_turn_about_the_file_s_y_and_a_set_rotation_turns_it() -> None:
    robot = _robot(NUE_WORLD)
    compass, level = robot.getDevice("compass"), robot.getDevice("level")
    compass.enable(32)
    level.enable(32)
    # A supervisor turns it 0.3 rad left about the file's up (y): Ry(0.3) Rx(-pi/2).
    turned = _rows(((0.0, 1.0, 0.0), 0.3), ((1.0, 0.0, 0.0), -QUARTER))
    field = robot.getSelf().getField("rotation")
    field.setSFRotation(list(axis_angle(turned)))
    assert simulations.current().simulator.pose[2] == pytest.approx(-QUARTER + 0.3, abs=1e-5)
    robot.step(32)
    assert compass.getValues() == pytest.approx([math.cos(0.3), -math.sin(0.3), 0.0], abs=1e-5)
    assert level.getRollPitchYaw() == pytest.approx([-QUARTER, 0.0, 0.3], abs=1e-5)
    assert robot.getSelf().getOrientation() == pytest.approx(turned, abs=1e-5)
    # What it reads back sets it where it is.
    field.setSFRotation(field.getSFRotation())
    assert simulations.current().simulator.pose[2] == pytest.approx(-QUARTER + 0.3, abs=1e-5)


def test_a_body_built_y_up_in_a_z_up_file_reads_the_rotation_that_stands_it_up() -> None:
    robot = _robot(Y_UP_WORLD)
    assert simulations.current().scene.body_y_up
    assert simulations.current().simulator.pose[2] == pytest.approx(QUARTER, abs=1e-6)
    me = robot.getSelf()
    standing = _rows(((1.0, 0.0, 0.0), QUARTER))
    assert me.getOrientation() == pytest.approx(standing, abs=1e-6)
    # Turned half a turn about z by a supervisor, it faces -y.
    half = _rows(((0.0, 0.0, 1.0), math.pi), ((1.0, 0.0, 0.0), QUARTER))
    me.getField("rotation").setSFRotation(list(axis_angle(half)))
    assert math.sin(simulations.current().simulator.pose[2]) == pytest.approx(-1.0, abs=1e-6)
    assert me.getOrientation() == pytest.approx(half, abs=1e-6)
