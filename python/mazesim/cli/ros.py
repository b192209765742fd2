"""The ``mazesim ros`` commands: the ROS nodes without roslaunch, and the bridge demo.

``mazesim ros bridge``, ``mazesim ros avoid-collision`` and ``mazesim ros perform-learning`` run the
nodes that the ROS package ``mazesim_ros`` launches; options take precedence over the nodes'
private ROS parameters, and trailing ``NAME:=VALUE`` arguments are ROS remappings (``_seed:=3``
sets a private parameter, ``__name:=bridge2`` renames the node). ``mazesim ros demo`` runs a whole
graph (the bridge and the perform-learning or avoid-collision node, recorded) on a private master.
ROS is imported only when a command runs; each command first checks, without importing it, that
ROS 1 is installed, and says what to install if it is not.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import Any

from mazesim.cli._args import (
    non_negative_seconds,
    positive_int,
    positive_number,
    positive_seconds,
    seed_argument,
)
from mazesim.cli._ros_commands import (
    Command,
    Option,
    demo_options,
    option,
    refuse_demo_overwrites,
    register_commands,
    wants_check,
)
from mazesim.errors import _shown
from mazesim.replay.views import add_viewing_options
from mazesim.ros._ros import check_ros_installed
from mazesim.ros.lockstep import IDLE_TIMEOUT_S

__all__ = ["check_before_parsing"]

#: The ROS commands ``mazesim ros demo`` runs: the master and the recorder.
DEMO_COMMANDS = ("roscore", "rosbag")
#: The ``mazesim ros`` commands that run one node.
NODE_COMMANDS = ("bridge", "avoid-collision", "perform-learning")


def check_before_parsing(arguments: Sequence[str]) -> None:
    """Fails fast on ``mazesim ros NODE ...`` where ROS 1 is missing, before the command line is
    parsed: building the parsers of every command imports the plotting and learning modules,
    which takes longer than the check.

    Raises:
        MissingDependencyError: ROS 1 is missing (see :func:`check_ros_installed`).
    """
    if not wants_check(arguments, "ros"):
        return
    if arguments[1] == "demo":
        check_ros_installed(DEMO_COMMANDS)
    elif arguments[1] in NODE_COMMANDS:
        check_ros_installed()


def _remapping(text: str) -> str:
    if ":=" not in text:
        raise argparse.ArgumentTypeError(
            "expected a ROS remapping NAME:=VALUE (e.g. sensors:=/robot1/sensors); found "
            f"{_shown(text)}"
        )
    return text


def _node_arguments(default_name: str) -> tuple[Option, ...]:
    """A node's ``--name`` and its trailing remappings."""
    return (
        option(
            "--name",
            default=default_name,
            help="the node's name, unless a __name:= remapping gives one (default: %(default)s)",
        ),
        option(
            "remappings",
            nargs="*",
            type=_remapping,
            metavar="NAME:=VALUE",
            help="ROS remapping arguments, e.g. sensors:=/robot1/sensors or _seed:=3",
        ),
    )


def _wait_option(topic: str) -> Option:
    """``--wait-for-subscribers`` of a node that publishes ``topic``."""
    return option(
        "--wait-for-subscribers",
        type=positive_int,
        metavar="N",
        help=f"subscribers of {topic} to wait for before starting: 1 (the bridge), 2 "
        "with a recorder (default: ~wait_for_subscribers or 1)",
    )


def _run_bridge(args: argparse.Namespace) -> int:
    check_ros_installed()
    from mazesim.ros.bridge import run_bridge

    options = {
        "world": args.world,
        "robot": args.robot,
        "seed": args.seed,
        "mode": args.mode,
        "speed": args.speed,
        "duration": args.duration,
        "noise": False if args.no_noise else None,
        "stop_at_goal": True if args.stop_at_goal else None,
        "command_period": args.command_period,
        "command_deadline": args.command_deadline,
        "bag": args.bag,
        "idle_timeout": args.idle_timeout,
    }
    return run_bridge(options, args.remappings, args.name)


def _run_avoid_collision(args: argparse.Namespace) -> int:
    check_ros_installed()
    from mazesim.ros.avoid_collision import run_avoid_collision

    options = {
        name: getattr(args, name) for name in ("threshold", "max_speed", "wait_for_subscribers")
    }
    return run_avoid_collision(options, args.remappings, args.name)


