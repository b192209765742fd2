"""What both lockstep bridges (ROS 1 and ROS 2) do when a state goes unanswered, and how a command
holds for a node that commands on a timer of simulated time. Plain Python: no ROS needed.

In lockstep a bridge steps once per command and then publishes the new state; the node answers
each state with one command. A state can go unanswered: a node that answers only from its second
message, one whose first command went out before the bridge listened, a lifecycle node paused by
its manager (its publisher drops what it is given while inactive) and resumed. Bridge and node
then wait for each other. :class:`UnansweredState` says when the bridge sends its state again:
``RESEND_S`` seconds after a state last went out, while a command writer (publisher) is
connected and no command waits; before the first command that is the reset state, afterwards
the last state as it went out (same bytes, same stamp). The run stays the in-process run, step
for step.

A node that commands on a timer of simulated time (``create_timer(0.1, ...)`` with
``use_sim_time``, Nav2's controller at its ``controller_frequency``) slower than the control step
cannot answer each state: after its command the clock moves one step, short of its next tick, and
it waits for time that moves on commands only. Given the node's period (``--command-period``),
:class:`TimerHold` makes the bridge hold each command over whole control steps until the clock
reaches the timer's next tick, as a simulator that runs on would: from the reset state the robot
stands still (no command yet) until the first tick, and a command answering the state stamped
``T`` holds until the first state stamped at or after the next multiple of the period after
``T``. A timer of period ``P`` started before its node's first ``/clock`` (rclpy's and rclcpp's
timers on simulated time, the clock still at zero) fires at the first ``/clock`` at or after each
multiple of ``P``: exactly the state at which the hold ends, so the node answers the state the
bridge waits on. How many steps each command holds is a function of the stamps alone, so the run
is deterministic and equal, field for field, to the in-process run that holds each command over
those steps. A node can let a tick go without a command: one that pairs the ``/scan`` it has with
the ``/tf`` of its stamp at each tick finds, now and then, the scan of the tick's state come and
its transform not yet (each topic arrives on a connection of its own, served by a thread of its
own, so one state's messages reach the node in any order), and skips that tick; on a simulator
whose clock runs on it pairs at the next one, but in lockstep the clock waited for a command that
never came. When no command has come ``SKIPPED_TICK_S`` after a hold ended at a tick, the bridge
takes the tick as let go and holds the last command on to the next tick, as that simulator would
(a node that commands at each tick never sees it): the run is the in-process run with that
command held over both periods.

A node that waits for simulated time at moments the bridge cannot tell from the wire (a timer
counted from the node's first ``/clock``, a ``sleep`` of simulated time after each command, a
``Rate`` made at some later state) waited forever: the bridge waited for its command, the node
for time that moved on commands only. A simulator users run such nodes on (Gazebo, Webots with
``webots_ros2``) keeps its clock moving whether or not a command comes. Given a deadline
(``--command-deadline``), :class:`CommandDeadline` does that and keeps lockstep for every node
that answers in time: once a command has been stepped, when no command comes within the deadline
after a state, the bridge steps with the last command held, then on in real time, one control
step per control step of wall-clock time, until a command comes. A node that answers each state
within the deadline runs the in-process run step for step; a node that waits for time gets it.
How many steps a command holds then depends on when it came, which the stamps record.

A bridge whose node never connects, or that a node left (a test or launch that ended and left its
bridge behind), waited for ever. :class:`IdleTimeout` says when it gives up: once no command has
come and no command writer has been connected for ``--idle-timeout`` seconds of wall-clock time
(``IDLE_TIMEOUT_S`` by default; 0: never), in either mode. A node that is connected, even one
that sends nothing for a long time (a teleop whose user looks away), keeps it running.
"""

from __future__ import annotations

import math

from mazesim.errors import InvalidArgumentError

