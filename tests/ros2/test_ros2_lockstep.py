"""The ROS 2 bridge in lockstep, driven from another process over DDS in a private network
namespace: every field of every message equals the in-process simulator's, in Humble's and
Jazzy's layouts, and a driver of the wrong layout is caught."""

from __future__ import annotations

import re
import shlex
import sys
from pathlib import Path

import pytest

import mazesim
from mazesim.ros2.state import StateTopics
from ros2_support import (
    DRIVER,
    MAZESIM,
    TWO_ROBOTS,
    needs_namespace,
    needs_ros2,
    run_in_namespace,
)

pytestmark = [needs_ros2, needs_namespace]


def _bridge(distro: str, steps: int, *extra: str) -> list[str]:
    return [*MAZESIM, "ros2", "bridge", "--ros-distro", distro, "--stop-after", str(steps), *extra]


def _driver(distro: str, steps: int, *extra: str) -> list[str]:
    return [sys.executable, str(DRIVER), "--distro", distro, "--steps", str(steps), *extra]


def test_humble_lockstep_2000_steps_equal_in_process_and_bag_reads_back(tmp_path: Path) -> None:
    bag = tmp_path / "run"
    result = run_in_namespace([_bridge("humble", 2000, "--bag", str(bag))], _driver("humble", 2000))
    assert result.returncode == 0, result.stderr
    assert "2000 steps, every field equal" in result.stdout
    assert "stopped after 2000 steps" in result.stderr
    # The bag holds exactly what went out: one message set per step (the reset state and 2,000
    # steps), /tf_static and /map once; an independent reader decodes it.
    simulator = mazesim.Simulator(mazesim.load_world("seed-maze"), robot="e-puck", seed=0)
    names = [topic.name for topic in StateTopics(simulator, "humble").topics]
    counts: dict[str, int] = {}
    clocks: list[int] = []
    make_reader = pytest.importorskip("mcap.reader").make_reader
    decoder_factory = pytest.importorskip("mcap_ros2.decoder").DecoderFactory
    mcap_file = next(bag.glob("*.mcap"))
    with mcap_file.open("rb") as stream:
        reader = make_reader(stream, decoder_factories=[decoder_factory()])
        for _schema, channel, message, decoded in reader.iter_decoded_messages():
            counts[channel.topic] = counts.get(channel.topic, 0) + 1
            if channel.topic == "/clock":
                clocks.append(decoded.clock.sec * 10**9 + decoded.clock.nanosec)
                assert message.log_time == clocks[-1]
    assert counts == {**{name: 2001 for name in names}, "/tf_static": 1, "/map": 1}
    assert clocks[0] == 1  # never time zero
    assert clocks[1:] == [32_000_000 * step for step in range(1, 2001)]


def test_jazzy_layouts_match_with_the_e_puck2_time_of_flight_sensor() -> None:
    result = run_in_namespace(
        [_bridge("jazzy", 300, "--robot", "e-puck2")],
        _driver("jazzy", 300, "--robot", "e-puck2"),
    )
    assert result.returncode == 0, result.stderr
    assert "300 steps, every field equal" in result.stdout


def test_a_driver_of_the_wrong_layout_is_caught() -> None:
    # Humble's Range (no variance) against a Jazzy bridge: DDS does not match the two types, so
    # the driver receives no Range and says which topics stayed silent.
    result = run_in_namespace(
        [_bridge("jazzy", 1)],
        _driver("jazzy", 1, "--reader-distro", "humble", "--wait", "2"),
        grace=1.0,
    )
    assert result.returncode != 0
    assert "no message within" in result.stderr
    assert "/ps0" in result.stderr and "/gs0" in result.stderr
    assert "/odom" not in result.stderr.split("no message within")[1].split("\n")[0]


@pytest.mark.parametrize(("distro", "cmd_vel"), [("humble", "twist-stamped"), ("jazzy", "twist")])
def test_a_driver_writing_the_other_distribution_s_cmd_vel_drives_too(
    distro: str, cmd_vel: str
) -> None:
    # Webots' test of its e-puck (webots_ros2_tests/test/test_system_epuck.py) writes
    # TwistStamped when ROS_DISTRO says jazzy, Twist otherwise, whatever the simulation speaks.
    result = run_in_namespace([_bridge(distro, 100)], _driver(distro, 100, "--cmd-vel", cmd_vel))
    assert result.returncode == 0, result.stderr
    assert "100 steps, every field equal" in result.stdout
    assert "policy" not in result.stderr and "stopped after 100 steps" in result.stderr


