"""The lockstep ROS 1 bridge's latched state, handed to a subscription that connects late once,
in the order the state went out.

rospy's latched publisher sends its last message to each subscription as that subscription
connects, in the order they connect. A node that answers each ``scan`` with the latest ``odom``
and subscribes ``scan`` first received the latched scan before any odometry, skipped it, and
waited 5 s for the state sent again. Sending the whole state again when a subscriber connects
gave a recorder (``rosbag record``, ``rostopic echo``) connected earlier a second copy.

The rule that holds for both: each state topic's connection gets the state it missed once, and
not on connecting but when no new connection has come for :data:`QUIET_S` (a node's
subscriptions connect within a few hundred milliseconds of each other), all such connections
together, in two parts as the ROS 2 bridge sends its first state: the motion (``/clock``,
``pose``, ``odom``, ``/tf``) first, the sensors' readings (``sensors``, the ranges, ``scan``)
:data:`LEAD_S` later. rospy takes each connection's messages on a thread of its own, so messages
sent one after the other on two connections may be served in either order; a quarter of a
second apart, the node above has its odometry before the scan. A connection that receives a
newer message on its topic meanwhile (a step) is not sent the old one. The hand-over is a state
going out: the bridge's wait before it sends a state unanswered again
(:class:`~mazesim.ros.lockstep.UnansweredState`) counts from it, and does not run out while
connections wait for it (:attr:`LateConnections.pending`). It counted from the reset state
alone: a node whose subscriptions connected about 5 s after the bridge started (a slow start
under load) had the reset state sent again as it connected, and a recorder that had the
hand-over received it twice.

A node that publishes its first command as soon as the state comes lost it when the bridge had
not connected to its command publisher yet (rospy drops a message to a subscriber not yet
connected), and waited 5 s for the state sent again: the bridge connects to a new publisher
only after the master tells it of one, which under load took longer than :data:`QUIET_S`. So
the connections waiting get the state once a command writer is connected to the bridge too, or
:data:`WRITER_WAIT_S` after the last connection when none comes (a recorder or ``rostopic echo``
alone). The publishers still say they are latching (the ``latching`` connection header), so
``rosbag`` records them as latched topics.

A node's subscriptions connect one by one, each on a thread of its own; under load the last one
came more than :data:`QUIET_S` after the first, and the node above had its scan before its odom
subscription had connected (and then waited 5 s for the state sent again). The master knows each
node's subscriptions before they connect (a subscription registers, then connects), so the
state waits, up to :data:`WRITER_WAIT_S` after the last connection, until every subscription of
the bridge's state topics that the master lists for a node with a connection waiting has
connected (``graph``: the master's subscribers and publishers, each node's topics). Likewise a
node's command publisher: under load the bridge connected to it more than 2 s after the node's
subscriptions had, the state went out, the node's answer was lost and it waited 5 s for the
state sent again; so while the master lists a node waiting as a publisher of a command topic
that the bridge is not connected to yet, the state waits for it, up to :data:`WRITER_COMING_S`.

The reset state goes out by the same rule, never on the wire
(:meth:`LateConnections.hold_the_reset_state`): a node subscribed before the bridge started
connects as the bridge advertises its publishers, one by one, and the reset state published
right after reached it before its command publisher existed (skipped, then 5 s waiting for the
state sent again).

Each hand-over is told in a line (``note``; the bridge logs it): whose connections got the state,
how long after the last one connected, what the master listed of those nodes' command topics and
which command writers the bridge was connected to. A master that does not answer holds the state
:data:`WRITER_WAIT_S` after the last connection (it went at once before), and the line says so.

rospy adds a connection to its publisher before it tells the listener of it: a state published
in between reaches the connection, and the connection then waits for that state again. So a
connection that has had any message on its topic by the time of the hand-over (rospy's count of
messages written to it, ``stat_num_msg``) is not sent the state: it has that state or a newer
one. rospy hands the listener a function sending to the connection alone (``publish_single``,
a closure over the connection ``c``); the connection is read from that closure.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Container, Iterable, Mapping
from typing import Any

from mazesim.errors import _shown
from mazesim.ros._ros import publisher
from mazesim.ros.standard import TF_TOPIC

__all__ = [
    "LEAD_S",
    "QUIET_S",
    "WRITER_COMING_S",
    "WRITER_WAIT_S",
    "LateConnections",
    "Remembered",
    "state_publisher",
]

#: Seconds without a new connection before the connections waiting get the state.
QUIET_S = 0.5
#: Seconds after the last connection the state waits for a command writer to connect.
WRITER_WAIT_S = 2.0
#: Seconds the state waits for a command publisher that the master lists for a node waiting
#: and that has not connected to the bridge yet (its first command would be lost).
WRITER_COMING_S = 10.0
#: Seconds between the state's motion and its sensors' readings, handed to late connections.
LEAD_S = 0.25

#: A connection waiting: its topic, the function sending to it alone, and rospy's connection
#: (None when it cannot be told).
_Waiting = tuple[str, Callable[[Any], None], Any]


def _connection_of(publish_one: Any) -> Any:
    """rospy's connection that ``publish_one`` sends to (the ``c`` of its closure), or None."""
    code = getattr(publish_one, "__code__", None)
    cells = getattr(publish_one, "__closure__", None) or ()
    if code is None:
        return None
    for name, cell in zip(code.co_freevars, cells, strict=False):
        if name == "c":
            return cell.cell_contents
    return None