__all__ = [
    "CommandDeadline",
    "IDLE_CLOCK_AFTER_S",
    "IDLE_EXIT_STATUS",
    "IDLE_TIMEOUT_S",
    "IdleTimeout",
    "MAX_LAG_STEPS",
    "RESEND_S",
    "RealTimePace",
    "SKIPPED_TICK_S",
    "TimerHold",
    "UnansweredState",
    "stamp_nanoseconds",
]

#: Lockstep: seconds after a state went out, a command writer connected and no command come,
#: before the bridge sends the state again.
RESEND_S = 5.0
#: Lockstep: seconds after a state (the reset state, or a later one) went out again unanswered
#: before ``/clock`` runs on its own.
IDLE_CLOCK_AFTER_S = 1.0
#: Lockstep with a command period: wall-clock seconds after a hold ended at the node's tick with
#: no command come, before the bridge takes that tick as let go and holds the last command on
#: (twice the wait before /clock runs on its own: a node slowed down by a loaded machine answers
#: within it).
SKIPPED_TICK_S = 2.0
#: Wall-clock seconds with no command and no command writer connected before a bridge gives up
#: (``--idle-timeout``; 0: never).
IDLE_TIMEOUT_S = 600.0
#: The exit status of a bridge that gave up with no node driving it.
IDLE_EXIT_STATUS = 3


def stamp_nanoseconds(seconds: float) -> int:
    """The stamp of a simulated time in nanoseconds, 1 ns at time zero: ROS reads a time of zero
    as "no clock yet" (a node with simulated time would not start its timers, ``rospy.sleep``
    waits for a clock first), so both bridges stamp the state before the first step 1 ns."""
    return max(round(seconds * 1e9), 1)


class UnansweredState:
    """When a lockstep bridge sends a state again that went unanswered.

    The bridge calls :meth:`went_out` whenever a state goes out (the reset state, a step's state,
    a state sent again) and :meth:`waited_long` on each look; once that says ``RESEND_S`` have
    passed, and a command writer is connected with no command waiting, the bridge sends the state
    again and calls :meth:`resending`.
    """

    def __init__(self, resend_s: float = RESEND_S) -> None:
        self.resend_s = resend_s
        #: When (``time.monotonic()``) a state last went out.
        self.last = 0.0
        #: How many times a state was sent again before the first command, and after it.
        self.resent_reset = 0
        self.resent_last = 0

    def went_out(self, now: float) -> None:
        """A state went out at ``now``."""
        self.last = now

    def waited_long(self, now: float) -> bool:
        """Whether ``RESEND_S`` have passed since a state last went out (or since the last
        look that said so: the wait restarts)."""
        if now - self.last < self.resend_s:
            return False
        self.last = now
        return True

    def resending(self, stepped: bool, step: int, topic: str, fix: str) -> str | None:
        """Counts a state going out again, and says what to say the first time (``None``
        afterwards).

        Args:
            stepped: A command has come (the last state goes out again, not the reset state).
            step: The step whose state goes out again.
            topic: A command topic with a writer connected, named in the message.
            fix: What to run a node that commands on a timer of simulated time with.
        """
        if stepped:
            self.resent_last += 1
            if self.resent_last > 1:
                return None
            return (
                f"lockstep: no command {self.resend_s:g} s after step {step} though {topic} has "
                f"a writer; publishing that step's state again, as it went out, every "
                f"{self.resend_s:g} s until a command comes (a node that let a state go "
                "unanswered, as a lifecycle node paused and resumed does, gets it again; a node "
                f"that commands on a timer of simulated time slower than the control step: {fix})"
            )
        self.resent_reset += 1
        if self.resent_reset > 1:
            return None
        return (
            f"lockstep: no command {self.resend_s:g} s after the reset state though {topic} has "
            f"a writer; publishing the reset state again, every {self.resend_s:g} s until a "
            "command comes (a node that answers only from its second message, or whose first "
            "command went out before the bridge listened, gets another; one still busy with the "
            "first that then answers every message would run a step behind)"
        )


