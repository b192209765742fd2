"""How fast Webots' E-puck gets its body moving: wheel traction limited by floor friction.

Webots simulates the E-puck PROTO with ODE. Its motors reach their commanded speed at once: the
PROTO's RotationalMotors set only ``maxVelocity`` (6.28 rad/s), so ``acceleration`` keeps its
default -1 (unlimited) and ``maxTorque`` its default 10 N m, against wheels of 5 g (Webots
reference manual, Motor and RotationalMotor nodes; ``E-puck.proto``). The body, though, is moved
only by the wheels' friction on the floor, which Coulomb's law bounds: each wheel pushes at most
``mu`` times the weight it carries (``ContactProperties.coulombFriction`` defaults to 1, gravity
to 9.81 m/s^2). With the PROTO's masses (body 0.15 kg, 0.13 kg for the e-puck2, wheels 0.005 kg),
its yaw inertia (``inertiaMatrix``: 8.74869e-5 kg m^2) and wheels 0.026 m either side of its
centre, the body gains at most 9.81 m/s^2 of forward speed and about 430 rad/s^2 of turn rate:
a full-speed turn in place takes about 10 ms to start, longer than one 8 ms basic time step: in
that step the body turns 1.6 degrees, where a kinematic model turns its whole 2 degrees.

:class:`Traction` holds the body's forward speed and turn rate and moves them toward what the
wheels ask, no faster than those forces allow, and gives the wheel speeds that drive the body at
its speeds at the step's end, as ODE's semi-implicit step moves it: a change the friction allows
within one basic time step (any change at Webots' default 32 ms) is made at once, as before. It
applies to an imported world's E-puck PROTO (not a ``kinematic TRUE`` one, nor Webots 8's
DifferentialWheels E-puck); mazesim's own worlds keep their kinematic robots. The wheels' encoders
count the wheels that drive the body (in Webots they count the motors' rotation, slip included).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Traction", "epuck_traction"]

#: ``ContactProperties.coulombFriction`` and ``WorldInfo.gravity`` defaults.
FRICTION = 1.0
GRAVITY = 9.81
#: The E-puck PROTO's wheels: their mass (kg) and distance from the body's centre (m).
WHEEL_MASS = 0.005
WHEEL_OFFSET = 0.026
#: The E-puck PROTO's body: mass (kg) by version, and yaw inertia (kg m^2).
BODY_MASS = {"1": 0.15, "2": 0.13}
YAW_INERTIA = 8.74869e-5


@dataclass
class Traction:
    """The body's motion limited by the wheels' friction (see the module's docstring).

    Attributes:
        mass: The robot's mass, wheels included (kg).
        yaw_inertia: Its moment of inertia about the vertical axis (kg m^2).
        wheel_offset: Each wheel's distance from the centre, where it pushes (m).
        wheel_radius: The wheel radius the robot's kinematics use (m).
        axle_length: The effective wheel distance its kinematics use (m).
        max_wheel_speed: The motors' limit (rad/s).
        speed: The body's forward speed now (m/s).
        turn_rate: Its turn rate now (rad/s).
    """

    mass: float
    yaw_inertia: float
    wheel_offset: float
    wheel_radius: float
    axle_length: float
    max_wheel_speed: float
    speed: float = 0.0
    turn_rate: float = 0.0

    def drive(self, left: float, right: float, dt: float) -> tuple[float, float]:
        """Takes one step of ``dt`` seconds toward the wheel speeds ``left``, ``right`` (rad/s,
        clamped to the motors' limit) and returns the wheel speeds that move the body as it
        moves at the step's end."""
        limit = self.max_wheel_speed
        left, right = (min(max(w, -limit), limit) for w in (left, right))
        r, axle = self.wheel_radius, self.axle_length
        speed, turn_rate = r * (left + right) / 2.0, r * (right - left) / axle
        d_speed, d_turn = speed - self.speed, turn_rate - self.turn_rate
        # The force each wheel would push with to reach the target within the step.
        linear = self.mass * d_speed / (2.0 * dt)
        torque = self.yaw_inertia * d_turn / (2.0 * self.wheel_offset * dt)
        needed = max(abs(linear + torque), abs(linear - torque))
        most = FRICTION * self.mass * GRAVITY / 2.0
        share = needed / most if needed > 0.0 else 0.0
        if share <= 1.0:
            self.speed, self.turn_rate = speed, turn_rate
        else:
            self.speed += d_speed / share
            self.turn_rate += d_turn / share
        # ODE's semi-implicit step moves the body by its speeds at the step's end.
        half = self.turn_rate * axle / 2.0
        return (self.speed - half) / r, (self.speed + half) / r

    def stop(self) -> None:
        """Puts the body at rest (a supervisor moved it)."""
        self.speed = self.turn_rate = 0.0


def epuck_traction(
    version: str, wheel_radius: float, axle_length: float, max_wheel_speed: float
) -> Traction:
    """The traction of Webots' E-puck PROTO of this ``version`` ("1" or "2") on a robot of
    these kinematics."""
    return Traction(
        mass=BODY_MASS.get(version, BODY_MASS["1"]) + 2 * WHEEL_MASS,
        yaw_inertia=YAW_INERTIA + 2 * WHEEL_MASS * WHEEL_OFFSET**2,
        wheel_offset=WHEEL_OFFSET,
        wheel_radius=wheel_radius,
        axle_length=axle_length,
        max_wheel_speed=max_wheel_speed,
    )
