"""An e-puck a supervisor imports senses through its node's own sensors, as one of the world
file does: a plain ``Robot`` e-puck whose ``DistanceSensor`` nodes carry their own
``lookupTable``, and an ``E-puck`` PROTO whose rays rise by the PROTO's tilt, read after their
import exactly as the same nodes read when the world file holds them."""

from __future__ import annotations

from pathlib import Path

import pytest

from mazesim.webots import controller
from proximity_probe import plain_robot, probe_world_run

#: The 10-bit proximity table of some course worlds (the e-puck's values scaled to 0..1023).
TEN_BIT = ((0.0, 1023.0, 0.0), (0.005, 868.0, 0.0), (0.01, 539.0, 0.0), (0.02, 169.0, 0.0))
TEN_BIT += ((0.03, 59.0, 0.0), (0.07, 17.0, 0.0))

ARENA = (
    "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nRectangleArena { floorSize 0.5 0.5 }\n"
    'E-puck { translation -0.1 -0.15 0 name "anchor" controller "probe" }\n'
)
#: The nodes the supervisor imports: "ten" 2 cm from the wall ahead, "proto" near "anchor".
NODES = (
    plain_robot(TEN_BIT, name="ten", controller_name="probe"),
    'E-puck { translation -0.05 -0.1 0 rotation 0 0 1 3.1416 name "proto" controller "probe" }',
)
#: A supervisor that imports its ``controllerArgs`` nodes after its first step (none given:
#: it only steps).
IMPORTER = f"""
import sys
from controller import Supervisor

NODES = {NODES!r}
supervisor = Supervisor()
children = supervisor.getRoot().getField("children")
first = True
while supervisor.step(32) != -1:
    if first and sys.argv[1:] == ["import"]:
        for text in NODES:
            children.importMFNodeFromString(-1, text)
    first = False
"""


def supervisor(args: str) -> str:
    """The supervisor's node, its ``controllerArgs`` ``args``."""
    return (
        'Robot { translation 0 0.2 0.3 name "importer" controller "importer" '
        f'controllerArgs [ "{args}" ] supervisor TRUE }}\n'
    )


@pytest.fixture(autouse=True)
def _released() -> None:
    controller.Robot.created = None


def test_an_imported_e_puck_reads_through_its_node_s_own_sensors(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    others = {"importer": IMPORTER}
    held = probe_world_run(
        tmp_path / "held", monkeypatch, ARENA + supervisor("none") + "".join(NODES), others
    )
    imported = probe_world_run(
        tmp_path / "imported", monkeypatch, ARENA + supervisor("import"), others
    )
    assert sorted(imported) == ["anchor", "proto", "ten"]
    ten = [v for row in TEN_BIT for v in row]
    assert imported["ten"]["tables"] == [ten] * 8
    # Its own 10-bit table: the wall 2 cm ahead reads 169 or so, not the built-in table's.
    assert 100.0 < max(imported["ten"]["values"]) <= 1023.0
    for name in ("ten", "proto"):
        assert imported[name]["values"] == held[name]["values"], name