def _node_of(connection: Any) -> str | None:
    """The subscribing node's name that rospy keeps on ``connection`` (its ``endpoint_id``)."""
    node = getattr(connection, "endpoint_id", None)
    return node if isinstance(node, str) and node != "unknown" else None


def _had_a_message(connection: Any) -> bool:
    """Whether rospy has written a message to ``connection`` (its ``stat_num_msg``)."""
    return bool(getattr(connection, "stat_num_msg", 0))


class LateConnections:
    """The connections of the bridge's state topics that have not had the state yet.

    rospy calls :meth:`peer_subscribe` (as a ``rospy.SubscribeListener``) when a subscription of
    one of the bridge's publishers connects, with a function that sends a message to that
    connection only. ``graph`` gives the topics each node subscribes to and those it
    publishes, as the master lists them (None: not asked).
    """

    def __init__(
        self,
        quiet_s: float = QUIET_S,
        lead_s: float = LEAD_S,
        writer_wait_s: float = WRITER_WAIT_S,
        graph: Callable[[], tuple[Mapping[str, set[str]], Mapping[str, set[str]]]] | None = None,
        writer_coming_s: float = WRITER_COMING_S,
        note: Callable[[str], None] | None = None,
    ) -> None:
        self.graph = graph
        #: Told each hand-over, in a line (the bridge logs it): whose connections got the state,
        #: how long after the last one connected, and what the master and the writers said.
        self.note = note
        #: What the last look at the master found, for the note.
        self._looked = "the master not asked"
        self.writer_coming_s = writer_coming_s
        self.quiet_s = quiet_s
        self.lead_s = lead_s
        self.writer_wait_s = writer_wait_s
        self._lock = threading.Lock()
        #: The topic and the send function of each connection waiting, in connection order.
        self._waiting: list[_Waiting] = []
        self._last_connected = -float("inf")
        #: The topics each node has connected to so far.
        self._connected: dict[str, set[str]] = {}
        #: The connections of the sensors' topics waiting for the second part, and when.
        self._sensing: list[_Waiting] = []
        self._sensing_at = float("inf")
        #: Connections handed the state so far.
        self.handed = 0
        #: While set, the state publishers keep what they publish off the wire (the reset
        #: state): every connection, one made as the bridge advertised too, gets it by the
        #: hand-over's rule (:meth:`hold_the_reset_state`).
        self.holding = False

    def hold_the_reset_state(self, publish: Callable[[], None]) -> None:
        """Runs ``publish`` (the bridge publishing its reset state) with the state publishers
        keeping their messages off the wire: the state is kept as the last state and every
        connection gets it from :meth:`hand_over`. A node subscribed before the bridge started
        connected as the bridge advertised, had the reset state before its command publisher
        existed, skipped it and waited for the state sent again."""
        self.holding = True
        try:
            publish()
        finally:
            self.holding = False

    def peer_subscribe(self, topic: str, publish_all: Any, publish_one: Any) -> None:
        """rospy: a subscription of ``topic`` connected; ``publish_one`` sends to it alone."""
        with self._lock:
            connection = _connection_of(publish_one)
            self._waiting.append((topic, publish_one, connection))
            node = _node_of(connection)
            if node is not None:
                self._connected.setdefault(node, set()).add(topic)
            self._last_connected = time.monotonic()

    @property
    def pending(self) -> bool:
        """Whether connections wait for the state, or for its sensors' part."""
        with self._lock:
            return bool(self._waiting or self._sensing)

    def peer_unsubscribe(self, topic: str, connections: int) -> None:
        """rospy: a subscription of ``topic`` went away (nothing to do: sending to a closed
        connection does nothing)."""

    def published(self, topic: str) -> None:
        """Every connection of ``topic`` has had its newest message: none waits for the state
        before it."""
        with self._lock:
            self._waiting = [entry for entry in self._waiting if entry[0] != topic]
            self._sensing = [entry for entry in self._sensing if entry[0] != topic]

    def hand_over(
        self,
        state: Iterable[tuple[str, Any]],
        sensing: Container[str],
        writer_connected: bool = True,
        now: float | None = None,
        writers: Callable[[], Mapping[str, set[str]]] | None = None,
    ) -> int:
        """Sends ``state`` (each message's topic and the message, in the order they went out) to
        the connections waiting, once :data:`QUIET_S` has passed since the last one connected
        and a command writer is connected (``writer_connected``), or :data:`WRITER_WAIT_S` has
        passed without one, and what the master lists of the nodes waiting has connected
        (:meth:`_hold_s`; ``writers`` gives the nodes connected as writers of each command
        topic, asked only while a connection waits):
        the motion first, the topics of ``sensing`` (the sensors'
        readings) :data:`LEAD_S` after the last motion handed over, so that a node's odometry
        callback has run before its scan callback (each connection's messages are taken on a
        thread of its own). A connection that has had a message on its topic meanwhile is left
        out. Returns how many connections it sent to."""
        now = time.monotonic() if now is None else now
        state = list(state)
        wait_s = self.quiet_s if writer_connected else self.writer_wait_s
        wait_s = max(wait_s, self._hold_s(state, now, writers))
        with self._lock:
            waiting: list[_Waiting] = []
            if self._waiting and now - self._last_connected >= wait_s:
                waiting, self._waiting = self._waiting, []
                # Every reading waiting goes LEAD_S after the last motion handed over.
                self._sensing += [entry for entry in waiting if entry[0] in sensing]
                self._sensing_at = now + self.lead_s
            sensing_due: list[_Waiting] = []
            if self._sensing and now >= self._sensing_at:
                sensing_due, self._sensing = self._sensing, []
        if waiting and self.note is not None:
            self.note(self._described(waiting, now))
        waiting = [entry for entry in waiting if not _had_a_message(entry[2])]
        sensing_due = [entry for entry in sensing_due if not _had_a_message(entry[2])]
        for entries, part in ((waiting, False), (sensing_due, True)):
            for topic, message in state:
                if (topic in sensing) != part:
                    continue
                for waiting_topic, publish_one, _ in entries:
                    if waiting_topic == topic:
                        publish_one(message)
        self.handed += len(waiting)
        return len(waiting)

    def _hold_s(
        self,
        state: list[tuple[str, Any]],
        now: float,
        writers: Callable[[], Mapping[str, set[str]]] | None,
    ) -> float:
        """How long after the last connection the state waits for what the master lists of the
        nodes with a connection waiting (0: nothing): :data:`WRITER_COMING_S` while one of them
        publishes a command topic (``writers``: each command topic's writers connected to the
        bridge) not yet connected to the bridge, :data:`WRITER_WAIT_S` while one has a
        subscription of a state topic not yet connected. Asked once the quiet time has passed."""
        with self._lock:
            since = now - self._last_connected
            if self.graph is None or not self._waiting or since < self.quiet_s:
                return 0.0
            if since >= max(self.writer_wait_s, self.writer_coming_s):
                return 0.0
            nodes = {_node_of(entry[2]) for entry in self._waiting} - {None}
            connected = {node: set(self._connected.get(node, ())) for node in nodes if node}
        if not connected:
            return 0.0
        try:
            subscribed, published = self.graph()
        except Exception as error:  # the master busy or gone: the writer wait, then without it
            self._looked = f"the master not answering ({_shown(error)})"
            return self.writer_wait_s if since < self.writer_wait_s else 0.0
        connected_writers = writers() if writers is not None else {}
        self._looked = (
            "; ".join(
                f"{node} publishes {sorted(published.get(node, set()) & set(connected_writers))}"
                for node in sorted(connected)
            )
            + f"; command writers connected: {dict(sorted(connected_writers.items()))}"
        )
        for node in connected:
            commands = published.get(node, set()) & set(connected_writers)
            if any(node not in connected_writers[topic] for topic in commands):
                if since < self.writer_coming_s:
                    return self.writer_coming_s
        topics = {topic for topic, _ in state}
        if any((subscribed.get(node, set()) & topics) - connected[node] for node in connected):
            if since < self.writer_wait_s:
                return self.writer_wait_s
        return 0.0

    def _described(self, waiting: list[_Waiting], now: float) -> str:
        """One line on a hand-over: each node's topics handed the state, how long after the
        last connection, and what the last look at the master found."""
        topics: dict[str, list[str]] = {}
        for topic, _, connection in waiting:
            topics.setdefault(_node_of(connection) or "(a node not told)", []).append(topic)
        handed = "; ".join(f"{node}: {', '.join(names)}" for node, names in topics.items())
        return (
            f"lockstep: the state handed to late subscriptions ({handed}) "
            f"{now - self._last_connected:.2f} s after the last connected; {self._looked}"
        )


