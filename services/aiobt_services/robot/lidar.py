"""The planar lidar as geometry: rays against rectangles and discs in the lidar's plane.

The walls are 1 m tall boxes standing on the floor and the lidar sweeps a plane
at 0.2 m, so in that plane every wall is a rectangle, an obstacle taller than
the plane a rectangle or a disc, and a scan is a set of ray-rectangle and
ray-disc intersections: done here in numpy for all rays at once. It gives the
ranges pybullet's ``rayTestBatch`` gives on the same bodies (Bullet rounds a
box's corners by its 4 cm collision margin: rays that graze a corner may differ
by up to about 2 cm), at a fraction of its cost (``bench/robot/sim_speed``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]


@dataclass(slots=True, frozen=True)
class Rectangles:
    """Rectangles sharing one orientation: bounds ``lo``/``hi`` (M x 2) in the frame
    rotated by ``yaw`` (for a map's walls, the map's own orientation)."""

    yaw: float
    lo: FloatArray
    hi: FloatArray

    @classmethod
    def from_centres(
        cls, xs: npt.ArrayLike, ys: npt.ArrayLike, half_x: npt.ArrayLike, half_y: npt.ArrayLike,
        yaw: float,
    ) -> Rectangles:  # fmt: skip
        xs, ys = np.asarray(xs, dtype=np.float64), np.asarray(ys, dtype=np.float64)
        c, s = math.cos(yaw), math.sin(yaw)
        centres = np.stack([c * xs + s * ys, -s * xs + c * ys], axis=1).astype(np.float64)
        half = np.stack([half_x, half_y], axis=1).astype(np.float64)
        if np.any(half < 0.0) or not np.all(np.isfinite(centres)):
            raise ValueError("rectangles need finite centres and half extents >= 0")
        return cls(yaw, centres - half, centres + half)


@dataclass(slots=True, frozen=True)
class Disc:
    x: float
    y: float
    radius: float


def rectangle_distances(
    rects: Rectangles, ox: float, oy: float, ux: FloatArray, uy: FloatArray
) -> FloatArray:
    """Distance along each unit ray (``ux``, ``uy``) from (``ox``, ``oy``) to the nearest
    rectangle (slab method); 0 when the origin is inside one; ``inf`` for no hit."""
    if len(rects.lo) == 0:
        return np.full(len(ux), np.inf)
    c, s = math.cos(rects.yaw), math.sin(rects.yaw)
    px, py = c * ox + s * oy, -s * ox + c * oy
    with np.errstate(divide="ignore", invalid="ignore"):
        inv_x = (1.0 / (c * ux + s * uy))[:, None]
        inv_y = (1.0 / (-s * ux + c * uy))[:, None]
        x1, x2 = (rects.lo[:, 0] - px) * inv_x, (rects.hi[:, 0] - px) * inv_x
        y1, y2 = (rects.lo[:, 1] - py) * inv_y, (rects.hi[:, 1] - py) * inv_y
        near = np.maximum(np.fmin(x1, x2), np.fmin(y1, y2))
        far = np.minimum(np.fmax(x1, x2), np.fmax(y1, y2))
    hit = (near <= far) & (far >= 0.0)
    best: FloatArray = np.where(hit, np.maximum(near, 0.0), np.inf).min(axis=1)
    return best


def disc_distances(
    discs: Sequence[Disc], ox: float, oy: float, ux: FloatArray, uy: FloatArray
) -> FloatArray:
    """Distance along each unit ray to the nearest disc; 0 inside one; ``inf``: none."""
    best = np.full(len(ux), np.inf)
    for disc in discs:
        mx, my = ox - disc.x, oy - disc.y
        b = mx * ux + my * uy
        inside = mx * mx + my * my - disc.radius * disc.radius
        root = np.sqrt(np.maximum(b * b - inside, 0.0))
        hit = (b * b - inside >= 0.0) & (root - b >= 0.0)
        best = np.minimum(best, np.where(hit, np.maximum(-b - root, 0.0), np.inf))
    return best


def cast(
    walls: Rectangles,
    obstacles: Sequence[Rectangles],
    discs: Sequence[Disc],
    origin: tuple[float, float],
    headings: FloatArray,
) -> FloatArray:
    """Distance along each heading (rad, in the map) to the nearest wall, rectangle or
    disc from ``origin``; ``inf`` where a ray meets nothing."""
    ox, oy = origin
    ux, uy = np.cos(headings), np.sin(headings)
    best = rectangle_distances(walls, ox, oy, ux, uy)
    for rects in obstacles:
        best = np.minimum(best, rectangle_distances(rects, ox, oy, ux, uy))
    if discs:
        best = np.minimum(best, disc_distances(discs, ox, oy, ux, uy))
    return best


# an obstacle as the lidar's plane cuts it: a box (x, y, yaw, half x, half y) or a disc
Solid = tuple[float, float, float, float, float] | Disc


def cast_solids(
    walls: Rectangles, solids: Sequence[Solid], origin: tuple[float, float], headings: FloatArray
) -> FloatArray:
    """:func:`cast` against the walls and ``solids`` (boxes one by one, the discs)."""
    rects, discs = [], []
    for shape in solids:
        if isinstance(shape, Disc):
            discs.append(shape)
        else:
            x, y, yaw, half_x, half_y = shape
            rects.append(Rectangles.from_centres([x], [y], [half_x], [half_y], yaw))
    return cast(walls, rects, discs, origin, headings)
