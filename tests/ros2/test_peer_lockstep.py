"""The ROS 2 bridge in lockstep, driven by a peer built on an independent ROS 2 implementation
(``tests/ros2_peer``: ros2-client over RustDDS, ``make ros2-peer``), in a private network namespace
with only the loopback interface: every decoded field of every step equals what the in-process
simulator, given the same commands, says it should be, for 2,000 steps in Humble's layouts and in
Jazzy's, with either distribution's ``cmd_vel``; a peer expecting the other distribution's
layout reports the mismatch.

The expected messages are built here from the simulator's state and the documented topic table
(docs/ros2.md), not with the bridge's encoder.
"""

from __future__ import annotations

import json
import math
import subprocess
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.ros import standard, topics
from mazesim.ros2 import state
from ros2_support import MAZESIM, needs_namespace, needs_ros2, run_in_namespace

ROOT = Path(__file__).resolve().parents[2]
PEER = ROOT / "target" / "ros2-peer" / "release" / "ros2-peer"
needs_peer = pytest.mark.skipif(
    not PEER.exists(), reason="the ROS 2 peer is not built: make ros2-peer"
)
pytestmark = [needs_ros2, needs_namespace, needs_peer]

#: The peer's exit status for a message whose layout is not its distribution's.
LAYOUT_MISMATCH = 3
STEP_NS = 32_000_000


def _bridge(distro: str, steps: int) -> list[str]:
    return [*MAZESIM, "ros2", "bridge", "--ros-distro", distro, "--stop-after", str(steps)]


#: The peer's waits for the reset state and for each step: ceilings that only bound a hang
#: (each wait ends on the messages it gathers), so a loaded machine never reaches them.
CEILINGS = ["--start-timeout", "180", "--step-timeout", "180"]


def _peer(out: Path, *args: str) -> list[str]:
    return [str(PEER), "--out", str(out), *CEILINGS, *args]


def _number(value: float) -> float | str:
    """A number as the peer writes it: non-finite ones as strings."""
    if math.isfinite(value):
        return value
    return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")


def _f32(value: float) -> float | str:
    return _number(float(np.float32(value)))


def _header(stamp_ns: int, frame: str) -> dict[str, Any]:
    sec, nanosec = divmod(stamp_ns, 10**9)
    return {"stamp": {"sec": sec, "nanosec": nanosec}, "frame_id": frame}


def _vector(x: float, y: float, z: float) -> dict[str, Any]:
    return {"x": _number(x), "y": _number(y), "z": _number(z)}


def _quaternion(yaw: float) -> dict[str, Any]:
    x, y, z, w = standard.yaw_quaternion(yaw)
    return {"x": _number(x), "y": _number(y), "z": _number(z), "w": _number(w)}


def _array(labels: list[str], data: list[float]) -> dict[str, Any]:
    dim = [{"label": ",".join(labels), "size": len(data), "stride": len(data)}] if labels else []
    return {"layout": {"dim": dim, "data_offset": 0}, "data": [_number(v) for v in data]}


