"""Rays against the world's walls, from any pose: the camera's view and extra distance sensors.

The core casts the profile's own sensors; these casts serve what the world adds (a camera, a
distance sensor in an extension slot), from the wall boxes of :meth:`World.wall_boxes`, their
colours (:meth:`World.wall_colours`) and the floor's paint and colours; with what else stands on
the floor (movable bodies, other robots: :meth:`WallBoxes.with_solids`) for the rays of the
devices the world adds.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Iterator

import numpy as np
import numpy.typing as npt

from mazesim._core import World
from mazesim._sizes import index_array, number_array
from mazesim.errors import MaybeInfinite, _shown

__all__ = ["FloorPaint", "WallBoxes"]

Floats = npt.NDArray[np.float64]


class WallBoxes:
    """The walls of a world as oriented boxes, ready for many rays at once; with ``sensed``, its
    sensed-only walls too (after the others), as infra-red rays and cameras see them. Seen from
    above, each stands from the floor to its top (:meth:`cast_sloped`)."""

    def __init__(self, world: World, sensed: bool = False) -> None:
        boxes = np.asarray(world.wall_boxes(), dtype=np.float64).reshape(-1, 6)
        colours = np.asarray(world.wall_colours(), dtype=np.float64).reshape(-1, 3)
        tops = np.asarray(world.wall_tops(), dtype=np.float64).reshape(-1)
        if sensed:
            boxes = np.concatenate([boxes, np.asarray(world.sensed_wall_boxes()).reshape(-1, 6)])
            more = np.asarray(world.sensed_wall_colours(), dtype=np.float64).reshape(-1, 3)
            colours = np.concatenate([colours, more])
            tops = np.concatenate([tops, np.asarray(world.sensed_wall_tops()).reshape(-1)])
        self._take(boxes, colours, tops)

    @classmethod
    def of_boxes(cls, boxes: list[tuple[float, float, float, float, float, float]]) -> WallBoxes:
        """Boxes (centre x, y, size x, y, yaw, reflectance each) as walls, of no colour."""
        made = cls.__new__(cls)
        array = number_array(boxes, "boxes").reshape(-1, 6)
        made._take(array, np.full((array.shape[0], 3), np.nan))
        return made

    def _take(self, boxes: Floats, colours: Floats, tops: Floats | None = None) -> None:
        """Holds ``boxes`` (N, 6), their ``colours`` (N, 3) and ``tops`` (N,; inf: higher than
        any ray goes, the default)."""
        self.center = boxes[:, 0:2]
        self.half = boxes[:, 2:4] / 2.0
        self.cos = np.cos(boxes[:, 4])
        self.sin = np.sin(boxes[:, 4])
        self.reflectance = boxes[:, 5]
        #: Red, green, blue in [0, 1] of each wall as a camera sees it; NaN where none is given.
        self.colour = colours
        #: How high each wall's top stands above the floor (m); inf where the world gives none.
        self.top = np.full(boxes.shape[0], np.inf) if tops is None else tops
        #: Upright cylinders met after the boxes (:meth:`with_solids`): centres (K, 2) and radii;
        #: their reflectances and tops follow the boxes' in :attr:`reflectance` and :attr:`top`.
        self.disc_center = np.zeros((0, 2))
        self.disc_radius = np.zeros(0)

    def with_solids(
        self, boxes: Floats, box_tops: Floats, discs: Floats, disc_tops: Floats
    ) -> WallBoxes:
        """A copy that meets more solids standing on the floor: ``boxes`` ((M, 6), as
        :meth:`of_boxes` takes them) of tops ``box_tops``, after the walls, then upright
        cylinders ``discs`` ((K, 4): centre x, y, radius, reflectance) of tops ``disc_tops``;
        this one when there are none. The new boxes have no colour; indices past the boxes
        (:meth:`cast_walls`) are cylinders."""
        boxes = number_array(boxes, "boxes").reshape(-1, 6)
        discs = number_array(discs, "discs").reshape(-1, 4)
        if not boxes.shape[0] and not discs.shape[0]:
            return self
        joined = copy.copy(self)
        count = self.center.shape[0]
        joined.center = np.concatenate([self.center, boxes[:, 0:2]])
        joined.half = np.concatenate([self.half, boxes[:, 2:4] / 2.0])
        joined.cos = np.concatenate([self.cos, np.cos(boxes[:, 4])])
        joined.sin = np.concatenate([self.sin, np.sin(boxes[:, 4])])
        joined.colour = np.concatenate([self.colour, np.full((boxes.shape[0], 3), np.nan)])
        joined.disc_center = np.concatenate([self.disc_center, discs[:, 0:2]])
        joined.disc_radius = np.concatenate([self.disc_radius, discs[:, 2]])
        # Reflectances and tops: the boxes', then the cylinders'.
        box_tops = number_array(box_tops, "box_tops", inf_means="a solid of no top").reshape(-1)
        disc_tops = number_array(disc_tops, "disc_tops", inf_means="a solid of no top").reshape(-1)
        joined.reflectance = np.concatenate(
            [self.reflectance[:count], boxes[:, 5], self.reflectance[count:], discs[:, 3]]
        )
        joined.top = np.concatenate([self.top[:count], box_tops, self.top[count:], disc_tops])
        return joined

    def moved(
        self,
        walls: list[int],
        before: tuple[float, float, float],
        now: tuple[float, float, float],
    ) -> WallBoxes:
        """A copy with the walls ``walls`` (indices) moved by the rigid motion, seen from
        above, that takes the pose ``before`` (x, y, yaw) to ``now``; this one when ``walls``
        is empty."""
        # Boxes without the sensed-only walls (``sensed`` False) leave those out: they come last.
        walls = [i for i in walls if i < len(self.center)]
        if not walls:
            return self
        moved = copy.copy(self)
        index = index_array(walls, "walls", len(self.center))
        turn = now[2] - before[2]
        c, s = math.cos(turn), math.sin(turn)
        dx = self.center[index, 0] - before[0]
        dy = self.center[index, 1] - before[1]
        moved.center = self.center.copy()
        moved.center[index, 0] = now[0] + c * dx - s * dy
        moved.center[index, 1] = now[1] + s * dx + c * dy
        # The box's axes turn by the motion's turn.
        moved.cos, moved.sin = self.cos.copy(), self.sin.copy()
        moved.cos[index] = self.cos[index] * c - self.sin[index] * s
        moved.sin[index] = self.sin[index] * c + self.cos[index] * s
        return moved

    def cast(self, origin: tuple[float, float], directions: Floats) -> tuple[Floats, Floats]:
        """Casts rays from ``origin`` along each of ``directions`` ((N, 2), not normalised).

        Returns:
            For each ray, the ray parameter ``t`` of the first wall met (the hit is at
            ``origin + t * direction``; ``inf`` when none) and that wall's reflectance (NaN when
            none).
        """
        distance, wall = self.cast_walls(origin, directions)
        return distance, self.reflectances(wall)

    def reflectances(self, wall: npt.NDArray[np.intp]) -> Floats:
        """The reflectance of each wall of indices ``wall`` (NaN for -1: none)."""
        if self.reflectance.shape[0] == 0:  # no wall: every ray meets none
            return np.full(wall.shape, np.nan)
        return np.where(wall >= 0, self.reflectance[np.maximum(wall, 0)], np.nan)

    def side_normals(
        self,
        origin: tuple[float, float],
        directions: Floats,
        distance: Floats,
        wall: npt.NDArray[np.intp],
    ) -> Floats:
        """The unit normal, seen from above, of the side of wall ``wall`` (indices; -1: none)
        that each ray from ``origin`` along ``directions`` meets ``distance`` along it ((N,
        2); NaN where a ray meets none): the side of the wall's box on which the hit lies."""
        normals = np.full(directions.shape, np.nan)
        hit = wall >= 0
        if not hit.any():
            return normals
        boxes = self.center.shape[0]
        round_ = hit & (wall >= boxes)
        if round_.any():
            # A cylinder's side faces out from its axis.
            index = wall[round_] - boxes
            out = origin + distance[round_, None] * directions[round_] - self.disc_center[index]
            normals[round_] = out / np.maximum(np.hypot(out[:, 0], out[:, 1]), 1e-12)[:, None]
            hit = hit & ~round_
        index = wall[hit]
        x = origin[0] + distance[hit] * directions[hit, 0] - self.center[index, 0]
        y = origin[1] + distance[hit] * directions[hit, 1] - self.center[index, 1]
        c, s = self.cos[index], self.sin[index]
        local_x, local_y = c * x + s * y, -s * x + c * y
        half = np.maximum(self.half[index], 1e-12)
        # The hit lies on the face whose side of the box it is furthest out to.
        on_x = np.abs(local_x) / half[:, 0] >= np.abs(local_y) / half[:, 1]
        nx = np.where(on_x, np.sign(local_x), 0.0)
        ny = np.where(on_x, 0.0, np.sign(local_y))
        normals[hit, 0] = c * nx - s * ny
        normals[hit, 1] = s * nx + c * ny
        return normals

    def nearest_distance(self, point: tuple[float, float]) -> float:
        """The distance from ``point``, seen from above, to the nearest wall (0 inside one;
        ``inf`` without walls), a hair short of it so that no ray meets a wall nearer."""
        if self.center.shape[0] + self.disc_radius.shape[0] == 0:
            return math.inf
        ox = point[0] - self.center[:, 0]
        oy = point[1] - self.center[:, 1]
        out_x = np.maximum(np.abs(self.cos * ox + self.sin * oy) - self.half[:, 0], 0.0)
        out_y = np.maximum(np.abs(-self.sin * ox + self.cos * oy) - self.half[:, 1], 0.0)
        to_disc = np.hypot(point[0] - self.disc_center[:, 0], point[1] - self.disc_center[:, 1])
        gaps = np.concatenate([np.hypot(out_x, out_y), np.maximum(to_disc - self.disc_radius, 0.0)])
        return float(np.min(gaps)) * (1.0 - 1e-9)

    def cast_walls(
        self, origin: tuple[float, float], directions: Floats
    ) -> tuple[Floats, npt.NDArray[np.intp]]:
        """As :meth:`cast`, with the index of the first wall met (-1 when none) instead of its
        reflectance."""
        count = directions.shape[0]
        if self.top.shape[0] == 0:
            return np.full(count, np.inf), np.full(count, -1, dtype=np.intp)
        near, far = self._entries(origin, directions)
        t = np.where(near <= far, near, np.inf)
        nearest = np.argmin(t, axis=1)
        distance = t[np.arange(count), nearest]
        return distance, np.where(np.isfinite(distance), nearest, -1)

    def cast_sloped(
        self,
        origin: tuple[float, float],
        directions: Floats,
        height: float,
        slopes: Floats,
        untopped: MaybeInfinite = math.inf,
    ) -> tuple[Floats, npt.NDArray[np.intp], npt.NDArray[np.bool_]]:
        """As :meth:`cast_walls`, for rays that leave ``origin`` ``height`` above the floor and
        rise by ``slopes`` for each unit of their parameter (a metre across the floor for a
        unit direction; negative: falling): one slope per ray ((N,)), or rows of them ((H, N)),
        rays running along the same lines across the floor at different slopes, as a level
        camera's pixels do. A ray meets a wall's side where it is no higher than the wall's top
        there, falls onto its top, or passes over it; a wall the world gives no top stands
        ``untopped`` high. Each line weighs the walls it crosses nearest first, until no ray
        can meet a nearer one; rows of slopes that every line shares (a level camera's, a
        lidar's layers) are weighed once for all rows (:meth:`_cast_rows`).

        Returns:
            Each ray's parameter at the first wall met (``inf``: none), that wall's index (-1)
            and whether it met the wall's top, shaped as ``slopes``.
        """
        grid = np.atleast_2d(slopes)
        if np.ndim(slopes) == 2 and grid.shape[0] > 1:
            # A broadcast row (stride 0) shares its slopes without a look at them.
            if grid.strides[1] == 0 or bool(np.all(grid == grid[:, :1])):
                return self._cast_rows(origin, directions, height, grid[:, 0], untopped)
        distance = np.full(grid.shape, np.inf)
        wall = np.full(grid.shape, -1, dtype=np.intp)
        on_top = np.zeros(grid.shape, dtype=bool)
        if self.top.shape[0] > 0:
            near, far = self._entries(origin, directions)
            # The entries of the walls each line has yet to weigh (inf: weighed, or missed).
            ahead = np.where(near <= far, near, np.inf)
            lines = np.arange(ahead.shape[0])
            tops = np.where(np.isfinite(self.top), self.top, untopped)
            tallest = float(np.max(tops))
            for _ in range(ahead.shape[1]):
                index = np.argmin(ahead, axis=1)
                entry = ahead[lines, index]
                # Per line, from the wall's and the rays' heights: the steepest slope that meets
                # the wall's side (at its entry), that falls onto its top (by its exit), and
                # above which a rising ray clears every wall's top from here on.
                rise = tops[index] - height
                with np.errstate(divide="ignore", invalid="ignore"):
                    side_most = rise / entry
                    top_most = rise / far[lines, index]
                    clear = (tallest - height) / entry
                # A ray whose hit so far is no farther than this entry, or that rises above
                # every wall's top before it, meets nothing nearer from here on.
                if not ((entry < distance) & ((grid < 0.0) | (grid <= clear))).any():
                    break
                side = grid <= side_most
                onto = ~side & (grid < 0.0) & (grid <= top_most)
                with np.errstate(divide="ignore", invalid="ignore"):
                    t = np.where(side, entry, rise / grid)
                # A line past its last wall weighs a wall it misses (entry inf): no hit.
                nearer = (side | onto) & (t < distance) & np.isfinite(entry)
                distance = np.where(nearer, t, distance)
                wall = np.where(nearer, index, wall)
                on_top = np.where(nearer, onto, on_top)
                ahead[lines, index] = np.inf
        shape = np.shape(slopes)
        return distance.reshape(shape), wall.reshape(shape), on_top.reshape(shape)

    def _cast_rows(
        self,
        origin: tuple[float, float],
        directions: Floats,
        height: float,
        slopes: Floats,
        untopped: float,
    ) -> tuple[Floats, npt.NDArray[np.intp], npt.NDArray[np.bool_]]:
        """:meth:`cast_sloped` of rows of rays that every line shares: every line across the
        floor (``directions``, (W, 2), the columns) carries a ray of each of ``slopes`` ((H,),
        the rows), so each line weighs its walls nearest first once for all its rows.

        Along a line, the walls met nearest first each have the steepest slope of a ray that
        meets them (at their side's entry for a wall above the rays' start, at their top's
        exit for one below it); a row meets the first wall whose slope is at least its own,
        which a sorted search over the running maximum of those slopes finds for every row at
        once. A line stops weighing when the rows still unmet can reach no farther wall: the
        falling ones meet the floor first (a falling ray meets nothing beyond the floor), the
        rising ones clear the tallest top.

        Returns:
            As :meth:`cast_sloped`, each shaped (H, W).
        """
        rows = number_array(slopes, "slopes").reshape(-1)
        count = directions.shape[0]
        shape = (rows.shape[0], count)
        if self.top.shape[0] == 0 or count == 0 or rows.shape[0] == 0:
            return _unmet(shape)
        near, far = self._entries(origin, directions)
        ahead = np.where(near <= far, near, np.inf)
        tops = np.where(np.isfinite(self.top), self.top, untopped)
        tallest = float(np.max(tops))
        # Whether a falling row may land on the top of a wall lower than the rays' start.
        landing = bool(np.any(tops < height))
        ascending = np.sort(rows)
        # The steepest slope met so far along each line, and each pass's wall, entry and slope.
        best = np.full(count, -np.inf)
        passes: list[tuple[npt.NDArray[np.intp], Floats, Floats, Floats]] = []
        lines = np.arange(count)
        # The lines that may meet a wall yet: a line's nearest wall left beyond its reach
        # stays beyond it (its unmet rows change only when it meets a wall).
        open_lines = np.ones(count, dtype=bool)
        while True:
            candidates = lines[open_lines]
            if candidates.shape[0] == 0:
                break
            index = np.argmin(ahead[candidates], axis=1)
            entry = ahead[candidates, index]
            reach = _reach(best[candidates], ascending, height, tallest, landing)
            keep = np.isfinite(entry) & (entry <= reach)
            open_lines[candidates[~keep]] = False
            live, index, entry = candidates[keep], index[keep], entry[keep]
            if live.shape[0] == 0:
                break
            rise = tops[index] - height
            with np.errstate(divide="ignore", invalid="ignore"):
                steepest = np.where(rise >= 0.0, rise / entry, rise / far[live, index])
            slope = np.full(count, -np.inf)
            slope[live] = np.where(np.isnan(steepest), -np.inf, steepest)
            walls_of = np.zeros(count, dtype=np.intp)
            walls_of[live] = index
            entries = np.full(count, np.inf)
            entries[live] = entry
            exits = np.full(count, -np.inf)
            exits[live] = far[live, index]
            passes.append((walls_of, entries, slope, exits))
            best = np.maximum(best, slope)
            ahead[live, index] = np.inf
        if not passes:
            return _unmet(shape)
        # How many rows (ascending) each pass's running slope reaches: a row is its first
        # reaching pass's (later passes drawn first, each over the rows it reaches).
        running = np.maximum.accumulate(np.stack([p[2] for p in passes]), axis=0)
        reached = np.searchsorted(ascending, running, side="right")
        place = np.searchsorted(ascending, rows, side="left")[:, None]
        distance = np.full(shape, np.inf)
        wall = np.full(shape, -1, dtype=np.intp)
        for (walls_of, entries, _, _), count_reached in zip(passes[::-1], reached[::-1]):
            hit = place < count_reached
            np.copyto(distance, entries, where=hit)
            np.copyto(wall, walls_of, where=hit)
        if not landing:
            # Every wall's top is at or above the rays' start: each is met at its side.
            return distance, wall, np.zeros(shape, dtype=bool)
        slope = rows[:, None]
        rise = np.where(wall >= 0, tops[np.maximum(wall, 0)], np.inf) - height
        with np.errstate(divide="ignore", invalid="ignore"):
            on_top = (wall >= 0) & (slope * distance > rise)
            distance = np.where(on_top, rise / slope, distance)
        if on_top.any():
            # A row that lands on a wall's top may meet a wall entered before it lands.
            for walls_of, entries, _, exits in passes:
                rise = tops[walls_of] - height
                with np.errstate(divide="ignore", invalid="ignore"):
                    side = slope * entries <= rise
                    onto = ~side & (slope < 0.0) & (slope * exits <= rise)
                    t = np.where(side, entries, np.where(onto, rise / slope, np.inf))
                nearer = on_top & (t < distance)
                distance = np.where(nearer, t, distance)
                wall = np.where(nearer, walls_of, wall)
                on_top = np.where(nearer, onto, on_top)
        return distance, wall, on_top

    def _entries(self, origin: tuple[float, float], directions: Floats) -> tuple[Floats, Floats]:
        """Where each ray (rows) enters and leaves each box, then each cylinder (columns), as
        ray parameters (the entry no earlier than the origin); entry above exit where it misses
        it."""
        near, far = self._box_entries(origin, directions)
        if self.disc_radius.shape[0] == 0:
            return near, far
        # |origin + t d - centre| = radius: a t^2 + 2 b t + c = 0 (d need not be a unit).
        ox = origin[0] - self.disc_center[:, 0]
        oy = origin[1] - self.disc_center[:, 1]
        a = np.sum(directions * directions, axis=1)[:, None]
        b = directions[:, 0:1] * ox + directions[:, 1:2] * oy
        c = ox * ox + oy * oy - self.disc_radius * self.disc_radius
        with np.errstate(divide="ignore", invalid="ignore"):
            root = np.sqrt(np.maximum(b * b - a * c, 0.0))
            crossed = (b * b - a * c >= 0.0) & (a > 0.0)
            enter = np.where(crossed, (-b - root) / a, np.inf)
            leave = np.where(crossed, (-b + root) / a, -np.inf)
        near = np.concatenate([near, np.maximum(enter, 0.0)], axis=1)
        return near, np.concatenate([far, leave], axis=1)

    def _box_entries(
        self, origin: tuple[float, float], directions: Floats
    ) -> tuple[Floats, Floats]:
        """:meth:`_entries` of the boxes."""
        # Origin and directions in each box's frame: (boxes,) and (rays, boxes).
        ox = origin[0] - self.center[:, 0]
        oy = origin[1] - self.center[:, 1]
        local_ox = self.cos * ox + self.sin * oy
        local_oy = -self.sin * ox + self.cos * oy
        dx = directions[:, 0:1]
        dy = directions[:, 1:2]
        local_dx = self.cos * dx + self.sin * dy
        local_dy = -self.sin * dx + self.cos * dy
        with np.errstate(divide="ignore", invalid="ignore"):
            near_x, far_x = _slab(local_ox, local_dx, self.half[:, 0])
            near_y, far_y = _slab(local_oy, local_dy, self.half[:, 1])
        return np.maximum(np.maximum(near_x, near_y), 0.0), np.minimum(far_x, far_y)


