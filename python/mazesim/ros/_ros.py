"""Lazy access to ROS 1's Python packages, and what every mazesim node does the same way.

Nothing here imports ROS at module level: :func:`require_ros` does, and turns a missing package
into a :class:`~mazesim.errors.MissingDependencyError` that says how to install it.
"""

from __future__ import annotations

import importlib.util
import os
import shutil
import signal
import sys
import threading
import time
import warnings
import xmlrpc.client
from types import FrameType, SimpleNamespace
from typing import Any

from mazesim.errors import InvalidArgumentError, MazesimError, MissingDependencyError, _shown

#: Seconds after which a node says it is still waiting for the bridge.
WAITING_NOTICE_S = 5.0

__all__ = [
    "check_ros_installed",
    "install_shutdown_handlers",
    "publish_unless_stopping",
    "publisher",
    "require_ros",
    "start_node",
    "subscriber_count",
    "topics_of_nodes",
    "wait_for_master",
    "writers_connected",
]

#: Seconds a node waits for the ROS master before giving up.
MASTER_TIMEOUT_S = 10.0

#: Debian's packages that give ``rospy``, the message types and the command-line tools.
DEBIAN_PACKAGES = (
    "python3-rosmaster python3-roslaunch python3-rospy python3-rostopic python3-std-msgs "
    "python3-rosgraph-msgs python3-rosbag rosout python3-sensor-msgs python3-nav-msgs "
    "python3-geometry-msgs python3-tf2-msgs python3-std-srvs"
)


#: The modules the nodes import, with the Debian package that provides each.
ROS_MODULES = {
    "rospy": "python3-rospy",
    "rosgraph": "python3-rosgraph",
    "rosbag": "python3-rosbag",
    "std_msgs": "python3-std-msgs",
    "rosgraph_msgs": "python3-rosgraph-msgs",
    "sensor_msgs": "python3-sensor-msgs",
    "nav_msgs": "python3-nav-msgs",
    "geometry_msgs": "python3-geometry-msgs",
    "tf2_msgs": "python3-tf2-msgs",
    "std_srvs": "python3-std-srvs",
}


def _install_advice() -> str:
    return (
        f"on Debian or Ubuntu run 'make ros-deps', or 'apt-get install {DEBIAN_PACKAGES}', and "
        f"make /usr/lib/python3/dist-packages importable (see docs/ros.md)"
    )


def _importable(module: str) -> bool:
    try:
        return importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):  # ValueError: sys.modules holds None for it
        return False


def check_ros_installed(commands: tuple[str, ...] = ()) -> None:
    """Fails fast when ROS 1 is missing, without importing it or contacting a master.

    Looks for each module of :data:`ROS_MODULES` on this interpreter's path and for each of
    ``commands`` (such as ``roscore``) on ``PATH``.

    Raises:
        MissingDependencyError: Something is missing; the message says what and how to install it.
    """
    missing = [
        f"{module} ({package})"
        for module, package in ROS_MODULES.items()
        if not _importable(module)
    ]
    python_folder = os.path.dirname(sys.executable)
    search_path = python_folder + os.pathsep + os.environ.get("PATH", "")
    missing += [
        f"the '{command}' command"
        for command in commands
        if shutil.which(command, path=search_path) is None
    ]
    if missing:
        raise MissingDependencyError(
            f"mazesim ros needs ROS 1, which {sys.executable} cannot find: missing "
            f"{', '.join(missing)}; {_install_advice()}"
        )


