"""A Lidar and a RangeFinder of a world before R2022a look along their -z axis, as a Camera of
such a world does, not along their x axis (Webots' Y-up device frame: x right, y up, z back; the
R2022a converter turned them to look along x). A public maze mapper of R2020b (an LDS-01 lidar
in the e-puck's turret, its left, middle and right points read as walls beside and ahead) read
the wall on its right as ahead and the one behind as on its left: each device scanned a quarter
turn to the right of where it looks.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from supervised_world import supervisor_in

#: A one-layer lidar and a range finder of three points over 3.1 rad, unturned in the turret.
DEVICES = (
    'Lidar { name "lidar" horizontalResolution 3 fieldOfView 3.1 numberOfLayers 1 maxRange 4 }\n'
    'RangeFinder { name "depth" width 3 height 1 fieldOfView 3.1 maxRange 4 }\n'
)


def _world(release: str) -> str:
    """An e-puck at the origin beside one wall, 20 cm to its left and 2 m long, in a world of
    ``release``: an R2022a-on file writes it Z-up (the robot looks along x, its left is y), an
    older one Y-up (the robot looks along -z, its left is -x)."""
    wall = "0 0.2 0.05" if release >= "R2022a" else "-0.2 0.05 0"
    size = "2 0.02 0.1" if release >= "R2022a" else "0.02 0.1 2"
    return (
        f"#VRML_SIM {release} utf8\nWorldInfo {{ basicTimeStep 16 }}\n"
        f"Solid {{ translation {wall} children [ Shape {{ geometry Box {{ size {size} }} }} ] "
        f"boundingObject Box {{ size {size} }} }}\n"
        f'E-puck {{ supervisor TRUE controller "<extern>" turretSlot [ {DEVICES} ] }}\n'
    )


@pytest.mark.usefixtures("fresh_robot")
@pytest.mark.parametrize("release", ["R2021b", "R2020b", "R2023b"])
def test_a_lidar_and_a_range_finder_look_ahead_in_a_world_of_every_release(
    tmp_path: Path, release: str
) -> None:
    robot = supervisor_in(tmp_path, _world(release))
    lidar, depth = robot.getDevice("lidar"), robot.getDevice("depth")
    lidar.enable(16)
    depth.enable(16)
    robot.step(16)
    left, middle, right = lidar.getRangeImage()
    # Points at 1.55, 0.52 and -0.52 rad from ahead: the wall's near face (0.19 m to the left)
    # is 0.19 / sin(1.55) m along the first, 0.19 / sin(0.52) m along the second, and no
    # wall stands to the right.
    assert left == pytest.approx(0.19 / math.sin(1.55), abs=0.02)
    assert middle == pytest.approx(0.19 / math.sin(3.1 / 6), abs=0.02)
    assert right == math.inf
    # The range finder's depth runs along its axis: the wall's face reads its depth ahead
    # along the left pixel only.
    image = depth.getRangeImage()
    assert image[0] < 1.0 and image[2] == math.inf