class Expected:
    """What each step's message set must hold, from an in-process simulator."""

    def __init__(self, distro: str) -> None:
        world = mazesim.load_world("seed-maze")
        self.simulator = simulator = mazesim.Simulator(world, robot="e-puck", seed=0)
        self.robot = simulator.robot
        self.jazzy = distro == "jazzy"
        self.frames = standard.sensor_frames(self.robot)
        tables = state.StateTopics(simulator, distro)
        self.ground = list(zip(tables.ground_names, tables.ground_tables, tables.ground_limits))

    def _range(self, stamp: int, frame: str, limits: tuple[float, float], distance: float) -> Any:
        message = {
            "header": _header(stamp, frame),
            "radiation_type": 1,
            "field_of_view": _f32(0.1),
            "min_range": _f32(limits[0]),
            "max_range": _f32(limits[1]),
            "range": _f32(distance),
        }
        if self.jazzy:
            message["variance"] = 0.0
        return message

    def step(self, step: int, command: dict[str, float] | None) -> dict[str, Any]:
        """Steps the simulator with ``command`` (none: the reset state) and returns the set."""
        simulator = self.simulator
        before = simulator.pose
        seconds = 0.0
        if command is not None:
            linear, angular = command["linear_x"], command["angular_z"]
            simulator.step(*standard.twist_wheel_speeds(linear, angular, self.robot))
            seconds = simulator.control_step_ms / 1000.0
        stamp = max(step * STEP_NS, 1)
        assert stamp == max(round(simulator.time * 1e9), 1)
        distances = standard.ranges(simulator)
        ranges = {
            frame.frame: self._range(stamp, frame.frame, (frame.min_range, frame.max_range), d)
            for frame, d in zip(self.frames, distances)
        }
        readings = simulator.ground_sensors().tolist()
        for (name, table, limits), reading in zip(self.ground, readings):
            ranges[name] = self._range(stamp, name, limits, state.ground_distance(table, reading))
        # Webots' e-puck scan: a ray every 15 degrees from -150 to 150; ps0..ps7 at their angles.
        scan = [0.0] * 21
        angles = {"ps0": -15, "ps1": -45, "ps2": -90, "ps3": -150}
        angles |= {"ps4": 150, "ps5": 90, "ps6": 45, "ps7": 15}
        for frame, distance in zip(self.frames, distances):
            ray = distance if distance <= 0.04 else 0.0
            scan[(angles[frame.frame] + 150) // 15] = ray + 0.035
        x, y, yaw = simulator.pose
        velocity = standard.body_velocity(before, (x, y, yaw), seconds)
        zeros = [0.0] * 36
        return {
            "step": step,
            "command": command,
            "clock": _header(stamp, "")["stamp"],
            "ranges": ranges,
            "scan": {
                "header": _header(stamp, "laser_scanner"),
                "angle_min": _f32(math.radians(-150)),
                "angle_max": _f32(math.radians(150)),
                "angle_increment": _f32(math.radians(15)),
                "time_increment": 0.0,
                "scan_time": _f32(seconds),
                "range_min": _f32(0.044),
                "range_max": _f32(1.035),
                "ranges": [_f32(r) for r in scan],
                "intensities": [],
            },
            "odom": {
                "header": _header(stamp, "odom"),
                "child_frame_id": "base_link",
                "pose": {
                    "position": _vector(x, y, 0.0),
                    "orientation": _quaternion(yaw),
                    "covariance": zeros,
                },
                "twist": {
                    "linear": _vector(velocity.forward, velocity.leftward, 0.0),
                    "angular": _vector(0.0, 0.0, velocity.turn),
                    "covariance": zeros,
                },
            },
            "tf": [
                {
                    "header": _header(stamp, "odom"),
                    "child_frame_id": "base_link",
                    "transform": {"translation": _vector(x, y, 0.0), "rotation": _quaternion(yaw)},
                }
            ],
            "sensors": _array(topics.sensor_names(simulator), topics.sensors_values(simulator)),
            "pose": _array(["x", "y", "yaw", "time"], topics.pose_values(simulator)),
        }


def _differences(found: Any, expected: Any, path: str = "") -> list[str]:
    if isinstance(expected, dict) and isinstance(found, dict):
        keys = sorted(set(found) | set(expected))
        return [
            d
            for key in keys
            for d in _differences(found.get(key), expected.get(key), f"{path}.{key}")
        ]
    if isinstance(expected, list) and isinstance(found, list) and len(found) == len(expected):
        pairs = enumerate(zip(found, expected))
        return [d for i, (f, e) in pairs for d in _differences(f, e, f"{path}[{i}]")]
    return [] if found == expected else [f"{path}: expected {expected!r}, found {found!r}"]


def _drive(
    tmp_path: Path, distro: str, steps: int, *options: str
) -> subprocess.CompletedProcess[str]:
    out = tmp_path / "steps.jsonl"
    peer = _peer(out, "--distro", distro, "--steps", str(steps), "--seed", "34", *options)
    result = run_in_namespace([_bridge(distro, steps)], peer)
    assert result.returncode == 0, result.stderr
    lines = out.read_text().splitlines()
    assert len(lines) == steps + 1  # the reset state, then one set per command
    expected = Expected(distro)
    for line in lines:
        found = json.loads(line)
        differences = _differences(found, expected.step(found["step"], found["command"]))
        assert not differences, f"step {found['step']}: " + "; ".join(differences[:5])
    return result


def test_humble_peer_drives_2000_steps_every_field_equal_in_process(tmp_path: Path) -> None:
    result = _drive(tmp_path, "humble", 2000)
    assert "stopped after 2000 steps" in result.stderr


def test_jazzy_peer_drives_2000_steps_every_field_equal_in_process(tmp_path: Path) -> None:
    _drive(tmp_path, "jazzy", 2000)


@pytest.mark.parametrize(("distro", "cmd_vel"), [("humble", "twist-stamped"), ("jazzy", "twist")])
def test_a_peer_writing_the_other_distribution_s_cmd_vel_drives_too(
    tmp_path: Path, distro: str, cmd_vel: str
) -> None:
    # Webots' drive calibrator writes Twist whatever the distribution, and teleop_twist_keyboard
    # with stamped:=true writes TwistStamped: the bridge reads /cmd_vel as both.
    _drive(tmp_path, distro, 200, "--cmd-vel", cmd_vel)


@pytest.mark.parametrize(
    ("bridge", "peer", "says"),
    [
        # Jazzy's Range goes on with a variance the Humble layout lacks.
        ("jazzy", ["--distro", "humble", "--cmd-vel", "twist-stamped"], "fields this layout lacks"),
        # Humble's Range ends before the variance Jazzy's layout reads.
        ("humble", ["--distro", "jazzy", "--cmd-vel", "twist"], "Range, jazzy layout"),
    ],
)
def test_a_peer_of_the_other_distribution_reports_a_layout_mismatch(
    tmp_path: Path, bridge: str, peer: list[str], says: str
) -> None:
    command = _peer(tmp_path / "steps.jsonl", *peer, "--steps", "5")
    result = run_in_namespace([_bridge(bridge, 5)], command, grace=0.5)
    # The bridge, never driven, is stopped after the grace: 100 more per background failure.
    assert result.returncode % 100 == LAYOUT_MISMATCH, result.stderr
    assert "ros2-peer: layout mismatch" in result.stderr
    assert says in result.stderr