def test_a_nan_command_takes_its_step_keeping_the_wheel_speeds() -> None:
    # A node answering each state with one command waited forever once the bridge dropped
    # its NaN twist; as ROS's diff drive controllers ignore one while time goes on, the step is
    # taken with the wheel speeds of the command before.
    result = run_in_namespace([_bridge("humble", 60)], _driver("humble", 60, "--nan-at", "20"))
    assert result.returncode == 0, result.stderr
    assert "60 steps, every field equal" in result.stdout
    assert result.stderr.count("ignored a command: expected a finite linear.x") == 1


def test_a_driver_that_answers_from_its_second_state_gets_the_reset_state_again() -> None:
    # Webots' e-puck drive calibrator (webots_ros2_epuck/drive_calibrator.py in
    # cyberbotics/webots_ros2) takes its first /odom as its start and answers from the second
    # on: in lockstep nothing came after the first, and bridge and node waited for each other.
    result = run_in_namespace(
        [_bridge("humble", 50)],
        _driver("humble", 50, "--answer-from-second-state", "--wait", "12"),
    )
    assert result.returncode == 0, result.stderr
    assert "50 steps, every field equal" in result.stdout
    assert "publishing the reset state again" in result.stderr
    assert "stopped after 50 steps" in result.stderr


def test_a_node_that_sleeps_on_simulated_time_first_starts_and_keeps_the_in_process_run() -> None:
    # A node that waits for simulated time before its first command (a start-up sleep on
    # /clock, as teleop_twist_keyboard's rospy.sleep under ROS 1) waited forever: lockstep
    # moved the clock only on commands. Once the reset state sent again goes unanswered, /clock
    # runs on its own until the first command; the simulator does not step meanwhile, so every
    # later state is the in-process run's, stamped a whole number of steps later.
    result = run_in_namespace(
        [_bridge("humble", 40)],
        _driver("humble", 40, "--sleep-sim", "0.5", "--wait", "15"),
    )
    assert result.returncode == 0, result.stderr
    assert "40 steps, every field equal" in result.stdout
    assert "/clock now runs on its own" in result.stderr
    ran = re.search(r"/clock ran (\d+) steps before the first command", result.stderr)
    assert ran is not None and int(ran.group(1)) >= 16, result.stderr  # 0.5 s of 32 ms steps


def test_a_node_that_leaves_a_state_unanswered_gets_it_again() -> None:
    # A lifecycle node paused by its manager (its publisher drops the answer) and resumed
    # waits for the next state, and the lockstep bridge for its command: nothing moved again.
    # The bridge now sends that state again as it went out, and the run goes on step for step.
    result = run_in_namespace(
        [_bridge("humble", 30)],
        _driver("humble", 30, "--skip-answer-at", "12", "--wait", "12"),
    )
    assert result.returncode == 0, result.stderr
    assert "30 steps, every field equal" in result.stdout
    assert "no command 5 s after step 12" in result.stderr
    assert "stopped after 30 steps" in result.stderr


@pytest.mark.parametrize("late_at", [1, 12])
def test_a_node_slower_than_the_resend_wait_reads_past_the_state_sent_again(late_at: int) -> None:
    # A node busy for longer than the resend wait (a loaded machine, a slow start) answers the
    # state late; the bridge has sent it again meanwhile, and the copy waits in the node's queues
    # ahead of the next state. The driver reads past it by its stamp and the run goes on step for
    # step: no command twice, no state taken for the next one.
    result = run_in_namespace(
        [_bridge("humble", 20)],
        _driver("humble", 20, "--late-answer-at", str(late_at), "--wait", "12"),
    )
    assert result.returncode == 0, result.stderr
    assert "20 steps, every field equal" in result.stdout
    assert "stopped after 20 steps" in result.stderr


