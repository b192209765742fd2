"""The wheel-speed rules the benchmark drives its robots with.

A workload is a rule that turns one step's observations into the next step's wheel speeds for a
whole batch, in numpy, as a user's Python controller would. Each is a class with the same three
methods, so a measurement (or a user's own loop) can take any of them:

- ``braitenberg``: the canonical workload's Braitenberg rule on ps0-ps7; the robots wander and
  steer clear of walls, touching one in a few percent of steps.
- ``contact``: phases of seeking walls (full speed ahead, curving right, turning towards what
  the sensors see: the robot meets a wall within about 50 steps and keeps pushing into it)
  alternating with phases of the Braitenberg rule (it turns away and wanders), each env's phases
  offset from its neighbours'; about half of all steps are in contact.
- ``random``: independent uniform wheel speeds in [-max, +max] every step, from a seeded stream.
"""

from __future__ import annotations

from typing import Literal, Optional, Protocol

import numpy as np
import numpy.typing as npt

from mazesim.errors import RegisteredName, WrongTypeError, _a_type, _known_name

__all__ = [
    "WORKLOADS",
    "BraitenbergWorkload",
    "ContactWorkload",
    "RandomWorkload",
    "Workload",
    "braitenberg",
    "braitenberg_one",
    "make_workload",
    "seek_walls",
]

F32 = npt.NDArray[np.float32]
#: The engine's own controllers that a workload may name (``BatchSimulator.run``), or None.
Builtin = Optional[Literal["braitenberg", "random"]]

#: The e-puck's largest wheel speed (rad/s), the bound of every workload's wheel speeds.
MAX_WHEEL_SPEED = 6.28

#: Steps of a contact workload's period spent seeking walls, then under the Braitenberg rule;
#: chosen so that about half of all steps are in contact (docs/performance.md).
CONTACT_PUSH_STEPS = 160
CONTACT_AVOID_STEPS = 80


def _sides(ps: F32) -> tuple[F32, F32, F32]:
    """Activations of the right side, the left side and the front, each in [0, 2.1]."""
    a = np.clip((ps - np.float32(67.19)) / np.float32(300.0), 0.0, 1.0)
    right_side = a[:, 0] + 0.7 * a[:, 1] + 0.4 * a[:, 2]
    left_side = a[:, 7] + 0.7 * a[:, 6] + 0.4 * a[:, 5]
    return right_side, left_side, 0.5 * (a[:, 0] + a[:, 7])


def _steer(forward: F32, turn: F32, out: F32) -> F32:
    """Left wheel ``forward - turn``, right wheel ``forward + turn``, within the motors' range."""
    np.subtract(forward, turn, out=out[:, 0])
    np.add(forward, turn, out=out[:, 1])
    np.clip(out, -MAX_WHEEL_SPEED, MAX_WHEEL_SPEED, out=out)
    return out


def braitenberg(ps: F32, out: F32) -> F32:
    """Braitenberg wheel speeds (rad/s) from e-puck proximity readings, written into ``out``.

    Each side's activation turns the robot away from that side; a frontal obstacle turns it
    left so it never stalls square to a wall.

    Args:
        ps: (N, 8) raw proximity readings.
        out: (N, 2) float32 buffer for left and right wheel speeds.

    Returns:
        ``out``.
    """
    right_side, left_side, front = _sides(ps)
    turn = 4.0 * (right_side - left_side) + 6.0 * front
    return _steer(5.0 * (1.0 - front), turn, out)


def braitenberg_one(ps: list[float]) -> tuple[float, float]:
    """The Braitenberg rule of :func:`braitenberg` for one robot, in plain Python floats
    (unclipped)."""
    a = [min(max((v - 67.19) / 300.0, 0.0), 1.0) for v in ps]
    right_side = a[0] + 0.7 * a[1] + 0.4 * a[2]
    left_side = a[7] + 0.7 * a[6] + 0.4 * a[5]
    front = 0.5 * (a[0] + a[7])
    base = 5.0 * (1.0 - front)
    turn = 4.0 * (right_side - left_side) + 6.0 * front
    return base - turn, base + turn


def seek_walls(ps: F32, out: F32) -> F32:
    """Wheel speeds (rad/s) that drive into walls, written into ``out``: the outer wheel at full
    speed, curving right in free space and towards whichever side sees more of a wall.

    Args:
        ps: (N, 8) raw proximity readings.
        out: (N, 2) float32 buffer for left and right wheel speeds.

    Returns:
        ``out``.
    """
    right_side, left_side, _ = _sides(ps)
    turn = 3.0 * (left_side - right_side) - 1.5  # > 0: to the left
    # The outer wheel at full speed, the inner one slower by twice the turn.
    return _steer(MAX_WHEEL_SPEED - np.abs(turn), turn, out)


