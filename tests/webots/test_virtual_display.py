"""A controller's Tk and OpenCV windows drawn on a virtual display (Xvfb) and its Qt windows off
screen where ``$DISPLAY`` is not set, as ``mazesim.webots.virtual_display`` does
(docs/webots.md)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import mazesim
from mazesim.webots.requirements import (
    NO_DISPLAY,
    OPENCV_WINDOWS_NOTE,
    QT_OFFSCREEN_NOTE,
    VIRTUAL_DISPLAY_NOTE,
    prepare_controller,
)
from mazesim.webots.runner import run_controller
from mazesim.webots.virtual_display import virtual_display, xvfb_program

needs_xvfb = pytest.mark.skipif(
    xvfb_program() is None, reason="Xvfb is not installed (make test installs Debian's xvfb)"
)

#: A controller whose turtle window a thread opens, and which waits for it before stepping.
TURTLE_CONTROLLER = """import threading, turtle
from controller import Robot
ready = threading.Event()
def draw():
    pen = turtle.Turtle()
    pen.forward(10)
    ready.set()
threading.Thread(target=draw, daemon=True).start()
assert ready.wait(20), "no window"
robot = Robot()
left, right = robot.getDevice("left wheel motor"), robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(3.0)
while robot.step(32) != -1:
    pass
"""


@needs_xvfb
def test_the_virtual_display_is_there_for_the_block_only(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.delenv("DISPLAY", raising=False)
    import tkinter

    with virtual_display() as name:
        assert name.startswith(":") and os.environ["DISPLAY"] == name
        window = tkinter.Tk()
        assert window.winfo_screenwidth() == 1280
        window.destroy()
    assert "DISPLAY" not in os.environ


#: A controller that shows its camera's image in OpenCV windows, as camera line followers do.
OPENCV_CONTROLLER = """import cv2
import numpy as np
from controller import Robot
robot = Robot()
camera = robot.getDevice("camera")
camera.enable(64)
cv2.namedWindow("preview")
left, right = robot.getDevice("left wheel motor"), robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(3.0)
while robot.step(64) != -1:
    image = np.frombuffer(camera.getImage(), np.uint8).reshape(
        (camera.getHeight(), camera.getWidth(), 4))
    cv2.imshow("preview", image)
    cv2.waitKey(1)
"""


@needs_xvfb
@pytest.mark.parametrize(
    ("controller", "module", "note"),
    [
        (TURTLE_CONTROLLER, "tkinter", VIRTUAL_DISPLAY_NOTE),
        (OPENCV_CONTROLLER, "cv2", OPENCV_WINDOWS_NOTE),
    ],
    ids=["tk", "opencv"],
)
def test_a_controller_with_windows_and_no_display_runs_on_a_virtual_one(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, controller: str, module: str, note: str
) -> None:
    pytest.importorskip(module)
    monkeypatch.delenv("DISPLAY", raising=False)
    (tmp_path / "mouse.py").write_text(controller)
    prepared = prepare_controller(str(tmp_path / "mouse.py"))
    assert prepared.runnable and prepared.virtual_display
    assert NO_DISPLAY not in prepared.missing and note in prepared.notes
    run = run_controller(str(tmp_path / "mouse.py"), mazesim.load_world("arena"), seconds=1.0)
    assert run.exit_status == 0, run.error
    assert run.steps > 0 and run.distance_m > 0.05
    assert "DISPLAY" not in os.environ


def test_opencv_without_its_windows_needs_no_display(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("DISPLAY", raising=False)
    (tmp_path / "counter.py").write_text(
        "import cv2\nfrom controller import Robot\nprint(cv2.countNonZero)\nRobot().step(64)\n"
    )
    prepared = prepare_controller(str(tmp_path / "counter.py"))
    assert not prepared.virtual_display and OPENCV_WINDOWS_NOTE not in prepared.notes


def test_an_opencv_controller_without_a_display_or_xvfb_is_not_started(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.setattr("mazesim.webots.virtual_display.xvfb_program", lambda: None)
    (tmp_path / "follower.py").write_text(OPENCV_CONTROLLER)
    prepared = prepare_controller(str(tmp_path / "follower.py"))
    assert NO_DISPLAY in prepared.missing and not prepared.runnable


def test_a_qt_controller_without_a_display_draws_off_screen(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("QT_QPA_PLATFORM", raising=False)
    # The view imports Qt only where a display is asked for: read, not run.
    (tmp_path / "view.py").write_text(
        "import os\nif os.environ.get('MAZESIM_TEST_NEVER_SET'):\n"
        "    from PySide6.QtWidgets import QApplication\n"
        "PLATFORM = os.environ.get('QT_QPA_PLATFORM')\n"
    )
    (tmp_path / "mouse.py").write_text(
        "import os\nimport view\nfrom controller import Robot\n"
        "print('platform', view.PLATFORM)\nRobot().step(32)\n"
    )
    prepared = prepare_controller(str(tmp_path / "mouse.py"))
    assert prepared.environment == {"QT_QPA_PLATFORM": "offscreen"}
    assert QT_OFFSCREEN_NOTE in prepared.notes
    run = run_controller(
        str(tmp_path / "mouse.py"), mazesim.load_world("arena"), seconds=0.1, prepared=prepared
    )
    assert run.exit_status == 0, run.error
    assert "platform offscreen" in capsys.readouterr().out
    assert "QT_QPA_PLATFORM" not in os.environ
    monkeypatch.setenv("QT_QPA_PLATFORM", "xcb")  # the user's own choice is kept
    assert prepare_controller(str(tmp_path / "mouse.py")).environment == {}