def _unmet(shape: tuple[int, int]) -> tuple[Floats, npt.NDArray[np.intp], npt.NDArray[np.bool_]]:
    """What :meth:`WallBoxes._cast_rows` returns where no ray meets a wall."""
    return np.full(shape, np.inf), np.full(shape, -1, dtype=np.intp), np.zeros(shape, bool)


def _reach(best: Floats, ascending: Floats, height: float, tallest: float, landing: bool) -> Floats:
    """How far along its line each line of :meth:`WallBoxes._cast_rows` may still meet a wall:
    its unmet rows are those of slopes above ``best``; a falling one meets the floor
    ``height / -slope`` away, a rising one clears the ``tallest`` top; -inf when every row is
    met. With ``landing`` (a wall lower than the rays' start), every falling row counts as
    unmet: one that lands on a top may yet meet a wall entered before it lands."""
    rows = ascending.shape[0]
    first_unmet = np.searchsorted(ascending, best, side="right")
    level_from = int(np.searchsorted(ascending, 0.0, side="left"))
    # The unmet falling row nearest level, and the unmet rising (or level) row nearest it.
    falls = (first_unmet < level_from) | (landing and level_from > 0)
    falling = ascending[max(level_from - 1, 0)]
    rising_at = np.maximum(first_unmet, level_from)
    rises = rising_at < rows
    rising = ascending[np.minimum(rising_at, rows - 1)]
    with np.errstate(divide="ignore", invalid="ignore"):
        to_floor = np.where(falls, height / -falling, -np.inf)
        if tallest < height:
            to_clear = np.full(best.shape, -np.inf)
        else:
            to_clear = np.where(rising > 0.0, (tallest - height) / rising, np.inf)
    return np.asarray(np.maximum(to_floor, np.where(rises, to_clear, -np.inf)))