def require_ros() -> Any:
    """Imports ``rospy`` and the message classes the nodes use.

    Returns:
        A namespace with ``rospy``, ``rosgraph``, ``Float64MultiArray``, ``MultiArrayDimension``,
        ``String``, ``Clock`` and the standard messages ``Range``, ``LaserScan``, ``Odometry``,
        ``OccupancyGrid``, ``Twist``, ``TransformStamped``, ``TFMessage`` and ``PoseStamped``,
        and the service
        ``Empty`` (``std_srvs``) with ``EmptyResponse``.

    Raises:
        MissingDependencyError: ROS 1's Python packages cannot be imported.
    """
    try:
        import rosgraph
        import rospy
        from geometry_msgs.msg import PoseStamped, TransformStamped, Twist
        from nav_msgs.msg import OccupancyGrid, Odometry
        from rosgraph_msgs.msg import Clock
        from sensor_msgs.msg import LaserScan, Range
        from std_msgs.msg import Float64MultiArray, MultiArrayDimension, String
        from std_srvs.srv import Empty, EmptyResponse
        from tf2_msgs.msg import TFMessage
    except ImportError as error:
        raise MissingDependencyError(
            f"mazesim.ros needs ROS 1's Python packages (import failed: {error}); "
            f"{_install_advice()}"
        ) from error
    return SimpleNamespace(
        rospy=rospy,
        rosgraph=rosgraph,
        Float64MultiArray=Float64MultiArray,
        MultiArrayDimension=MultiArrayDimension,
        String=String,
        Clock=Clock,
        Range=Range,
        LaserScan=LaserScan,
        Odometry=Odometry,
        OccupancyGrid=OccupancyGrid,
        Twist=Twist,
        TransformStamped=TransformStamped,
        TFMessage=TFMessage,
        PoseStamped=PoseStamped,
        Empty=Empty,
        EmptyResponse=EmptyResponse,
    )


def wait_for_master(ros: Any, timeout: float) -> None:
    """Waits until the ROS master at ``ROS_MASTER_URI`` answers.

    Args:
        ros: The namespace from :func:`require_ros`.
        timeout: Seconds to wait before giving up.

    Raises:
        MazesimError: No master answered within ``timeout`` seconds.
    """
    master = ros.rosgraph.Master("/mazesim")
    deadline = time.monotonic() + timeout
    while not master.is_online():
        if time.monotonic() >= deadline:
            uri = os.environ.get("ROS_MASTER_URI", "http://localhost:11311 (the default)")
            raise MazesimError(
                f"no ROS master answered at ROS_MASTER_URI={uri} within {timeout:g} s; "
                f"start one with 'roscore' or set ROS_MASTER_URI"
            )
        time.sleep(0.1)


def topics_of_nodes(ros: Any) -> tuple[dict[str, set[str]], dict[str, set[str]]]:
    """The topics each node subscribes to and those each publishes, as the master lists them
    (``getSystemState``).

    Args:
        ros: The namespace from :func:`require_ros`.
    """
    with xmlrpc.client.ServerProxy(ros.rosgraph.get_master_uri()) as master:
        answer: Any = master.getSystemState(ros.rospy.get_name())
    code, message, state = answer
    if code != 1:
        raise MazesimError(f"the ROS master refused getSystemState: {message}")
    publishers, subscribers, _ = state
    return _by_node(subscribers), _by_node(publishers)


def _by_node(listed: list[list[Any]]) -> dict[str, set[str]]:
    """``[[topic, [node, ...]], ...]`` as each node's topics."""
    nodes: dict[str, set[str]] = {}
    for topic, names in listed:
        for name in names:
            nodes.setdefault(name, set()).add(topic)
    return nodes


def writers_connected(subscribers: list[Any]) -> dict[str, set[str]]:
    """The nodes whose publishers each of ``subscribers`` (rospy subscribers) is connected to,
    by its topic: the caller id each connection's publisher sent (rospy's ``callerid_pub``)."""
    writers: dict[str, set[str]] = {}
    for sub in subscribers:
        connections = list(getattr(sub.impl, "connections", None) or ())
        writers[sub.resolved_name] = {str(getattr(c, "callerid_pub", "")) for c in connections}
    return writers


def install_shutdown_handlers(stop: threading.Event) -> None:
    """Makes SIGINT and SIGTERM set ``stop`` instead of raising in the main thread.

    The nodes call ``rospy.init_node(..., disable_signals=True)``: rospy's own handler can hang a
    node that is publishing when Ctrl-C arrives, so each node waits on ``stop`` and then shuts
    rospy down itself.
    """

    def request_stop(signum: int, frame: FrameType | None) -> None:
        stop.set()

    signal.signal(signal.SIGINT, request_stop)
    signal.signal(signal.SIGTERM, request_stop)