class Workload(Protocol):
    """A batch controller: one call per step, wheel speeds for every env.

    ``builtin`` names the engine's own controller that runs the same rule inside
    ``BatchSimulator.run`` (many steps per call), or is None where the engine has none.
    """

    name: str
    builtin: Builtin

    def act(self, observations: F32, actions: F32) -> F32:
        """Writes the next wheel speeds (N, 2) into ``actions`` from ``observations`` (N, W)
        and returns ``actions``."""
        ...


class BraitenbergWorkload:
    """The canonical workload: the Braitenberg rule of :func:`braitenberg` on ps0-ps7."""

    name: str = "braitenberg"
    builtin: Builtin = "braitenberg"

    def __init__(self, envs: int, seed: int = 0) -> None:
        del envs, seed  # the rule has no state

    def act(self, observations: F32, actions: F32) -> F32:
        return braitenberg(observations[:, :8], actions)


class ContactWorkload:
    """Robots pushed into walls about half the time.

    Each env runs a period of :data:`CONTACT_PUSH_STEPS` steps of :func:`seek_walls` (it drives
    into a wall and keeps pushing) and :data:`CONTACT_AVOID_STEPS` steps of the Braitenberg rule
    (it turns away and wanders off). Env ``i`` starts its period
    at step ``i * period // N`` of it, so the batch as a whole is in every phase at once and the
    share of steps in contact holds steady from step to step. A reset restarts nothing: the
    phase is the env's own clock.
    """

    name: str = "contact"
    builtin: Builtin = None

    def __init__(self, envs: int, seed: int = 0) -> None:
        del seed  # the phases are fixed by the env index
        self.period = CONTACT_PUSH_STEPS + CONTACT_AVOID_STEPS
        self.clock = (np.arange(envs, dtype=np.int64) * self.period) // max(envs, 1)
        self.pushing = np.zeros(envs, bool)
        self.seeking = np.zeros((envs, 2), np.float32)

    def act(self, observations: F32, actions: F32) -> F32:
        braitenberg(observations[:, :8], actions)
        seek_walls(observations[:, :8], self.seeking)
        np.less(self.clock, CONTACT_PUSH_STEPS, out=self.pushing)
        np.copyto(actions, self.seeking, where=self.pushing[:, None])
        self.clock += 1
        self.clock %= self.period
        return actions


class RandomWorkload:
    """Uniform random wheel speeds in [-max, +max], drawn afresh every step for every env.

    The draws come from one ``numpy.random.Generator`` seeded from ``seed``, so a run replays.
    """

    name: str = "random"
    builtin: Builtin = "random"  # the engine's own streams: the same law, other draws

    def __init__(self, envs: int, seed: int = 0) -> None:
        del envs
        (stream,) = np.random.SeedSequence(seed).spawn(1)
        self.rng = np.random.default_rng(stream)

    def act(self, observations: F32, actions: F32) -> F32:
        """Fills ``actions`` (float32, shape (envs, 2)) with the next draws and returns it.

        Raises:
            WrongTypeError: ``actions`` is not a numpy array (numpy's generators read an ``out``
                that is not one as an array, which can crash the process).
        """
        del observations
        if not isinstance(actions, np.ndarray):
            raise WrongTypeError(
                f"RandomWorkload.act: expected actions as a float32 numpy array of shape "
                f"(envs, 2), found {_a_type(actions)}"
            )
        self.rng.random(dtype=np.float32, out=actions)
        actions *= np.float32(2.0 * MAX_WHEEL_SPEED)
        actions -= np.float32(MAX_WHEEL_SPEED)
        return actions


#: The workloads by name, in the order ``mazesim bench --workload`` lists them.
WORKLOADS: dict[str, type[BraitenbergWorkload | ContactWorkload | RandomWorkload]] = {
    "braitenberg": BraitenbergWorkload,
    "contact": ContactWorkload,
    "random": RandomWorkload,
}


def make_workload(name: RegisteredName, envs: int, seed: int = 0) -> Workload:
    """The workload called ``name`` for a batch of ``envs`` envs.

    Raises:
        UnknownNameError: ``name`` is not one of :data:`WORKLOADS`.
    """
    kind = WORKLOADS[_known_name(name, "a workload", tuple(WORKLOADS))]
    return kind(envs, seed)