def _slab(origin: Floats, direction: Floats, half: Floats) -> tuple[Floats, Floats]:
    """Entry and exit parameters of rays through the slab ``-half <= s <= half``."""
    low = (-half - origin) / direction
    high = (half - origin) / direction
    inside = np.abs(origin) <= half
    parallel = direction == 0.0
    near = np.where(parallel, np.where(inside, -np.inf, np.inf), np.minimum(low, high))
    far = np.where(parallel, np.where(inside, np.inf, -np.inf), np.maximum(low, high))
    return near, far


class FloorPaint:
    """The floor paint of a world, read once, for the reflectance and colour at many points at
    a time."""

    def __init__(self, world: World) -> None:
        self.background = float(world.floor_background)
        self.regions = world.paint_regions()
        #: The reflectance of the bare floor, then of each region.
        self.reflectances = np.array(
            [self.background] + [_number(r, "reflectance") for r in self.regions]
        )
        #: The colour (red, green, blue in [0, 1]) of the bare floor, then of each region; NaN
        #: where none is given.
        self.colours = np.array(
            [_colour(world.floor_colour)] + [_colour(r.get("colour")) for r in self.regions]
        ).reshape(-1, 3)
        self._grid = _PaintGrid([_bounds(r) for r in self.regions])

    def reflectance(self, x: Floats, y: Floats) -> Floats:
        """The floor's reflectance factor at each point (later paint drawn over earlier)."""
        return np.asarray(self.reflectances[self.region(x, y) + 1], dtype=np.float64)

    def region(self, x: Floats, y: Floats) -> npt.NDArray[np.intp]:
        """The paint region seen at each point (the last drawn there), -1 for the bare floor.

        Each region tests only the points in the grid cells its bounding box covers."""
        nowhere = "a point in no region"
        x, y = np.broadcast_arrays(
            number_array(x, "x", nan_means=nowhere, inf_means=nowhere),
            number_array(y, "y", nan_means=nowhere, inf_means=nowhere),
        )
        px, py = x.ravel(), y.ravel()
        result = np.full(px.shape, -1, dtype=np.intp)
        for index, points in self._grid.candidates(px, py):
            inside = _inside(self.regions[index], px[points], py[points])
            result[points[inside]] = index
        return result.reshape(x.shape)