def start_node(
    program: str, node_name: str, remappings: list[str], time_source: bool = False
) -> tuple[Any, threading.Event]:
    """Starts this process's node once the master answers: ``node_name`` (unless a ``__name:=``
    remapping overrides it) with ``program`` and ``remappings`` as its arguments, rospy's signal
    handling off and SIGINT and SIGTERM setting the returned event instead
    (:func:`install_shutdown_handlers`). A ``time_source`` (the bridge) first sets
    ``/use_sim_time`` unless the launch decided otherwise, so nodes started after it run on the
    simulated time.

    Returns:
        The namespace of :func:`require_ros` and the stop event.

    Raises:
        MazesimError: No master answered within :data:`MASTER_TIMEOUT_S` seconds.
    """
    ros = require_ros()
    wait_for_master(ros, MASTER_TIMEOUT_S)
    if time_source and not ros.rospy.has_param("/use_sim_time"):
        ros.rospy.set_param("/use_sim_time", True)
    ros.rospy.init_node(node_name, argv=[program, *remappings], disable_signals=True)
    stop = threading.Event()
    install_shutdown_handlers(stop)
    return ros, stop


def subscriber_count(rospy: Any, given: Any) -> int:
    """How many subscribers of its output a node waits for: ``given`` (from the command line),
    else its private parameter ``wait_for_subscribers`` (default 1).

    Raises:
        InvalidArgumentError: Not a whole number >= 1.
    """
    count = rospy.get_param("~wait_for_subscribers", 1) if given is None else given
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise InvalidArgumentError(
            "expected parameter wait_for_subscribers to be a whole number >= 1; found "
            f"{_shown(count)}"
        )
    return count


def publisher(
    ros: Any,
    topic: str,
    message_class: Any,
    synchronous: bool,
    latch: bool = False,
    late: Any = None,
) -> Any:
    """Creates a publisher, synchronous or queued.

    A synchronous publisher (``queue_size=None``) writes to every subscriber inside ``publish``:
    nothing is dropped, and a slow subscriber slows the publisher, which is what lockstep wants.
    A queued one keeps the latest 10 messages per subscriber and drops older ones. With ``late``
    (a :class:`~mazesim.ros.latched.LateConnections`) it is latched that way instead of rospy's:
    it says it latches, and ``late`` hands a subscription that connects the message it missed.
    """
    with warnings.catch_warnings():
        # rospy warns about queue_size=None, which is how it spells synchronous publishing.
        warnings.simplefilter("ignore", SyntaxWarning)
        return ros.rospy.Publisher(
            topic,
            message_class,
            queue_size=None if synchronous else 10,
            latch=latch and late is None,
            subscriber_listener=late,
            headers={"latching": "1"} if late is not None else None,
        )


def publish_unless_stopping(
    rospy: Any, topic_publisher: Any, message: Any, stop: threading.Event
) -> None:
    """Publishes ``message`` from a callback; a publish that finds its topic closed once the node
    is stopping (``stop`` set, or rospy shut down) is dropped.

    roslaunch stops a node with SIGINT, which sets ``stop``; the node then shuts rospy down, whose
    shutdown hooks close the topics before rospy says it is shut down (``rospy.is_shutdown()``
    is still false), so a reading arriving meanwhile met "publish() to a closed topic" and its
    callback's traceback went to the launch's log.

    Raises:
        rospy.ROSException: The topic is closed while the node is not stopping.
    """
    try:
        topic_publisher.publish(message)
    except rospy.ROSException:
        if not (stop.is_set() or rospy.is_shutdown()):
            raise


def wait_for_subscribers(
    rospy: Any, topic_publisher: Any, count: int, stop: threading.Event
) -> None:
    """Waits until ``topic_publisher`` has ``count`` connected subscribers (the bridge, and a
    recorder if there is one) or ``stop`` is set; says so in the log after
    :data:`WAITING_NOTICE_S` seconds."""
    started = time.monotonic()
    noticed = False
    while topic_publisher.get_num_connections() < count and not stop.is_set():
        if not noticed and time.monotonic() - started > WAITING_NOTICE_S:
            rospy.loginfo(
                "waiting for %d subscriber(s) of %s (the bridge)",
                count,
                topic_publisher.resolved_name,
            )
            noticed = True
        stop.wait(0.01)