def test_a_node_restarted_while_the_bridge_runs_gets_the_last_state_again() -> None:
    # A node that stops and starts again while the lockstep bridge runs (a crash, an edit, one
    # more `ros2 run`) waited for a state that had gone out before it was there, and the bridge
    # waited for its command: nothing moved again.
    answer = " ".join([sys.executable, "-c", shlex.quote(_ANSWER_ODOM), "10"])
    result = run_in_namespace([_bridge("humble", 20)], ["bash", "-c", f"{answer} && {answer}"])
    assert result.returncode == 0, result.stderr
    first, second = result.stdout.split()
    # The first run answers the reset state and steps 1-9; the second starts from step 10, the
    # state that went out once already (its stamp says so), and drives the bridge to step 20.
    assert first == f"answered:{1}..{9 * 32_000_000}"
    assert second == f"answered:{10 * 32_000_000}..{19 * 32_000_000}"
    assert "stopped after 20 steps" in result.stderr
    assert "a command writer or state reader matched after the last state" in result.stderr


def test_a_robot_s_node_restarted_gets_its_robot_s_state_again_and_no_other_robot_s(
    tmp_path: Path,
) -> None:
    world = tmp_path / "two.toml"
    world.write_text(TWO_ROBOTS)
    answer = [sys.executable, "-c", shlex.quote(_ANSWER_ODOM)]
    west = " ".join([*answer, "40", "/west"])
    east = " ".join([*answer, "10", "/east_1"])
    out = tmp_path / "west.txt"
    result = run_in_namespace(
        [[*MAZESIM, "ros2", "bridge", "--world", str(world)]],
        ["bash", "-c", f"{west} > {out} & {east} && {east} && wait $! && cat {out}"],
        grace=2.0,
    )
    first_east, second_east, west_run = result.stdout.split()
    assert first_east == f"answered:{1}..{9 * 32_000_000}"
    start, end = (int(part) for part in second_east.split(":")[1].split(".."))
    assert start >= 10 * 32_000_000 and end - start == 9 * 32_000_000
    # The west robot's node got every state once: 40 answers, 40 states in a row.
    assert west_run == f"answered:{1}..{39 * 32_000_000}", result.stderr
    assert "(e.g. on /east_1/cmd_vel" in result.stderr


def test_a_world_of_one_robot_runs_in_the_namespace_a_node_names() -> None:
    # The formation controller of ustbmicl-ros2epucksRL/safe-rl-manifold-suite
    # (cosmos/ros2/scripts/formation_controller.py) names its robots' topics /epuck<i>/odom,
    # /epuck<i>/cmd_vel: with num_robots 1 it read /epuck0/odom, which a world of one robot did
    # not publish, and waited in silence.
    answer = [sys.executable, "-c", _ANSWER_ODOM, "20", "/epuck0"]
    result = run_in_namespace([_bridge("humble", 20, "--namespace", "epuck0")], answer)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == [f"answered:{1}..{19 * 32_000_000}"]
    assert "e-puck (namespace /epuck0) in seed-maze" in result.stderr
    assert "stopped after 20 steps" in result.stderr


def test_a_node_waiting_for_odom_before_its_command_writer_gets_the_reset_state() -> None:
    # rclpy.wait_for_message(Odometry, node, '/odom') at start-up (a reliable reader of depth 1,
    # one message), and only then the node's cmd_vel publisher: in lockstep the bridge waited
    # for a command writer before its first state, and both waited in silence.
    node = [sys.executable, "-c", _WAIT_FOR_ODOM]
    result = run_in_namespace([_bridge("humble", 5)], node)
    assert result.returncode == 0, result.stderr
    # The reset state (stamped 1 ns) to the first reader, the first command: step 1, then 4 more.
    assert result.stdout.split() == ["first:1", f"answered:{32_000_000}..{4 * 32_000_000}"]
    assert "stopped after 5 steps" in result.stderr


#: The end of a node's script: answers each /odom with one command until it has answered
#: ANSWERS; prints the stamps of the first and last odometry answered.
_ANSWER_ODOM_UNTIL = """
stamps = []
while len(stamps) < ANSWERS and time.monotonic() < deadline:
    for data in odom.take():
        stamps.append(cdr.decode_clock(data))
        cmd_vel.publish(twist)
    time.sleep(0.002)
cmd_vel.dds.wait_for_acks(120 * 10**9)  # the last command reaches the bridge before this ends
print(f"answered:{stamps[0]}..{stamps[-1]}" if stamps else "answered:nothing")
"""
#: The same after a first command.
_SEND_AND_ANSWER_ODOM = (
    """
twist = cdr.encode_twist((0.05, 0.0, 0.0), (0.0, 0.0, 0.3))
cmd_vel.publish(twist)
"""
    + _ANSWER_ODOM_UNTIL
)