def _inside(region: dict[str, object], x: Floats, y: Floats) -> npt.NDArray[np.bool_]:
    """Whether each point lies in the paint region."""
    shape = region["shape"]
    if shape == "rect":
        cx, cy = _pair(region, "center")
        sx, sy = _pair(region, "size")
        yaw = _number(region, "yaw")
        c, s = np.cos(yaw), np.sin(yaw)
        u = c * (x - cx) + s * (y - cy)
        v = -s * (x - cx) + c * (y - cy)
        return np.asarray((np.abs(u) <= sx / 2.0) & (np.abs(v) <= sy / 2.0))
    if shape == "circle":
        cx, cy = _pair(region, "center")
        return np.asarray(np.hypot(x - cx, y - cy) <= _number(region, "radius"))
    a, b = _pair(region, "a"), _pair(region, "b")
    return np.asarray(_segment_distance(x, y, a, b) <= _number(region, "radius"))


#: Added to each side of a paint region's bounding box (m), far above rounding errors.
BOUNDS_MARGIN = 1e-6
#: Cells along each side of the grid over the paint.
GRID_CELLS = 64


def _bounds(region: dict[str, object]) -> tuple[float, float, float, float]:
    """A box (x0, y0, x1, y1) holding the paint region, a little larger."""
    shape = region["shape"]
    if shape == "rect":
        cx, cy = _pair(region, "center")
        sx, sy = _pair(region, "size")
        c, s = abs(math.cos(_number(region, "yaw"))), abs(math.sin(_number(region, "yaw")))
        half_x = (c * abs(sx) + s * abs(sy)) / 2.0
        half_y = (s * abs(sx) + c * abs(sy)) / 2.0
        box = (cx - half_x, cy - half_y, cx + half_x, cy + half_y)
    elif shape == "circle":
        cx, cy = _pair(region, "center")
        r = abs(_number(region, "radius"))
        box = (cx - r, cy - r, cx + r, cy + r)
    else:
        (ax, ay), (bx, by) = _pair(region, "a"), _pair(region, "b")
        r = abs(_number(region, "radius"))
        box = (min(ax, bx) - r, min(ay, by) - r, max(ax, bx) + r, max(ay, by) + r)
    m = BOUNDS_MARGIN
    return (box[0] - m, box[1] - m, box[2] + m, box[3] + m)


