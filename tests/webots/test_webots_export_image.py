"""A supervisor's ``exportImage`` writes the view of the world now, the frame ``--video`` draws,
as a PNG or a JPEG by the file's extension, and refuses other extensions as Webots does (#33)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from mazesim.render.topdown import TopDownRenderer
from mazesim.webots import simulation as simulations
from supervised_world import WORLD, drive, supervisor_in

pytestmark = pytest.mark.usefixtures("fresh_robot")


def video_frame(walls: np.ndarray | None = None) -> np.ndarray:
    """The frame ``--video`` draws of the current simulation (its robot, path and ``walls``)."""
    simulation = simulations.current()
    simulator = simulation.simulator
    profile = simulator.robot
    renderer = TopDownRenderer(
        simulation.world, profile, (400, 400), profile.distance_sensor_range, walls=walls
    )
    return renderer.frame(
        tuple(float(v) for v in simulator.pose),
        bool(simulator.colliding),
        trail=np.column_stack((simulation.xs, simulation.ys)),
    )


def test_the_view_is_written_as_png_and_jpeg_with_the_walls_where_they_are(
    tmp_path: Path,
) -> None:
    supervisor = supervisor_in(tmp_path, WORLD)
    drive(supervisor, 3.0, 5)
    supervisor.exportImage(str(tmp_path / "view.png"), 100)
    png = np.asarray(Image.open(tmp_path / "view.png").convert("RGB"))
    assert png.shape == (400, 400, 3)
    assert np.array_equal(png, video_frame())
    supervisor.exportImage(str(tmp_path / "view.JPEG"), 90)
    with Image.open(tmp_path / "view.JPEG") as jpeg:
        assert jpeg.format == "JPEG"
        lossy = np.asarray(jpeg.convert("RGB"), dtype=np.float64)
    assert np.abs(lossy - png).mean() < 4.0
    # The supervisor moves the gate: the next view draws it where it is now.
    world = simulations.current().world
    walls = np.asarray(world.wall_boxes(), dtype=np.float64)[:, :5].copy()
    gate = int(np.argmin(np.abs(walls[:, 0] - 0.1) + np.abs(walls[:, 1])))
    supervisor.getFromDef("GATE").getField("translation").setSFVec3f([0.1, 0.6, 0.05])
    supervisor.step(32)
    supervisor.exportImage(str(tmp_path / "moved.png"), 100)
    moved = np.asarray(Image.open(tmp_path / "moved.png").convert("RGB"))
    assert not np.array_equal(moved, video_frame())
    walls[gate, 1] += 0.6
    assert np.array_equal(moved, video_frame(walls))


@pytest.mark.parametrize(
    ("name", "quality", "said"),
    [
        ("view.bmp", 90, "unsupported image format '.bmp'"),
        ("view", 90, "unsupported image format '(none)'"),
        ("view.png", 0, "'quality' argument (0) must be between 1 and 100"),
    ],
)
def test_another_extension_or_quality_is_refused_and_nothing_written(
    tmp_path: Path, capfd: pytest.CaptureFixture[str], name: str, quality: int, said: str
) -> None:
    supervisor = supervisor_in(tmp_path, WORLD)
    supervisor.step(32)
    capfd.readouterr()
    supervisor.exportImage(str(tmp_path / name), quality)
    assert f"Error: wb_supervisor_export_image(): {said}" in capfd.readouterr().err
    assert not (tmp_path / name).exists()