#: Waits for one /odom on a reader of its own (depth 1), then creates its /cmd_vel writer and
#: an /odom reader, sends a first command once the writer matches and answers each /odom.
_WAIT_FOR_ODOM = (
    """
import time
from mazesim.ros2 import cdr
from mazesim.ros2.node import Node
from mazesim.ros2.qos import COMMAND, TopicQos
node = Node("waits_for_odom")
first = node.reader("/odom", "nav_msgs/msg/Odometry", TopicQos(True, False, 1))
deadline = time.monotonic() + 120  # a ceiling for a hang: each wait ends on what it waits for
found = []
while not found and time.monotonic() < deadline:
    found = first.take(1)
    time.sleep(0.005)
print(f"first:{cdr.decode_clock(found[0])}" if found else "first:nothing", flush=True)
odom = node.reader("/odom", "nav_msgs/msg/Odometry", TopicQos(True, False, 10))
cmd_vel = node.writer("/cmd_vel", "geometry_msgs/msg/Twist", COMMAND)
while not cmd_vel.subscribers() and time.monotonic() < deadline:
    time.sleep(0.005)
ANSWERS = 4
"""
    + _SEND_AND_ANSWER_ODOM
)


def test_a_reader_made_before_the_first_command_gets_the_reset_state_at_once() -> None:
    # A node whose cmd_vel writer and /pose reader matched first (the reset state goes out to
    # them), then waits for one /odom on a new reader (rclpy.wait_for_message) before its first
    # command: a volatile reader gets nothing sent before it matched. It waited for the reset
    # state sent again after 5 s; it now gets it once the grace period has passed, as after a
    # reset call.
    node = [sys.executable, "-c", _WAIT_FOR_ODOM_AFTER_THE_RESET_STATE]
    result = run_in_namespace([_bridge("humble", 3)], node)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["reset-pose:1", "odom:1", "answered:32000000..64000000"]
    assert "state reader matched after the last state went out" in result.stderr
    assert "no command 5 s after the reset state" not in result.stderr
    assert "stopped after 3 steps" in result.stderr


#: Makes its /cmd_vel writer and a /pose reader, takes the reset state's /pose, then waits for
#: one /odom on a reader made only then, and answers each /odom from there.
_WAIT_FOR_ODOM_AFTER_THE_RESET_STATE = (
    """
import time
from mazesim.ros2 import cdr
from mazesim.ros2.node import Node
from mazesim.ros2.qos import COMMAND, TopicQos
node = Node("waits_for_odom_late")
pose = node.reader("/pose", "std_msgs/msg/Float64MultiArray", TopicQos(True, False, 10))
cmd_vel = node.writer("/cmd_vel", "geometry_msgs/msg/Twist", COMMAND)
deadline = time.monotonic() + 120  # a ceiling for a hang: each wait ends on what it waits for
found = []
while not found and time.monotonic() < deadline:
    found = pose.take(1)
    time.sleep(0.005)
values = cdr.decode_float64_array(found[0])
print(f"reset-pose:{round(values[3] * 1e9) or 1}", flush=True)
odom = node.reader("/odom", "nav_msgs/msg/Odometry", TopicQos(True, False, 10))
found = []
while not found and time.monotonic() < deadline:
    found = odom.take(1)
    time.sleep(0.005)
print(f"odom:{cdr.decode_clock(found[0])}", flush=True)
ANSWERS = 2
"""
    + _SEND_AND_ANSWER_ODOM
)


def test_a_navigator_given_a_goal_after_the_reset_state_gets_that_state_again() -> None:
    # A navigator that answers /odom only once a goal has come on /goal_pose (rviz2's 2D Goal
    # Pose, here a second after the reset state reached it) let the reset state go by and
    # waited for it sent again after 5 s; the bridge notes the goal and sends it 0.5 s later.
    node = [sys.executable, "-c", _DRIVE_ONCE_A_GOAL_CAME]
    result = run_in_namespace([_bridge("humble", 3)], node)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["reset-pose:1", "answered:1..64000000"]
    assert "or a goal came on /goal_pose" in result.stderr
    assert "no command 5 s after the reset state" not in result.stderr
    assert "stopped after 3 steps" in result.stderr