class _PaintGrid:
    """A grid over the paint regions' bounding boxes: which points may lie in which region."""

    def __init__(self, bounds: list[tuple[float, float, float, float]]) -> None:
        self.count = len(bounds)
        unknown = "a box of no known bounds"
        boxes = np.array(
            number_array(bounds, "bounds", nan_means=unknown, inf_means=unknown)
        ).reshape(-1, 4)
        #: Whether every box is finite; otherwise every point is every region's candidate.
        self.bounded = bool(np.isfinite(boxes).all())
        self.low = boxes[:, :2].min(axis=0) if self.count else np.zeros(2)
        self.high = boxes[:, 2:].max(axis=0) if self.count else np.zeros(2)
        self.cell = np.zeros(2)
        if self.bounded:
            self.cell = np.maximum((self.high - self.low) / GRID_CELLS, 1e-9)
            #: Each region's first and last cell along x and y.
            self.first = self._cells(boxes[:, :2])
            self.last = self._cells(boxes[:, 2:])

    def _cells(self, points: Floats) -> npt.NDArray[np.intp]:
        """The cell (column, row) of each point, clamped to the grid."""
        cells = np.floor((points - self.low) / self.cell)
        return np.asarray(np.clip(cells, 0, GRID_CELLS - 1), dtype=np.intp)

    def candidates(self, x: Floats, y: Floats) -> Iterator[tuple[int, npt.NDArray[np.intp]]]:
        """Each region's index, in drawing order, with the indices of the points in the
        cells its box covers, where there are any (a point outside every box is nobody's
        candidate)."""
        if self.count == 0:
            return
        if not self.bounded:
            for index in range(self.count):
                yield index, np.arange(len(x))
            return
        points = np.stack([x, y], axis=1)
        within = np.all((points >= self.low) & (points <= self.high), axis=1)
        kept = np.flatnonzero(within)
        cells = self._cells(points[kept])
        cell_ids = cells[:, 1] * GRID_CELLS + cells[:, 0]
        order = np.argsort(cell_ids, kind="stable")
        sorted_points = kept[order]
        starts = np.searchsorted(cell_ids[order], np.arange(GRID_CELLS * GRID_CELLS + 1))
        for index in range(self.count):
            (x0, y0), (x1, y1) = self.first[index], self.last[index]
            rows = [
                sorted_points[starts[row * GRID_CELLS + x0] : starts[row * GRID_CELLS + x1 + 1]]
                for row in range(y0, y1 + 1)
            ]
            candidates = np.concatenate(rows)
            if candidates.size:
                yield index, candidates