class Remembered:
    """A publisher that hands each message it publishes to ``note`` (the bridge keeps the last
    state as it went out, to send it again, and tells :class:`LateConnections` the topic went
    out); everything else is the publisher's. ``/tf`` at the stamp it last went out with is
    noted and kept off the wire (``on_the_wire=False``), and so is everything published while
    ``late`` holds the reset state (:meth:`LateConnections.hold_the_reset_state`)."""

    def __init__(
        self, made: Any, note: Callable[..., None], late: LateConnections | None = None
    ) -> None:
        self.made = made
        self._note = note
        self._late = late
        #: ``/tf``: the stamp its transforms last went out with.
        self._tf_stamp: Any = None

    def publish(self, message: Any) -> None:
        if self.made.resolved_name == TF_TOPIC:
            # tf2 keeps transforms by stamp and warns of the same ones again (TF_REPEATED_DATA):
            # the reset state sent again keeps them in the last state, off the wire.
            stamp = message.transforms[0].header.stamp
            if stamp == self._tf_stamp:
                self._note((self.made, message), on_the_wire=False)
                return
            self._tf_stamp = stamp
        if self._late is not None and self._late.holding:
            self._note((self.made, message), on_the_wire=False)
            return
        self.made.publish(message)
        self._note((self.made, message))

    def __getattr__(self, name: str) -> Any:
        return getattr(self.made, name)


def state_publisher(
    ros: Any,
    topic: str,
    message_class: Any,
    lockstep: bool,
    late: LateConnections,
    note: Callable[..., None],
) -> Remembered:
    """A publisher of a bridge's state: latched, synchronous in lockstep (every subscriber, a
    recorder too, gets every step before the next command is taken) and queued in real time (a
    slow subscriber loses old messages); in lockstep a late subscription gets the state from
    ``late``, once, in the order it went out. Each message it publishes goes to ``note``."""
    made = publisher(
        ros,
        topic,
        message_class,
        synchronous=lockstep,
        latch=True,
        late=late if lockstep else None,
    )
    return Remembered(made, note, late if lockstep else None)