def _run_perform_learning(args: argparse.Namespace) -> int:
    check_ros_installed()
    from mazesim.ros.perform_learning import run_perform_learning

    options = {
        name: getattr(args, name) for name in ("policy", "control_step_ms", "wait_for_subscribers")
    }
    return run_perform_learning(options, args.remappings, args.name)


def _run_demo(args: argparse.Namespace) -> int:
    import sys

    from mazesim.replay.views import viewing_outputs

    refuse_demo_overwrites(args, ("maze.bag", "trajectory.png"), viewing_outputs(args))
    # Before a master is started: without ROS the nodes would fail one by one, much later.
    check_ros_installed(DEMO_COMMANDS)

    from mazesim.ros.demo import run_demo

    return run_demo(args, sys.stdout)


_DEMO = demo_options(
    "the controller node: hrl (perform-learning, robot seed) or avoid-collision (robot e-puck) "
    "(default: %(default)s)",
    "mazesim-ros-demo",
)

#: The ``mazesim ros`` commands.
COMMANDS = (
    Command(
        "bridge",
        "the simulator node: publishes sensors, sensor_data, pose, /clock, odom, tf, Range",
        "Run a simulator as a ROS node. Publishes sensors (distance then ground sensors, "
        "Float64MultiArray), sensor_data (Sharp distances in cm + checkpoint, robots with "
        "Sharp sensors), pose ([x, y, yaw, time]) and /clock; subscribes motor ([left, right] "
        "rad/s) and action (a primitive action code, String). Beside them: a "
        "sensor_msgs/Range per distance sensor (ps0..ps7 on the e-puck), nav_msgs/Odometry "
        "on odom, /tf (odom -> base_link) and /tf_static (the sensor frames); subscribes "
        "cmd_vel (geometry_msgs/Twist). In lockstep mode it advances one control step per "
        "command received. Options left out fall back to the node's private parameters "
        "(~world, ~robot, ...), then to the defaults shown.",
        (
            "mazesim ros bridge",
            "mazesim ros bridge --world arena --mode realtime --speed 2",
            "mazesim ros bridge --robot seed --stop-at-goal __name:=bridge2 pose:=/robot2/pose",
        ),
        (
            option(
                "--world",
                metavar="NAME|PATH",
                help="built-in world or world file (default: seed-maze)",
            ),
            option("--robot", metavar="NAME", help="robot profile (default: e-puck)"),
            option(
                "--seed",
                type=seed_argument,
                metavar="N",
                help="seed of the sensor noise (default: 0)",
            ),
            option(
                "--mode",
                choices=("lockstep", "realtime"),
                help="lockstep: one control step per command; realtime: step on the clock "
                "(default: lockstep)",
            ),
            option(
                "--speed",
                type=positive_number,
                metavar="FACTOR",
                help="realtime mode: simulated seconds per wall-clock second (default: 1)",
            ),
            option(
                "--duration",
                type=non_negative_seconds,
                metavar="S",
                help="stop after S simulated seconds; 0 runs until stopped (default: 0)",
            ),
            option("--no-noise", action="store_true", help="turn the sensor noise off"),
            option(
                "--stop-at-goal",
                action="store_true",
                help="stop after the step that brings the robot into the world's goal disc",
            ),
            option(
                "--command-period",
                type=non_negative_seconds,
                metavar="S",
                help="lockstep: the controller commands at a rospy.Rate of simulated time "
                "with this period (rospy.Rate(10): 0.1): each command holds, whole steps, "
                "until the clock reaches the rate's next tick (default: 0, a step per "
                "command)",
            ),
            option(
                "--command-deadline",
                type=non_negative_seconds,
                metavar="S",
                help="lockstep: when no command comes S wall-clock seconds after a state, step "
                "with the last command held, then on in real time until one comes, for a "
                "controller that waits for simulated time the bridge cannot foresee (a "
                "rospy.Timer or rospy.sleep counted from a later time) (default: 0, wait for "
                "each command)",
            ),
            option(
                "--idle-timeout",
                type=non_negative_seconds,
                metavar="S",
                help="give up (exit status 3) once no command has come and no node has had a "
                "command topic open for S wall-clock seconds, so a bridge whose controller "
                f"never connected, or ended, does not run for ever (default: ~idle_timeout or "
                f"{IDLE_TIMEOUT_S:g}; 0: never)",
            ),
            option(
                "--bag",
                metavar="PATH",
                help="write every message the bridge sends and every command it takes into "
                "this ROS 1 bag, every step by construction (a rosbag record node can miss "
                "some); written as PATH.active, renamed to PATH when the bridge stops",
            ),
            *_node_arguments("mazesim_bridge"),
        ),
        _run_bridge,
    ),
    Command(
        "avoid-collision",
        "the report's avoid-collision controller node (Listing 3.2)",
        "Subscribe sensors, run the avoid-collision rule (Alg. 1) on ps0..ps7 and publish "
        "[left, right] on motor, one command per reading. Needs a bridge running the e-puck.",
        (
            "mazesim ros avoid-collision",
            "mazesim ros avoid-collision --threshold 120 --wait-for-subscribers 2",
        ),
        (
            option(
                "--threshold",
                type=positive_number,
                metavar="RAW",
                help="proximity reading that means an obstacle (default: ~threshold or 80)",
            ),
            option(
                "--max-speed",
                type=positive_number,
                metavar="RAD_S",
                help="maximum wheel speed in rad/s (default: ~max_speed or 6.28)",
            ),
            _wait_option("motor"),
            *_node_arguments("avoid_collision"),
        ),
        _run_avoid_collision,
    ),
    Command(
        "perform-learning",
        "the hierarchical policy node (Alg. 5)",
        "Subscribe sensor_data, ask the hierarchical policy of mazesim.learn (Alg. 5) for a "
        "primitive action and publish its code on action, one action per reading. Needs a "
        "bridge running a robot with Sharp sensors (--robot seed). The policy dead-reckons "
        "its sub-tasks from its actions, each lasting one control step of the bridge (read "
        "from the control_step_ms parameter the bridge sets).",
        ("mazesim ros perform-learning", "mazesim ros perform-learning --policy mazesim-policy"),
        (
            option(
                "--policy",
                metavar="DIR",
                help="folder of trained tables (default: ~policy, else the ones shipped "
                "for seed-maze)",
            ),
            option(
                "--control-step-ms",
                type=positive_number,
                metavar="MS",
                help="how long each action runs (default: ~control_step_ms, else the "
                "bridge's control_step_ms parameter)",
            ),
            _wait_option("action"),
            *_node_arguments("perform_learning"),
        ),
        _run_perform_learning,
    ),
    Command(
        "demo",
        "bridge + the hierarchical policy node in lockstep on a private master, in a bag",
        "Start a ROS master on a free loopback port, the bridge in lockstep, a controller "
        "node and 'rosbag record'; stop everything when the bridge stops, then read the bag "
        "back and plot the trajectory. With --controller hrl (the default) the seed robot "
        "runs the perform-learning node (the hierarchical policy shipped for seed-maze) and "
        "the bridge stops at the goal, or after --seconds; with avoid-collision the e-puck "
        "runs the avoid-collision node for --seconds. Writes DIR/maze.bag, "
        "DIR/trajectory.png and DIR/logs/.",
        (
            "mazesim ros demo",
            "mazesim ros demo --controller avoid-collision --world arena --seconds 30",
            "mazesim ros demo --controller avoid-collision --robot my-epuck.toml",
            "mazesim ros demo --html ros-demo.html",
        ),
        (
            _DEMO["controller"],
            _DEMO["world"],
            _DEMO["robot"],
            option(
                "--seed", type=seed_argument, default=0, metavar="N", help="noise seed (default: 0)"
            ),
            option(
                "--seconds",
                type=positive_seconds,
                default=60.0,
                metavar="S",
                help="simulated seconds to run at most; hrl stops at the goal before "
                "(default: %(default)s)",
            ),
            _DEMO["out"],
        ),
        _run_demo,
        (add_viewing_options,),
    ),
)


def register(commands: Any) -> None:
    """Adds ``mazesim ros ...`` to the ``mazesim`` command's subparsers."""
    register_commands(
        commands,
        "ros",
        (
            "run the ROS 1 bridge and controller nodes (needs ROS 1)",
            "Run mazesim as ROS 1 nodes, as the report's custom ROS controller: the bridge "
            "publishes sensors, sensor_data, pose and /clock and steps on motor or action "
            "commands. ROS_MASTER_URI says which master to use. Needs ROS 1's Python packages "
            "(on Debian: 'make ros-deps').",
            (
                "mazesim ros demo",
                "mazesim ros bridge --robot seed --stop-at-goal",
                "mazesim ros perform-learning",
            ),
        ),
        COMMANDS,
        "NODE",
    )