#: Takes the reset state's /pose, sends a goal on /goal_pose a second later (as a PoseStamped:
#: its CDR written by rosbags), then answers each /odom from there.
_DRIVE_ONCE_A_GOAL_CAME = (
    """
import time
from rosbags.typesys import Stores, get_typestore
from mazesim.ros2 import cdr
from mazesim.ros2.node import Node
from mazesim.ros2.qos import COMMAND, TopicQos
node = Node("navigator")
pose = node.reader("/pose", "std_msgs/msg/Float64MultiArray", TopicQos(True, False, 10))
odom = node.reader("/odom", "nav_msgs/msg/Odometry", TopicQos(True, False, 10))
cmd_vel = node.writer("/cmd_vel", "geometry_msgs/msg/Twist", COMMAND)
goal = node.writer("/goal_pose", "geometry_msgs/msg/PoseStamped", TopicQos(True, False, 10))
deadline = time.monotonic() + 120  # a ceiling for a hang: each wait ends on what it waits for
found = []
while not found and time.monotonic() < deadline:
    found = pose.take(1)
    time.sleep(0.005)
print(f"reset-pose:{round(cdr.decode_float64_array(found[0])[3] * 1e9) or 1}", flush=True)
time.sleep(1.0)  # the user clicks a second after the robot appeared
odom.take()  # the states before the goal go by unanswered
store = get_typestore(Stores.ROS2_HUMBLE)
kind = store.types["geometry_msgs/msg/PoseStamped"]
goal.publish(bytes(store.serialize_cdr(kind(header=store.types["std_msgs/msg/Header"](
    stamp=store.types["builtin_interfaces/msg/Time"](sec=0, nanosec=0), frame_id="map"),
    pose=store.types["geometry_msgs/msg/Pose"](
        position=store.types["geometry_msgs/msg/Point"](x=0.3, y=0.125, z=0.0),
        orientation=store.types["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0))),
    "geometry_msgs/msg/PoseStamped")))
twist = cdr.encode_twist((0.05, 0.0, 0.0), (0.0, 0.0, 0.3))
ANSWERS = 3
"""
    + _ANSWER_ODOM_UNTIL
)


#: Answers each /odom with one /cmd_vel, as many times as its first argument says, in the
#: namespace its second names if any; prints the stamps of the first and last odometry answered.
_ANSWER_ODOM = """
import sys, time
from mazesim.ros2 import cdr
from mazesim.ros2.node import Node
from mazesim.ros2.qos import COMMAND, SENSOR
node = Node("answerer")
namespace = sys.argv[2] if len(sys.argv) > 2 else ""
odom = node.reader(namespace + "/odom", "nav_msgs/msg/Odometry", SENSOR)
cmd_vel = node.writer(namespace + "/cmd_vel", "geometry_msgs/msg/Twist", COMMAND)
node.announce()
stamps = []
deadline = time.monotonic() + 120  # a ceiling for a hang: the loop ends on the answers' count
while len(stamps) < int(sys.argv[1]) and time.monotonic() < deadline:
    for data in odom.take():
        stamps.append(cdr.decode_clock(data))  # a header's stamp opens it, as a Clock's time
        cmd_vel.publish(cdr.encode_twist((0.05, 0.0, 0.0), (0.0, 0.0, 0.3)))
    time.sleep(0.002)
cmd_vel.dds.wait_for_acks(120 * 10**9)  # the last command reaches the bridge before this ends
print(f"answered:{stamps[0]}..{stamps[-1]}" if stamps else "answered:nothing")
sys.exit(0 if len(stamps) == int(sys.argv[1]) else 1)
"""


@pytest.mark.parametrize("period", ["0.1", "0.064"])
def test_a_node_on_a_timer_of_simulated_time_drives_in_lockstep_with_its_period(
    period: str,
) -> None:
    # A node commanding on a timer of simulated time slower than the control step (a 10 Hz
    # create_timer with use_sim_time, 32 ms steps) stepped once and then waited for a tick that
    # never came. With --command-period each command holds until the clock reaches the
    # timer's next tick, whole steps, the robot at rest before the first: the driver fires as
    # rcl's timers do and finds every field of every step equal to the in-process run that
    # holds each command over the same steps.
    result = run_in_namespace(
        [_bridge("humble", 90, "--command-period", period)],
        _driver("humble", 90, "--timer-period", period, "--wait", "60"),
        timeout=150,
    )
    assert result.returncode == 0, result.stderr
    assert "90 steps, every field equal" in result.stdout
    # A command at each tick up to the state of step 89 (2.848 s): 28 of 0.1 s, 44 of 0.064 s.
    assert f"driver: {dict([('0.1', 28), ('0.064', 44)])[period]} commands on a timer" in (
        result.stdout
    )
    assert "stopped after 90 steps" in result.stderr
    assert "publishing" not in result.stderr  # nothing went out twice