class TimerHold:
    """How long a command holds in lockstep for a node commanding on a timer of simulated time
    (see the module's description).

    Args:
        period_s: The node's timer period in seconds (0: none, every command one step).
        control_step_s: The bridge's control step in seconds.
        origin_ns: When the node's timer counts from: 0 for rcl's timers (made before the
            node's first ``/clock``, they tick at the multiples of the period), the reset
            state's stamp (1 ns) for ``rospy.Rate``, which counts from the time it is made.

    Raises:
        InvalidArgumentError: The period is not finite, negative, or not longer than a control
            step (a node on such a timer answers every state: leave the period out).
    """

    def __init__(self, period_s: float, control_step_s: float, origin_ns: int = 0) -> None:
        if not math.isfinite(period_s) or period_s < 0.0:
            raise InvalidArgumentError(
                f"expected a command period in seconds >= 0 (0: none); found {period_s}"
            )
        if 0.0 < period_s <= control_step_s:
            raise InvalidArgumentError(
                f"expected a command period longer than the control step ({control_step_s:g} "
                f"s); found {period_s:g} s: a node on such a timer answers every state, so "
                "leave --command-period out"
            )
        #: The period in nanoseconds, as rclpy's timers hold it (0: none).
        self.period_ns = int(period_s * 1e9)
        self.origin_ns = origin_ns
        self._until_ns = 0
        #: When (``time.monotonic()``) the last hold ended at a tick with no command since.
        self._ended_at = math.inf
        #: Ticks the node let go without a command, each held on to the next tick.
        self.skipped = 0

    @property
    def active(self) -> bool:
        """Whether commands hold over several steps."""
        return self.period_ns > 0

    def start(self, stamp_ns: int) -> None:
        """A command answers the state stamped ``stamp_ns`` (or the reset state went out): it
        holds until the first state stamped at or after the timer's next tick (the origin plus
        the next multiple of the period)."""
        if self.active:
            ticks = (stamp_ns - self.origin_ns) // self.period_ns + 1
            self._until_ns = self.origin_ns + ticks * self.period_ns
            self._ended_at = math.inf

    def holds(self, stamp_ns: int) -> bool:
        """Whether the command holds for another step after the state stamped ``stamp_ns``."""
        return self.active and stamp_ns < self._until_ns

    def ended(self, now: float) -> None:
        """A command's hold ended at the node's tick at ``now`` (wall clock): its next command
        is due."""
        if self.active:
            self._ended_at = now

    def wait(self, now: float) -> float:
        """Seconds until the tick the last hold ended at counts as let go (``math.inf``: no
        hold waits for a command)."""
        return max(self._ended_at + SKIPPED_TICK_S - now, 0.0)

    def let_go(self, now: float) -> bool:
        """Whether the node let the tick the last hold ended at go: no command has come
        ``SKIPPED_TICK_S`` after."""
        return now >= self._ended_at + SKIPPED_TICK_S

    def holding_on(self) -> str | None:
        """Counts a tick let go, whose command holds on to the next tick (the bridge then calls
        :meth:`start`); says what to say the first time (``None`` afterwards)."""
        self.skipped += 1
        self._ended_at = math.inf
        if self.skipped > 1:
            return None
        return (
            f"lockstep: no command {SKIPPED_TICK_S:g} s after the state at the node's tick; "
            "holding the last command on to its next tick, as a simulator whose clock runs on "
            "would (--command-period: a node that skips a tick, e.g. finding one of the tick's "
            "messages not come yet, commands at the next)"
        )


