"""The lockstep rules both ROS bridges share (``mazesim.ros.lockstep``), without ROS: when a state
that went unanswered goes out again, how long a command holds for a node on a timer, and when a
bridge nobody drives gives up."""

from __future__ import annotations

import math
from collections.abc import Callable
from types import SimpleNamespace
from typing import Any

import pytest

from mazesim.errors import InvalidArgumentError
from mazesim.ros.lockstep import (
    MAX_LAG_STEPS,
    RESEND_S,
    SKIPPED_TICK_S,
    CommandDeadline,
    IdleTimeout,
    RealTimePace,
    TimerHold,
    UnansweredState,
)
from ros_support import needs_ros

STEP_NS = 32_000_000


def held_steps(period_s: float, commands: int) -> list[int]:
    """How many steps the reset state's hold and each of ``commands`` commands take, a command
    coming at each state where the hold ends."""
    hold = TimerHold(period_s, STEP_NS / 1e9)
    stamp, counts = 1, []  # the reset state is stamped 1 ns
    for _ in range(commands + 1):
        hold.start(stamp)
        steps = 0
        while True:
            stamp = (stamp // STEP_NS + 1) * STEP_NS
            steps += 1
            if not hold.holds(stamp):
                break
        counts.append(steps)
    return counts


def timer_ticks(period_s: float, until_ns: int) -> list[int]:
    """The stamps at which rclpy's timer of ``period_s`` on simulated time, made before the
    first /clock, fires when /clock goes out every step: the first stamp at or after each
    multiple of the period."""
    period_ns = int(period_s * 1e9)
    fired, tick = [], period_ns
    for stamp in range(STEP_NS, until_ns, STEP_NS):
        if stamp >= tick:
            fired.append(stamp)
            tick = (stamp // period_ns + 1) * period_ns
    return fired


@pytest.mark.parametrize("period_s", [0.1, 0.064, 0.05, 0.25])
def test_a_hold_ends_exactly_where_the_node_s_timer_fires(period_s: float) -> None:
    counts = held_steps(period_s, 40)
    ends = [sum(counts[: i + 1]) * STEP_NS for i in range(len(counts))]
    assert ends == timer_ticks(period_s, ends[-1] + 1)


def test_a_10_hz_timer_with_32_ms_steps_holds_3_or_4_steps() -> None:
    # 0.128, 0.224, 0.32, 0.416, 0.512, 0.608, 0.704, 0.8 (a tick on a step), 0.928 ...
    assert held_steps(0.1, 8) == [4, 3, 3, 3, 3, 3, 3, 3, 4]


def test_without_a_period_every_command_is_one_step() -> None:
    hold = TimerHold(0.0, 0.032)
    hold.start(1)
    assert not hold.active and not hold.holds(1)


@pytest.mark.parametrize("period_s", [0.032, 0.01, -1.0, float("nan"), float("inf")])
def test_a_period_not_longer_than_a_step_is_refused(period_s: float) -> None:
    # NaN and infinities are refused by the surface check, naming the parameter.
    words = "command period|period_s refused: expected a (finite )?number"
    with pytest.raises(InvalidArgumentError, match=words):
        TimerHold(period_s, 0.032)


def test_an_unanswered_state_goes_out_again_every_resend_interval_while_driven() -> None:
    unanswered = UnansweredState()
    unanswered.went_out(100.0)
    assert not unanswered.waited_long(100.0 + RESEND_S - 0.01)
    assert unanswered.waited_long(100.0 + RESEND_S)
    # The wait restarts at each look that says so, and at each state that goes out.
    assert not unanswered.waited_long(100.0 + RESEND_S + 1.0)
    unanswered.went_out(110.0)
    assert not unanswered.waited_long(110.0 + RESEND_S - 0.01)


def test_the_notice_is_said_once_for_the_reset_state_and_once_for_a_step() -> None:
    unanswered = UnansweredState()
    first = unanswered.resending(False, 0, "/cmd_vel", "use free mode")
    assert first is not None and "reset state again" in first
    assert unanswered.resending(False, 0, "/cmd_vel", "use free mode") is None
    later = unanswered.resending(True, 12, "/motor", "use free mode")
    assert later is not None and "after step 12" in later and "/motor" in later
    assert "use free mode" in later
    assert unanswered.resending(True, 13, "/motor", "use free mode") is None
    assert (unanswered.resent_reset, unanswered.resent_last) == (2, 2)


def rate_wakes(period_s: float, origin_ns: int, until_ns: int) -> list[int]:
    """The stamps at which a ``rospy.Rate`` of ``period_s`` made at ``origin_ns`` wakes when
    /clock goes out every step: ``Rate.sleep`` sleeps until the clock reaches its last tick
    plus the period (its ticks are the origin plus the multiples of the period)."""
    period_ns = round(period_s * 1e9)
    woke, tick = [], origin_ns + period_ns
    for stamp in range(STEP_NS, until_ns, STEP_NS):
        if stamp >= tick:
            woke.append(stamp)
            tick += period_ns
    return woke


@pytest.mark.parametrize("period_s", [0.1, 0.064, 0.25])
def test_a_hold_from_the_rate_s_origin_ends_where_rospy_rate_wakes(period_s: float) -> None:
    # rospy.Rate counts from the time it is made, the reset state's 1 ns: a hold counted from 0
    # ended 1 ns short at a tick on a step (0.8 s at 10 Hz), where the rate slept on.
    hold = TimerHold(period_s, STEP_NS / 1e9, origin_ns=1)
    stamp, ends = 1, []
    for _ in range(40):  # a command at each wake, the first at the reset state
        hold.start(stamp)
        stamp = (stamp // STEP_NS + 1) * STEP_NS
        while hold.holds(stamp):
            stamp += STEP_NS
        ends.append(stamp)
    assert ends == rate_wakes(period_s, 1, ends[-1] + 1)
    if period_s == 0.1:  # the tick at 0.8 s + 1 ns is the state at 0.832 s
        assert 800_000_000 not in ends and 832_000_000 in ends


def test_a_command_deadline_steps_once_it_passes_then_every_control_step() -> None:
    deadline = CommandDeadline(0.2, 0.032)
    assert deadline.wait(10.0) == math.inf and not deadline.due(10.0)  # no command yet
    deadline.commanded(10.0)
    assert not deadline.due(10.19) and deadline.wait(10.1) == pytest.approx(0.1)
    assert deadline.due(10.201)
    notice = deadline.stepped(10.201)
    assert notice is not None and "--command-deadline" in notice
    # Then in real time, a control step apart, said once.
    assert not deadline.due(10.231) and deadline.due(10.2325)
    assert deadline.stepped(10.2325) is None and deadline.steps == 2
    deadline.commanded(11.0)  # a command came: the deadline again
    assert not deadline.due(11.1) and deadline.due(11.201)


def test_no_command_deadline_never_steps() -> None:
    deadline = CommandDeadline(0.0, 0.032)
    deadline.commanded(1.0)
    assert not deadline.active and not deadline.due(1e9) and deadline.wait(1.0) == math.inf


@pytest.mark.parametrize("seconds", [-1.0, math.nan, math.inf])
def test_a_command_deadline_that_is_no_time_is_refused(seconds: float) -> None:
    words = "expected a command deadline in seconds|seconds refused: expected a (finite )?number"
    with pytest.raises(InvalidArgumentError, match=words):
        CommandDeadline(seconds, 0.032)


def test_a_tick_let_go_holds_the_last_command_on_to_the_next_tick() -> None:
    # A node pairing each scan with the /tf of its stamp at each tick of a 0.2 s timer found, at
    # one tick, the scan come and its transform not yet, and let the tick go; the clock waited
    # for a command that never came (3 runs of 5 stalled). Once SKIPPED_TICK_S pass with no
    # command after a hold ended, the tick counts as let go and the command holds on.
    hold = TimerHold(0.2, STEP_NS / 1e9, origin_ns=1)
    assert hold.wait(5.0) == math.inf and not hold.let_go(1e9)  # no hold ended yet
    hold.start(1)
    hold.ended(10.0)  # at the state stamped 0.224 s
    assert hold.wait(10.25) == pytest.approx(SKIPPED_TICK_S - 0.25)
    assert not hold.let_go(10.0 + SKIPPED_TICK_S - 1e-3)
    assert hold.let_go(10.0 + SKIPPED_TICK_S)
    notice = hold.holding_on()
    assert notice is not None and "--command-period" in notice and hold.skipped == 1
    assert not hold.let_go(1e9)  # nothing ended since: one hold on per tick let go
    hold.start(224_000_000)  # held on from the tick's state to the next tick, 0.4 s + 1 ns
    assert hold.holds(384_000_000) and not hold.holds(416_000_000)
    hold.ended(12.0)
    assert hold.let_go(12.0 + SKIPPED_TICK_S) and hold.holding_on() is None  # said once
    assert hold.skipped == 2
    hold.start(416_000_000)  # a command came: no tick waits until its hold ends
    assert hold.wait(20.0) == math.inf


def test_without_a_period_no_tick_is_ever_let_go() -> None:
    hold = TimerHold(0.0, STEP_NS / 1e9)
    hold.start(1)
    hold.ended(1.0)
    assert not hold.let_go(1e9) and hold.wait(1.0) == math.inf


def test_a_bridge_nobody_drives_gives_up_after_its_idle_timeout() -> None:
    idle = IdleTimeout(2.0, now=100.0)
    assert not idle.watch(101.9, driven=False) and idle.wait(101.0) == pytest.approx(1.0)
    assert idle.watch(102.0, driven=False) and idle.expired
    assert "for 2 s; giving up (--idle-timeout sets" in idle.message("--idle-timeout")


def test_a_node_connected_keeps_the_bridge_and_the_timeout_counts_from_when_it_left() -> None:
    idle = IdleTimeout(2.0, now=0.0)
    for now in (1.0, 5.0, 50.0):  # a teleop connected, sending nothing
        assert not idle.watch(now, driven=True)
    assert not idle.watch(51.9, driven=False)  # it left at 50 s
    assert idle.watch(52.0, driven=False)


def test_an_idle_timeout_of_zero_never_gives_up() -> None:
    idle = IdleTimeout(0.0, now=0.0)
    assert not idle.watch(1e9, driven=False) and idle.wait(1e9) == math.inf


@pytest.mark.parametrize("seconds", [-1.0, math.nan, math.inf])
def test_an_idle_timeout_that_is_no_time_is_refused(seconds: float) -> None:
    words = "expected an idle timeout in seconds >= 0|seconds refused: expected a (finite )?number"
    with pytest.raises(InvalidArgumentError, match=words):
        IdleTimeout(seconds, now=0.0)


def test_a_real_time_bridge_catches_up_a_few_steps_and_starts_again_after_more() -> None:
    pace = RealTimePace(0.1, now=0.0)
    assert pace.stepped(0.05) == pytest.approx(0.05)  # on time: waits for the next period
    # 0.3 s late (3 steps): no wait until the steps fallen behind are taken.
    assert pace.stepped(0.5) == 0.0
    assert pace.stepped(0.5) == 0.0
    assert pace.stepped(0.5) == 0.0
    assert pace.stepped(0.5) == pytest.approx(0.0)
    assert pace.stepped(0.5) == pytest.approx(0.1)
    # More than MAX_LAG_STEPS behind: it starts again from now, one period on.
    late = 0.6 + (MAX_LAG_STEPS + 2) * 0.1
    assert pace.stepped(late) == 0.0
    assert pace.stepped(late) == pytest.approx(0.1)


def test_a_bridge_counting_its_commands_gives_up_only_after_none_came_and_none_could() -> None:
    idle = IdleTimeout(10.0, now=0.0)
    assert not idle.look(9.0, commands=0, connected=False)
    assert not idle.look(15.0, commands=1, connected=False)  # a command came since: counts anew
    assert not idle.look(24.0, commands=1, connected=False)
    assert not idle.look(30.0, commands=1, connected=True)  # a writer connected: counts anew
    assert not idle.look(39.0, commands=1, connected=False)
    assert idle.look(40.0, commands=1, connected=False) and idle.expired


def test_late_connections_wait_for_a_command_writer_then_get_the_state_motion_first() -> None:
    from mazesim.ros.latched import LateConnections

    late = LateConnections(quiet_s=0.5, lead_s=0.25, writer_wait_s=2.0)
    sent: list[tuple[str, str]] = []
    for topic in ("scan", "odom"):
        late.peer_subscribe(topic, None, lambda message, topic=topic: sent.append((topic, message)))
    state = [("odom", "odom@0"), ("scan", "scan@0")]
    connected = late._last_connected
    # Quiet, but no command writer yet: a node answering at once would lose its command.
    assert late.hand_over(state, {"scan"}, writer_connected=False, now=connected + 1.0) == 0
    assert sent == []
    # Its publisher connected: the motion now, the readings a lead later.
    assert late.hand_over(state, {"scan"}, writer_connected=True, now=connected + 1.1) == 2
    assert sent == [("odom", "odom@0")]
    late.hand_over(state, {"scan"}, writer_connected=True, now=connected + 1.2)
    assert sent == [("odom", "odom@0")]
    late.hand_over(state, {"scan"}, writer_connected=True, now=connected + 1.4)
    assert sent == [("odom", "odom@0"), ("scan", "scan@0")]
    late.hand_over(state, {"scan"}, writer_connected=True, now=connected + 9.0)
    assert len(sent) == 2  # once


def test_late_connections_with_no_command_writer_get_the_state_after_the_writer_wait() -> None:
    from mazesim.ros.latched import LateConnections

    late = LateConnections(quiet_s=0.5, lead_s=0.25, writer_wait_s=2.0)
    sent: list[str] = []
    late.peer_subscribe("pose", None, sent.append)  # rostopic echo /pose, alone
    connected = late._last_connected
    assert late.hand_over([("pose", "pose@0")], set(), False, now=connected + 1.9) == 0
    assert late.hand_over([("pose", "pose@0")], set(), False, now=connected + 2.0) == 1
    assert sent == ["pose@0"]


class _Connection:
    """A stand-in for rospy's connection: what was written to it, and rospy's count of it."""

    def __init__(self) -> None:
        self.written: list[str] = []
        self.stat_num_msg = 0


def _sending_to(c: _Connection) -> Callable[[str], None]:
    # As rospy's publisher hands its listener: a closure over the connection ``c``.
    def publish_single(message: str) -> None:
        c.written.append(message)
        c.stat_num_msg += 1

    return publish_single


def test_a_connection_that_had_the_state_before_its_listener_heard_of_it_is_not_sent_it_again() -> (
    None
):
    from mazesim.ros.latched import LateConnections

    # rospy adds the connection, the bridge publishes a step to it and notes the topic published,
    # then rospy tells the listener of the connection: it has the state already.
    late = LateConnections(quiet_s=0.5, lead_s=0.25, writer_wait_s=2.0)
    had, fresh = _Connection(), _Connection()
    _sending_to(had)("odom@0")  # the step's publish reached it
    late.published("odom")
    late.peer_subscribe("odom", None, _sending_to(had))
    late.peer_subscribe("odom", None, _sending_to(fresh))
    connected = late._last_connected
    assert late.hand_over([("odom", "odom@0")], set(), True, now=connected + 0.5) == 1
    assert had.written == ["odom@0"] and fresh.written == ["odom@0"]
    # A reading's connection that has had a newer reading by its lead is left out too.
    scan = _Connection()
    late.peer_subscribe("scan", None, _sending_to(scan))
    connected = late._last_connected
    state = [("odom", "odom@1"), ("scan", "scan@1")]
    assert late.hand_over(state, {"scan"}, True, now=connected + 0.5) == 1
    _sending_to(scan)("scan@2")
    late.hand_over(state, {"scan"}, True, now=connected + 1.0)
    assert scan.written == ["scan@2"]


def test_the_reset_state_is_kept_off_the_wire_and_handed_to_a_connection_made_before_it() -> None:
    from mazesim.ros.latched import LateConnections, Remembered

    # A node subscribed odom before the bridge started: it connected as the bridge advertised,
    # before the reset state went out. Sent on the wire, it reached the node before its command
    # publisher existed (skipped, then 5 s waiting for the state sent again).
    class Made:
        resolved_name = "/odom"

        def __init__(self) -> None:
            self.wire: list[str] = []

        def publish(self, message: str) -> None:
            self.wire.append(message)

    late = LateConnections(quiet_s=0.5, lead_s=0.25, writer_wait_s=2.0)
    noted: list[tuple[Any, bool]] = []
    made = Made()
    odom = Remembered(made, lambda sent, on_the_wire=True: noted.append((sent, on_the_wire)), late)
    early = _Connection()
    late.peer_subscribe("/odom", None, _sending_to(early))
    late.hold_the_reset_state(lambda: odom.publish("odom@0"))
    assert made.wire == [] and noted == [((made, "odom@0"), False)] and late.pending
    connected = late._last_connected
    assert late.hand_over([("/odom", "odom@0")], set(), False, now=connected + 1.0) == 0
    assert late.hand_over([("/odom", "odom@0")], set(), True, now=connected + 1.1) == 1
    assert early.written == ["odom@0"]
    odom.publish("odom@1")  # the steps go on the wire
    assert made.wire == ["odom@1"] and not late.holding


@needs_ros
def test_the_connection_is_read_from_rospys_own_publisher() -> None:
    # The mechanism relies on rospy's publisher handing its listener a closure over the
    # connection and counting the messages written to it: checked on rospy itself.
    import rospy.topics
    from rospy.impl.transport import OUTBOUND, Transport
    from std_msgs.msg import String

    from mazesim.ros.latched import _connection_of, _had_a_message

    class Connection(Transport):  # type: ignore[misc]
        def write_data(self, data: bytes) -> None:
            self.stat_num_msg += 1

        def fileno(self) -> None:
            return None

        def close(self) -> None:
            # Once, as rospy's own transports close: the publisher's cleanup callback closes
            # the connection again, and Transport.close calls it every time. Unguarded, the
            # publisher's __del__ recursed without end when the garbage collector met it, later,
            # in another test: "Cannot recover from stack overflow", the test process aborted.
            self.closes = getattr(self, "closes", 0) + 1
            if not self.done:
                super().close()

    impl = rospy.topics._PublisherImpl("/odom", String)
    handed: list[Any] = []

    class Listener:
        def peer_subscribe(self, topic: str, publish_all: Any, publish_one: Any) -> None:
            handed.append(publish_one)

    impl.add_subscriber_listener(Listener())
    connection = Connection(OUTBOUND, "probe")
    impl.add_connection(connection)
    assert _connection_of(handed[0]) is connection and not _had_a_message(connection)
    impl.publish(String(data="step"))
    assert _had_a_message(connection)
    impl.close()
    assert connection.done and not impl.connections and connection.closes <= 2


def test_late_connections_wait_for_every_subscription_the_master_lists_for_a_node() -> None:
    from mazesim.ros.latched import LateConnections

    # A Bug-like node subscribed scan then odom; under load its odom connection came 0.7 s
    # after its scan connection. The master lists both: the state waits for the odom one.
    listed = {"/bug": {"/scan", "/odom"}, "/echo": {"/pose"}}
    late = LateConnections(0.5, 0.25, 2.0, graph=lambda: (listed, {}))
    echo, scan, odom = _Connection(), _Connection(), _Connection()
    echo.endpoint_id, scan.endpoint_id, odom.endpoint_id = "/echo", "/bug", "/bug"
    state = [("/pose", "pose@0"), ("/odom", "odom@0"), ("/scan", "scan@0")]
    late.peer_subscribe("/pose", None, _sending_to(echo))
    late.peer_subscribe("/scan", None, _sending_to(scan))
    connected = late._last_connected
    assert late.hand_over(state, {"/scan"}, True, now=connected + 0.6) == 0
    late.peer_subscribe("/odom", None, _sending_to(odom))
    connected = late._last_connected
    assert late.hand_over(state, {"/scan"}, True, now=connected + 0.5) == 3
    late.hand_over(state, {"/scan"}, True, now=connected + 0.8)
    assert (echo.written, odom.written, scan.written) == (["pose@0"], ["odom@0"], ["scan@0"])
    # A subscription the master lists that never connects holds the state the writer wait only.
    late = LateConnections(0.5, 0.25, 2.0, graph=lambda: (listed, {}))
    scan = _Connection()
    scan.endpoint_id = "/bug"
    late.peer_subscribe("/scan", None, _sending_to(scan))
    connected = late._last_connected
    assert late.hand_over(state, {"/scan"}, True, now=connected + 1.9) == 0
    assert late.hand_over(state, {"/scan"}, True, now=connected + 2.0) == 1


def test_late_connections_wait_for_a_command_publisher_the_master_lists_for_a_node() -> None:
    from mazesim.ros.latched import LateConnections

    # The node's subscriptions are in; its cmd_vel publisher is registered with the master but
    # the bridge has not connected to it yet: its first answer would be lost. The state waits
    # for it (another node's writer being connected does not count), at most 10 s.
    subscribed = {"/bug": {"/scan", "/odom"}}
    published = {"/bug": {"/cmd_vel"}, "/teleop": {"/cmd_vel"}}
    late = LateConnections(0.5, 0.25, 2.0, graph=lambda: (subscribed, published))
    scan, odom = _Connection(), _Connection()
    scan.endpoint_id = odom.endpoint_id = "/bug"
    late.peer_subscribe("/scan", None, _sending_to(scan))
    late.peer_subscribe("/odom", None, _sending_to(odom))
    connected = late._last_connected
    state = [("/odom", "odom@0"), ("/scan", "scan@0")]
    others = {"/cmd_vel": {"/teleop"}}.copy  # what the bridge would read now
    assert late.hand_over(state, {"/scan"}, True, now=connected + 3.0, writers=others) == 0
    ready = {"/cmd_vel": {"/teleop", "/bug"}}.copy
    assert late.hand_over(state, {"/scan"}, True, now=connected + 3.1, writers=ready) == 2
    # A publisher that never connects holds the state 10 s, then it goes.
    late = LateConnections(0.5, 0.25, 2.0, graph=lambda: (subscribed, published))
    again = _Connection()
    again.endpoint_id = "/bug"
    late.peer_subscribe("/odom", None, _sending_to(again))
    connected = late._last_connected
    assert late.hand_over(state, {"/scan"}, True, now=connected + 9.9, writers=others) == 0
    assert late.hand_over(state, {"/scan"}, True, now=connected + 10.0, writers=others) == 1


def test_a_hand_over_is_told_in_a_line_and_a_master_not_answering_holds_the_writer_wait() -> None:
    from mazesim.ros.latched import LateConnections

    # Each hand-over says whose connections got the state, when, and what the master listed, so
    # that a log shows why a state went out when it did.
    subscribed = {"/bug": {"/scan"}}
    published = {"/bug": {"/cmd_vel", "/rosout"}}
    told: list[str] = []
    late = LateConnections(0.5, 0.25, 2.0, graph=lambda: (subscribed, published), note=told.append)
    scan = _Connection()
    scan.endpoint_id = "/bug"
    late.peer_subscribe("/scan", None, _sending_to(scan))
    connected = late._last_connected
    ready = {"/cmd_vel": {"/bug"}, "/motor": set()}.copy
    assert late.hand_over([("/scan", "scan@0")], {"/scan"}, True, connected + 0.5, ready) == 1
    assert told == [
        "lockstep: the state handed to late subscriptions (/bug: /scan) 0.50 s after the last "
        "connected; /bug publishes ['/cmd_vel']; command writers connected: "
        "{'/cmd_vel': {'/bug'}, '/motor': set()}"
    ]

    # A master that does not answer: the state waits the writer wait (it went at once).
    def refusing() -> Any:
        raise ConnectionRefusedError("master gone")

    told.clear()
    late = LateConnections(0.5, 0.25, 2.0, graph=refusing, note=told.append)
    late.peer_subscribe("/scan", None, _sending_to(scan))
    connected = late._last_connected
    assert late.hand_over([("/scan", "scan@0")], {"/scan"}, True, connected + 1.9, ready) == 0
    assert late.hand_over([("/scan", "scan@0")], {"/scan"}, True, connected + 2.0, ready) == 1
    assert "the master not answering (ConnectionRefusedError('master gone'))" in told[0]


def test_the_writers_are_read_from_the_callers_rospy_names() -> None:
    from mazesim.ros._ros import writers_connected

    # rospy's subscriber connection keeps the publishing node's caller id (callerid_pub).
    bug, teleop = SimpleNamespace(callerid_pub="/bug"), SimpleNamespace(callerid_pub="/teleop")
    cmd_vel = SimpleNamespace(resolved_name="/cmd_vel", impl=SimpleNamespace(connections=[bug]))
    motor = SimpleNamespace(resolved_name="/motor", impl=SimpleNamespace(connections=[teleop]))
    idle = SimpleNamespace(resolved_name="/action", impl=SimpleNamespace(connections=[]))
    assert writers_connected([cmd_vel, motor, idle]) == {
        "/cmd_vel": {"/bug"},
        "/motor": {"/teleop"},
        "/action": set(),
    }


@needs_ros
def test_rospy_keeps_the_publishers_caller_id_on_a_subscribers_connection() -> None:
    from rospy.impl.tcpros_base import TCPROSTransport, TCPROSTransportProtocol

    transport = TCPROSTransport(TCPROSTransportProtocol("/cmd_vel", None), "/cmd_vel")
    transport._validate_header({"md5sum": "*", "type": "geometry_msgs/Twist", "callerid": "/bug"})
    assert transport.callerid_pub == "/bug"


@needs_ros
def test_a_node_stopping_drops_a_command_to_its_closed_topic_and_says_nothing() -> None:
    # roslaunch's SIGINT sets the node's stop event; rospy's shutdown then closes the topics
    # before rospy.is_shutdown() turns true, and a reading arriving meanwhile met
    # "publish() to a closed topic": a traceback in the launch's log.
    import threading

    import rospy
    from rospy.topics import _PublisherImpl
    from std_msgs.msg import Float64MultiArray

    from mazesim.ros._ros import publish_unless_stopping

    closed = _PublisherImpl("/motor", Float64MultiArray)
    closed.close()
    motor = SimpleNamespace(publish=closed.publish)  # as rospy.Publisher hands a message on
    message = Float64MultiArray(data=[1.0, 2.0])
    stop = threading.Event()
    assert not rospy.is_shutdown()
    with pytest.raises(rospy.ROSException, match="closed topic"):
        publish_unless_stopping(rospy, motor, message, stop)  # a closed topic while running
    stop.set()
    publish_unless_stopping(rospy, motor, message, stop)
