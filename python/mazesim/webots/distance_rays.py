"""The rays of a Webots DistanceSensor: where they point, what each weighs, and how a sensor of
each type makes one distance of what they meet.

Facts from Webots' ``WbDistanceSensor`` (src/webots/nodes/WbDistanceSensor.cpp, R2022a to
R2025a) and its reference manual (DistanceSensor node):

- The node's fields are corrected as Webots corrects them: a negative ``aperture`` is taken
  positive, ``numberOfRays`` below 1 is 1, a ``gaussianWidth`` of 0 or less is 1; a ``laser``
  sensor casts one ray; several rays of aperture 0 are one ray. (mazesim casts at most
  :data:`MOST_RAYS` rays, and one of an aperture that is no number.)
- One ray points along the sensor's x axis. Up to 10 rays follow a fixed layout of circles in a
  cone of half-angle ``aperture / 2`` around that axis (2 rays: one up and one down, in the plane
  of the sensor's x and z axes; 3: a circle of three; 4 to 8: the axis and a circle of the rest;
  9 and 10: two circles, the axis too for 10); beyond 10, rays fill concentric cones of 1, 4, 7,
  ... rays, the outermost at the full half-angle.
- A ray at an angle ``theta`` from the axis weighs ``exp(-(theta / (aperture *
  gaussianWidth))^2)``, the weights scaled to sum to 1.
- Each ray reaches as far as the lookup table's largest distance (``reach`` here). A ``generic``
  sensor reads the weighted mean of its rays' distances (a ray that meets nothing counts
  ``reach``); an ``infra-red`` one that mean divided by the weighted mean of the reflection
  factors its rays meet (``0.2 + 0.8 * red``; 1 for a ray that meets nothing), as much as its
  ``redColorSensitivity`` says; a ``sonar`` one the nearest distance of a ray that meets a surface
  within pi/8 of its normal (``reach`` when none does), weights ignored; a ``laser`` one its single
  ray's distance.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = [
    "GENERIC",
    "INFRA_RED",
    "LASER",
    "MOST_RAYS",
    "SONAR",
    "SONAR_CONE",
    "RayHits",
    "DistanceRays",
    "sensor_distance",
    "sensor_type",
]

Floats = npt.NDArray[np.float64]

#: Webots' DistanceSensor types (``wb_distance_sensor_get_type``'s values).
GENERIC, INFRA_RED, SONAR, LASER = 0, 1, 2, 3
#: The most rays mazesim casts for one sensor (a ``numberOfRays`` above it casts this many).
MOST_RAYS = 1024
#: How far from a surface's normal a sonar ray may meet it and still be heard back (rad).
SONAR_CONE = math.pi / 8

#: The layouts of 1 to 10 rays: per ray its place on a circle (a turn from the sensor's left
#: towards its up, in full turns) and the circle's angle from the axis (a fraction of the cone's).
_LAYOUTS: tuple[tuple[tuple[float, float], ...], ...] = (
    ((0.0, 0.0),),
    ((0.25, 1.0), (-0.25, 1.0)),
    ((0.0, 1.0), (1 / 3, 1.0), (-1 / 3, 1.0)),
    ((0.0, 0.0), (0.0, 1.0), (1 / 3, 1.0), (-1 / 3, 1.0)),
    ((0.0, 0.0), *((k / 4 if k < 3 else -0.25, 1.0) for k in range(4))),
    ((0.0, 0.0), *((k / 5, 1.0) for k in range(5))),
    ((0.0, 0.0), *((k / 6, 1.0) for k in range(6))),
    ((0.0, 0.0), *((k / 7, 1.0) for k in range(7))),
    ((0.0, 0.3), (1 / 3, 0.3), (-1 / 3, 0.3), *((k / 6, 1.0) for k in range(6))),
    ((0.0, 0.0), (0.0, 0.5), (1 / 3, 0.5), (-1 / 3, 0.5), *((k / 6, 1.0) for k in range(6))),
)


def sensor_type(text: str) -> int:
    """A DistanceSensor ``type`` field's value as Webots reads it: ``generic``, ``infra-red``
    (or ``infrared``) and ``laser`` in any case; anything else is a sonar."""
    lowered = text.lower()
    if lowered == "generic":
        return GENERIC
    if lowered in ("infra-red", "infrared"):
        return INFRA_RED
    if lowered == "laser":
        return LASER
    return SONAR


def _cones(count: int) -> list[tuple[float, float]]:
    """The places of ``count`` rays (more than 10) in concentric cones of 1, 4, 7 ... rays: a
    ray's turn is its overall index over its cone's size (as Webots lays them), its angle its
    cone's number over the outermost one's."""
    places: list[tuple[int, int]] = []  # (cone, size of the cone)
    cone = 0
    while len(places) < count:
        size = min(3 * cone + 1, count - len(places))
        places.extend((cone, size) for _ in range(size))
        cone += 1
    outermost = max(cone - 1, 1)
    return [(index / size, ring / outermost) for index, (ring, size) in enumerate(places)]


@dataclass(frozen=True)
class DistanceRays:
    """The rays of one DistanceSensor: unit directions in the sensor's frame (x its axis; (N, 3))
    and weights summing to 1 (N,)."""

    #: A world's field values, NaN included, are corrected as Webots corrects them (an aperture
    #: of NaN is one ray): the surface check lets NaN through (``mazesim._checks``).
    _takes_nan = True

    directions: Floats
    weights: Floats

    @classmethod
    def of(
        cls, count: int, aperture: float, gaussian_width: float = 1.0, kind: int = GENERIC
    ) -> DistanceRays:
        """The rays of a sensor of ``numberOfRays`` ``count``, ``aperture`` (rad) and
        ``gaussianWidth``, corrected as Webots corrects them (see the module notes)."""
        aperture = abs(aperture) if math.isfinite(aperture) else 0.0
        gaussian_width = gaussian_width if gaussian_width > 0.0 else 1.0
        count = min(max(int(count), 1), MOST_RAYS)
        if kind == LASER or aperture == 0.0:
            count = 1
        if count == 1:
            return cls(np.array([[1.0, 0.0, 0.0]]), np.ones(1))
        places = list(_LAYOUTS[count - 1]) if count <= len(_LAYOUTS) else _cones(count)
        # A turn of 0 on a circle is the sensor's left (its y axis), a quarter turn its up (z).
        turn = np.array([p[0] for p in places]) * math.tau + math.pi / 2
        theta = np.array([p[1] for p in places]) * aperture / 2
        directions = np.stack(
            [np.cos(theta), np.sin(theta) * np.sin(turn), -np.sin(theta) * np.cos(turn)], axis=1
        )
        # exp(-(theta / (aperture * gaussianWidth))^2), measured from the nearest ray's so that
        # a narrow gaussian does not underflow to 0 for every ray (the same weights once scaled
        # to sum to 1).
        beyond = theta**2 - theta.min() ** 2
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            spread = np.where(beyond > 0.0, beyond / (aperture * gaussian_width) ** 2, 0.0)
        weights = np.exp(-spread)
        return cls(directions, weights / weights.sum())

    def __len__(self) -> int:
        return int(self.weights.shape[0])


@dataclass(frozen=True)
class RayHits:
    """What each ray of a sensor met: how far (``inf``: nothing within reach), the reflection
    factor of what it met (``0.2 + 0.8 * red``; any value where it met nothing) and the cosine
    of the angle between the ray and the surface's normal there."""

    distances: Floats
    factors: Floats
    incidences: Floats


def sensor_distance(
    kind: int, rays: DistanceRays, hits: RayHits, reach: float, red_sensitivity: float = 1.0
) -> float:
    """The one distance a sensor of type ``kind`` reads of what its ``rays`` met (see the module
    notes); each ray reaches ``reach`` (m)."""
    met = hits.distances < reach
    distances = np.where(met, hits.distances, reach)
    if kind == LASER:
        return float(distances[0])
    if kind == SONAR:
        heard = met & (hits.incidences > math.cos(SONAR_CONE))
        return float(np.min(distances[heard])) if heard.any() else reach
    mean = float(np.dot(rays.weights, distances))
    if kind != INFRA_RED:
        return mean
    factor = max(float(np.dot(rays.weights, np.where(met, hits.factors, 1.0))), 1e-6)
    if red_sensitivity == 1.0:
        return mean / factor
    return mean + (mean / factor - mean) * red_sensitivity