class CommandDeadline:
    """When a lockstep bridge steps without a command (see the module's description).

    The bridge calls :meth:`commanded` when a command has been stepped (or a reset answered),
    and :meth:`due` on each look; once that says the deadline has passed with no command, it
    steps with the last command held and calls :meth:`stepped`, and keeps doing so, a control
    step of wall-clock time apart, until the next command.

    Args:
        seconds: The deadline in wall-clock seconds (0: none, the bridge waits for a command).
        control_step_s: The bridge's control step in seconds.

    Raises:
        InvalidArgumentError: The deadline is not finite or negative.
    """

    def __init__(self, seconds: float, control_step_s: float) -> None:
        if not math.isfinite(seconds) or seconds < 0.0:
            raise InvalidArgumentError(
                f"expected a command deadline in seconds >= 0 (0: none); found {seconds}"
            )
        self.seconds = seconds
        self.control_step_s = control_step_s
        #: When (``time.monotonic()``) the next step without a command is due.
        self.due_at = math.inf
        #: Steps taken without a command.
        self.steps = 0

    @property
    def active(self) -> bool:
        """Whether the bridge steps without a command."""
        return self.seconds > 0.0

    def commanded(self, now: float) -> None:
        """A command was stepped at ``now`` (or a reset answered): the next step without one
        is due a deadline later."""
        if self.active:
            self.due_at = now + self.seconds

    def wait(self, now: float) -> float:
        """Seconds until the next step without a command (``math.inf``: none is due)."""
        return max(self.due_at - now, 0.0)

    def due(self, now: float) -> bool:
        """Whether a step without a command is due."""
        return now >= self.due_at

    def stepped(self, now: float) -> str | None:
        """Counts a step without a command, taken at ``now``; the next is a control step of
        wall-clock time later. Says what to say the first time (``None`` afterwards)."""
        self.steps += 1
        self.due_at = max(self.due_at + self.control_step_s, now - self.control_step_s)
        if self.steps > 1:
            return None
        return (
            f"lockstep: no command {self.seconds:g} s after a state; stepping with the last "
            "command held, in real time, until one comes (--command-deadline: a node that "
            "waits for simulated time gets it; one that answers each state within the "
            "deadline runs step for step)"
        )


class IdleTimeout:
    """When a bridge nobody drives gives up: once ``seconds`` of wall-clock time have passed with
    no command come and no command writer connected (0: never)."""

    def __init__(self, seconds: float, now: float) -> None:
        if not (math.isfinite(seconds) and seconds >= 0.0):
            raise InvalidArgumentError(
                f"expected an idle timeout in seconds >= 0 (0: never give up); found {seconds}"
            )
        self.seconds = seconds
        self._since = now
        self._commands_seen = 0
        #: Whether the bridge gave up.
        self.expired = False

    def watch(self, now: float, driven: bool) -> bool:
        """Notes a look at the bridge (``driven``: a command writer is connected, or a command
        came since the last look); returns whether the bridge gives up now."""
        if driven or not self.seconds:
            self._since = now
            return False
        self.expired = self.expired or now - self._since >= self.seconds
        return self.expired

    def look(self, now: float, commands: int, connected: bool) -> bool:
        """:meth:`watch` for a bridge that counts the ``commands`` it has had so far
        (``connected``: a command writer is connected now)."""
        driven = connected or commands != self._commands_seen
        self._commands_seen = commands
        return self.watch(now, driven)

    def wait(self, now: float) -> float:
        """Seconds until the bridge would give up if nothing changes (``math.inf``: never)."""
        return max(self._since + self.seconds - now, 0.0) if self.seconds else math.inf

    def message(self, option: str) -> str:
        """What the bridge says as it gives up; ``option``: how its timeout is set."""
        return (
            f"no command came and no node had a command topic open for {self.seconds:g} s; "
            f"giving up ({option} sets how long to wait, 0 for ever)"
        )


#: How many control steps a real-time bridge may fall behind before it stops catching up.
MAX_LAG_STEPS = 5


class RealTimePace:
    """When a real-time ROS 1 bridge (one robot or several) takes its next step: one ``period``
    of wall-clock time after the last, catching up on steps it fell behind by unless that is more
    than :data:`MAX_LAG_STEPS`, when it starts again from now."""

    def __init__(self, period: float, now: float) -> None:
        self.period = period
        self._next = now

    def stepped(self, now: float) -> float:
        """Notes a step taken at ``now``; returns the seconds to wait before the next (0: now)."""
        self._next += self.period
        delay = self._next - now
        if delay < -MAX_LAG_STEPS * self.period:
            self._next = now
        return max(delay, 0.0)
