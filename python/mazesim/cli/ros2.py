"""The ``mazesim ros2`` commands: the ROS 2 bridge, the controller nodes and the demo.

No ROS 2 installation is needed: the extra ``mazesim[ros2]`` (``cyclonedds``, ``rosbags``) is;
without it every command says what to install, at once, before parsing its options.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from mazesim.cli._args import non_negative_int, positive_number, seed_argument
from mazesim.cli._ros_commands import (
    Command,
    demo_options,
    option,
    refuse_demo_overwrites,
    register_commands,
    wants_check,
)
from mazesim.episodes import MAX_STEPS
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.ros.lockstep import IDLE_TIMEOUT_S
from mazesim.ros2._deps import require_ros2

__all__ = ["check_before_parsing", "take_ros_arguments"]

DISTROS = ("humble", "jazzy")


def check_before_parsing(arguments: Sequence[str]) -> None:
    """Fails fast on ``mazesim ros2 COMMAND ...`` where the ROS 2 extra is missing.

    Raises:
        MissingDependencyError: ``cyclonedds`` or ``rosbags`` is missing.
    """
    if wants_check(arguments, "ros2"):
        require_ros2()


def take_ros_arguments(arguments: Sequence[str]) -> tuple[list[str], Any]:
    """``arguments`` without their ``--ros-args`` sections (as a launch file or ``ros2 run``
    passes a node's namespace, name, remappings and parameters), and what those say.

    Raises:
        InvalidArgumentError: a section that ROS 2 would not take, or a parameter mazesim's
            nodes do not have.
    """
    from mazesim.ros2.ros_args import split_ros_arguments

    return split_ros_arguments(arguments)


def _bridge_namespace(args: argparse.Namespace) -> str:
    """``--namespace``, or the launch file's ``__ns``: one namespace, said once."""
    given = args.namespace or ""
    launched = args.ros_arguments.namespace.strip("/")
    if given and launched and given.strip("/") != launched:
        raise InvalidArgumentError(
            f"expected one namespace for the bridge; found --namespace {given} and "
            f"--ros-args -r __ns:=/{launched}: leave one out"
        )
    return given or launched


def _refuse_ros_arguments(args: argparse.Namespace, command: str) -> None:
    """Only the bridge takes a namespace, name or remappings from ``--ros-args``."""
    ros_arguments = args.ros_arguments
    if ros_arguments.namespace or ros_arguments.node_name or ros_arguments.remappings:
        raise InvalidArgumentError(
            f"expected no remapping in --ros-args of mazesim ros2 {command} (only mazesim ros2 "
            "bridge takes __ns, __node and topic remappings); found "
            + " ".join(
                [f"__ns:={ros_arguments.namespace}"] * bool(ros_arguments.namespace)
                + [f"__node:={ros_arguments.node_name}"] * bool(ros_arguments.node_name)
                + [f"{source}:={target}" for _, source, target in ros_arguments.remappings]
            )
        )


#: The largest speed factor and timer period the commands take.
LARGEST = 1e6


def _non_negative(text: str, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and 0.0 <= value <= LARGEST):
        raise argparse.ArgumentTypeError(
            f"expected {what} from 0 to {LARGEST:g}; found {_shown(text)}"
        )
    return value


def _speed(text: str) -> float:
    return _non_negative(text, "a speed factor (0: as fast as possible)")


def _command_period(text: str) -> float:
    return _non_negative(text, "a timer period in seconds (0: a step per command)")


def _command_deadline(text: str) -> float:
    return _non_negative(text, "a deadline in wall-clock seconds (0: wait for each command)")


def _idle_timeout(text: str) -> float:
    return _non_negative(text, "seconds of wall-clock time (0: never give up)")


def _period_ms(text: str) -> float:
    return _non_negative(text, "a timer period in ms (0: answer each reading)")


def _policy(text: str) -> str:
    if not text or "\0" in text:
        raise argparse.ArgumentTypeError(
            f"expected a folder of trained tables; found {_shown(text)}"
        )
    return text


def _robot_namespace(text: str) -> str:
    """A robot's name as its namespace (``east-1``: ``/east_1``), as the bridge names it."""
    from mazesim.ros2.robots import robot_namespaces

    if not text or "\0" in text:
        raise argparse.ArgumentTypeError(f"expected a robot's name; found {_shown(text)}")
    return robot_namespaces([text.lstrip("/")])[0]


#: The options every ``mazesim ros2`` command takes, last.
_COMMON = (
    option(
        "--ros-distro",
        choices=DISTROS,
        default="humble",
        help="the ROS 2 distribution whose message layouts to speak (default: %(default)s)",
    ),
    option(
        "--network",
        action="store_true",
        help="discover over the network (the subnet); by default this machine only, unless "
        "ROS_AUTOMATIC_DISCOVERY_RANGE or ROS_LOCALHOST_ONLY=0 says otherwise",
    ),
)


def _run_bridge(args: argparse.Namespace) -> int:
    from mazesim.ros2.bridge import BridgeSettings, run_bridge

    return run_bridge(
        BridgeSettings(
            world=args.world,
            robot=args.robot,
            seed=args.seed,
            noise=not args.no_noise,
            distro=args.ros_distro,
            mode=args.mode,
            speed=args.speed,
            paused=args.paused,
            stop_after=args.stop_after,
            stop_at_goal=args.stop_at_goal,
            bag=args.bag,
            network=args.network,
            frame_prefix=args.frame_prefix,
            namespace=_bridge_namespace(args),
            command_period=args.command_period,
            command_deadline=args.command_deadline,
            idle_timeout=args.idle_timeout,
            ros_arguments=args.ros_arguments,
        )
    )


def _run_perform_learning(args: argparse.Namespace) -> int:
    _refuse_ros_arguments(args, "perform-learning")
    from mazesim.ros2.nodes import run_perform_learning

    return run_perform_learning(args.ros_distro, args.policy, args.control_step_ms, args.network)


def _run_avoid_collision(args: argparse.Namespace) -> int:
    _refuse_ros_arguments(args, "avoid-collision")
    from mazesim.ros2.nodes import run_avoid_collision

    return run_avoid_collision(
        args.ros_distro, args.period_ms, args.network, namespace=args.namespace or ""
    )


def _run_demo(args: argparse.Namespace) -> int:
    _refuse_ros_arguments(args, "demo")
    import mazesim
    from mazesim.maze import refuse_blocked_start
    from mazesim.ros2.demo import run_demo

    refuse_demo_overwrites(args, ("bag",))
    world = mazesim.load_world(args.world)  # a bad world fails here, before any process starts
    refuse_blocked_start(world, args.world)
    if len(world.robots) > 1:
        raise InvalidArgumentError(
            f"mazesim ros2 demo drives one robot; world {_shown(world.name)} holds "
            f"{len(world.robots)}: run 'mazesim ros2 bridge --world {args.world}' and a node per "
            "robot, such as 'mazesim ros2 avoid-collision --robot NAME'"
        )
    result = run_demo(
        Path(args.out),
        args.controller,
        args.ros_distro,
        args.seed,
        args.steps,
        args.world,
        args.robot,
    )
    goal = "goal not reached" if result.goal_step is None else f"goal at step {result.goal_step}"
    print(f"mazesim ros2 demo: {result.steps} steps, {goal}; bag: {result.bag}")
    return 0


_DEMO = demo_options("the node that drives (default: %(default)s)", "mazesim-ros2-demo")

#: The ``mazesim ros2`` commands.
COMMANDS = (
    Command(
        "bridge",
        "the simulator behind the e-puck's ROS 2 topics",
        "Run a simulator as a ROS 2 node: after each control step it publishes the sensors "
        "(a sensor_msgs/Range per distance and ground sensor, /scan, /sensors, /sensor_data), "
        "/odom, /joint_states, /tf and /clock; it drives on /cmd_vel, /motor ([left, right] "
        "rad/s) or /action (a primitive action code). In lockstep mode it advances one "
        "control step per command; free mode steps on its own, controlled on /sim_control.",
        (
            "mazesim ros2 bridge --world seed-maze --bag run1",
            "mazesim ros2 bridge --robot seed --stop-at-goal --ros-distro jazzy",
            "mazesim ros2 bridge --mode free --speed 0 --paused",
        ),
        (
            option(
                "--world", default="seed-maze", help="world name or file (default: %(default)s)"
            ),
            option("--robot", default="e-puck", help="robot profile (default: %(default)s)"),
            option(
                "--seed",
                type=seed_argument,
                default=0,
                help="the sensor noise's seed (default: %(default)s)",
            ),
            option("--no-noise", action="store_true", help="noise-free sensors"),
            option(
                "--mode",
                choices=("lockstep", "free"),
                default="lockstep",
                help="lockstep: one control step per command; free: steps on its own "
                "(default: %(default)s)",
            ),
            option(
                "--speed",
                type=_speed,
                default=1.0,
                help="free mode: simulated seconds per wall-clock second, 0 for as fast "
                "as possible (default: %(default)s)",
            ),
            option("--paused", action="store_true", help="free mode: start paused"),
            option(
                "--stop-after",
                type=non_negative_int,
                default=0,
                help="stop after N steps, 0 for never (default: %(default)s)",
            ),
            option("--stop-at-goal", action="store_true", help="stop once at the goal"),
            option("--bag", default=None, help="record a rosbag2 (MCAP) into this new folder"),
            option(
                "--frame-prefix",
                action="store_true",
                help="a world of several robots: each robot's frames start with its name "
                "(west/odom, west/base_link...) and its transforms go on the one /tf and "
                "/tf_static, as ros2_control's diff drive controller in a namespace names "
                "them",
            ),
            option(
                "--namespace",
                default="",
                help="a world of one robot: put its topics in this namespace (epuck0: "
                "/epuck0/odom, /epuck0/cmd_vel...; /clock stays), as a node written for one "
                "robot of several names them; a world of several robots puts each in its own "
                "(default: none, the topics at the root)",
            ),
            option(
                "--command-period",
                type=_command_period,
                default=0.0,
                help="lockstep: the driving node commands on a timer of simulated time "
                "with this period in seconds (create_timer(0.1, ...) with use_sim_time): each "
                "command holds, whole steps, until the clock reaches the timer's next tick "
                "(default: 0, a step per command)",
            ),
            option(
                "--command-deadline",
                type=_command_deadline,
                default=0.0,
                help="lockstep: when no command comes this many wall-clock seconds after a "
                "state, step with the last command held, then on in real time until one comes, "
                "for a node that waits for simulated time the bridge cannot foresee (a timer "
                "counted from its first /clock, a sleep after each command) (default: 0, wait "
                "for each command)",
            ),
            option(
                "--idle-timeout",
                type=_idle_timeout,
                default=IDLE_TIMEOUT_S,
                help="give up (exit status 3) once no node has had a command topic open for "
                "this many wall-clock seconds, so a bridge whose node never came, or ended, does "
                "not run for ever (default: %(default)g; 0: never)",
            ),
            *_COMMON,
        ),
        _run_bridge,
    ),
    Command(
        "perform-learning",
        "the shipped hierarchical navigator: /sensor_data -> /action",
        "Run the hierarchical navigator (the shipped one, or a folder 'mazesim train' wrote) "
        "as a ROS 2 node: it reads /sensor_data (the Sharp distances and the checkpoint "
        "crossed) and answers each reading with an action code on /action. Start 'mazesim "
        "ros2 bridge --robot seed' beside it.",
        (
            "mazesim ros2 perform-learning",
            "mazesim ros2 perform-learning --ros-distro jazzy --control-step-ms 32",
        ),
        (
            option(
                "--policy",
                type=_policy,
                default=None,
                help="a folder of trained tables (default: shipped)",
            ),
            option(
                "--control-step-ms",
                type=positive_number,
                default=32.0,
                help="the bridge's step (default: %(default)s)",
            ),
            *_COMMON,
        ),
        _run_perform_learning,
    ),
    Command(
        "avoid-collision",
        "the report's Alg. 1: /sensors -> /motor",
        "Run the report's avoid-collision rule (Alg. 1) as a ROS 2 node: it reads /sensors "
        "(ps0..ps7 first) and answers with wheel speeds on /motor, to each reading or on a "
        "timer of simulation time. Start 'mazesim ros2 bridge' beside it.",
        (
            "mazesim ros2 avoid-collision",
            "mazesim ros2 avoid-collision --period-ms 64",
            "mazesim ros2 avoid-collision --robot west",
        ),
        (
            option(
                "--period-ms",
                type=_period_ms,
                default=0.0,
                help="0: answer each reading; else a timer of this period on simulation "
                "time (/clock) (default: %(default)s)",
            ),
            option(
                "--robot",
                dest="namespace",
                type=_robot_namespace,
                default=None,
                metavar="NAME",
                help="in a world of several robots, drive robot NAME: its /NAME/sensors "
                "and /NAME/motor (default: the topics of a world of one robot)",
            ),
            *_COMMON,
        ),
        _run_avoid_collision,
    ),
    Command(
        "demo",
        "bridge + navigator node to the goal, recorded in a bag",
        "Run the bridge in lockstep and a controller node (the shipped navigator, or the "
        "avoid-collision rule) as two processes on this machine until the goal or the step "
        "limit, recording the run in a rosbag2 (MCAP) folder, DIR/bag.",
        (
            "mazesim ros2 demo --out ros2-demo",
            "mazesim ros2 demo --controller avoid-collision --steps 500 --ros-distro jazzy",
            "mazesim ros2 demo --controller avoid-collision --robot my-epuck.toml",
        ),
        (
            _DEMO["world"],
            _DEMO["out"],
            _DEMO["controller"],
            _DEMO["robot"],
            option(
                "--seed",
                type=seed_argument,
                default=0,
                help="the bridge's seed (default: %(default)s)",
            ),
            option(
                "--steps",
                type=non_negative_int,
                default=MAX_STEPS,
                help="step limit (default: %(default)s)",
            ),
            *_COMMON,
        ),
        _run_demo,
    ),
)


def register(commands: Any) -> None:
    """Adds ``mazesim ros2`` and its subcommands."""
    register_commands(
        commands,
        "ros2",
        (
            "run the ROS 2 bridge and controller nodes over DDS (needs mazesim[ros2])",
            "Run mazesim as ROS 2 nodes over DDS, with no ROS 2 installation (the extra "
            "mazesim[ros2] brings Cyclone DDS and rosbags): the bridge publishes the e-puck's "
            "standard topics (/scan, /odom, /tf, one Range per sensor, /clock) and the report's "
            "/sensors and /sensor_data, and drives on /cmd_vel, /motor or /action; the controller "
            "nodes and a recorded demo are beside it (docs/ros2.md).",
            (
                "mazesim ros2 bridge --world seed-maze",
                "mazesim ros2 bridge --mode free --speed 2 --ros-distro jazzy",
                "mazesim ros2 demo --out ros2-demo",
            ),
        ),
        COMMANDS,
        "COMMAND",
    )