def _number(region: dict[str, object], key: str) -> float:
    value = region[key]
    assert isinstance(value, (int, float)), f"paint {key}: expected a number, found {_shown(value)}"
    return float(value)


def _colour(value: object) -> tuple[float, float, float]:
    """A colour given as (red, green, blue), or NaNs for none."""
    if value is None:
        return (math.nan, math.nan, math.nan)
    assert isinstance(value, (list, tuple)), f"colour: expected (r, g, b), found {_shown(value)}"
    red, green, blue = (float(v) for v in value)
    return (red, green, blue)


def _pair(region: dict[str, object], key: str) -> tuple[float, float]:
    value = region[key]
    assert isinstance(value, (list, tuple)), f"paint {key}: expected [x, y], found {_shown(value)}"
    return float(value[0]), float(value[1])


def _segment_distance(
    x: Floats, y: Floats, a: tuple[float, float], b: tuple[float, float]
) -> Floats:
    abx, aby = b[0] - a[0], b[1] - a[1]
    length2 = abx * abx + aby * aby
    if length2 == 0.0:
        return np.asarray(np.hypot(x - a[0], y - a[1]))
    t = np.clip(((x - a[0]) * abx + (y - a[1]) * aby) / length2, 0.0, 1.0)
    return np.asarray(np.hypot(x - (a[0] + t * abx), y - (a[1] + t * aby)))