def test_a_tick_let_go_holds_the_last_command_on_to_the_next_tick() -> None:
    # A node on a timer that lets a tick go without a command (it pairs each /scan with the
    # /tf of its stamp and found one not come yet) waited for its next tick while the bridge
    # waited for its command. Once SKIPPED_TICK_S pass without one after a hold ended, the
    # bridge holds the last command on to the next tick: the driver, keeping its command over
    # that tick as the node does, finds every field of every step equal to the in-process run.
    result = run_in_namespace(
        [_bridge("humble", 30, "--command-period", "0.1")],
        _driver("humble", 30, "--timer-period", "0.1", "--let-go-tick", "3", "--wait", "60"),
        timeout=150,
    )
    assert result.returncode == 0, result.stderr
    assert "30 steps, every field equal" in result.stdout
    assert "1 ticks let go without a command (--command-period)" in result.stderr


def test_a_node_timing_itself_from_its_first_clock_drives_with_a_command_deadline() -> None:
    # A node that commands every 0.1 s of simulated time counted from the first /clock it reads
    # (not from the multiples of 0.1 s, as rcl's timers, so --command-period cannot foresee its
    # ticks) stepped the bridge once and waited for time that moved on commands only, while the
    # bridge waited for its command. With --command-deadline the bridge steps on, the last
    # command held, once no command has come within the deadline, as a simulator whose clock
    # runs (Gazebo, Webots' ROS 2 driver) does.
    node = [sys.executable, "-c", _FIRST_CLOCK_TIMER, "8"]
    result = run_in_namespace([_bridge("humble", 0, "--command-deadline", "0.2")], node, grace=1.0)
    assert result.returncode == 0, result.stderr
    ticks = [int(stamp) for stamp in result.stdout.split()[1:]]
    assert result.stdout.split()[0] == "commands:8" and len(ticks) == 8, result.stdout
    # Each command at a later /clock, every /clock a whole number of control steps.
    assert all(a < b for a, b in zip(ticks, ticks[1:])), ticks
    assert all(tick % 32_000_000 == 0 for tick in ticks), ticks
    assert "no command 0.2 s after a state; stepping with the last command held" in result.stderr
    assert re.search(r"\d+ steps without a command \(--command-deadline\)", result.stderr)


#: Commands every 0.1 s of simulated time counted from the first /clock it reads, as many times as
#: its argument says, each a twist on /cmd_vel; prints how many and the /clock of each.
_FIRST_CLOCK_TIMER = """
import sys, time
from mazesim.ros2 import cdr
from mazesim.ros2.node import Node
from mazesim.ros2.qos import CLOCK, COMMAND
node = Node("first_clock_timer")
clock = node.reader("/clock", "rosgraph_msgs/msg/Clock", CLOCK)
cmd_vel = node.writer("/cmd_vel", "geometry_msgs/msg/Twist", COMMAND)
node.announce()
twist = cdr.encode_twist((0.05, 0.0, 0.0), (0.0, 0.0, 0.3))
first, now, sent = None, 0, []
deadline = time.monotonic() + 300  # a ceiling for a hang: the loop ends on its count of ticks
while len(sent) < int(sys.argv[1]) and time.monotonic() < deadline:
    for data in clock.take():
        now = cdr.decode_clock(data)
        first = now if first is None else first
    if first is not None and now >= first + (len(sent) + 1) * 100_000_000:
        sent.append(now)
        cmd_vel.publish(twist)
    time.sleep(0.002)
cmd_vel.dds.wait_for_acks(120 * 10**9)  # the last command reaches the bridge before this ends
print(f"commands:{len(sent)}", *sent)
sys.exit(0 if len(sent) == int(sys.argv[1]) else 1)
"""
