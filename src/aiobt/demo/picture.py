"""The demo's PNG: map, inflated costmap, planned paths, the driven tracks (the pose
estimate's, and the simulation's truth wide under it), start, goals with their
tolerance, recoveries; a title, a summary, a scale bar and a legend
(:mod:`aiobt.demo.annotate`)."""

from __future__ import annotations

import io
import math

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from aiobt.costmap.grid import LETHAL, NO_INFORMATION, GridGeometry
from aiobt.costmap.inflation import InflationParams, inflate
from aiobt.demo.annotate import (
    COST,
    GOAL,
    OBSTACLE,
    PLAN,
    TRAIL,
    TRUTH,
    UNKNOWN,
    WALL,
    cross,
    framed,
    scale_bar,
    start_mark,
)
from aiobt.demo.record import XY, Record
from aiobt.display import plural

SCALE = 6  # pixels per map cell
GOAL_TOLERANCE = 0.25  # m: the goal checker's xy_goal_tolerance (Nav2's default)


def summary(record: Record) -> str:
    """``4 of 4 goals reached in 85.3 s of sim time, 1 recovery`` and, with the truth, a
    second line: ``pose estimate off the truth by 1.2 cm RMS, 4.0 cm at worst``."""
    reached = sum(leg.reached for leg in record.legs)
    seconds = sum(leg.seconds for leg in record.legs)
    recoveries = sum(leg.recoveries for leg in record.legs)
    tracking = record.tracking.summary()
    return (
        f"{reached} of {plural(len(record.legs), 'goal')} reached in {seconds:.1f} s of sim "
        f"time, {plural(recoveries, 'recovery')}" + (f"\n{tracking}" if tracking else "")
    )


def render(
    record: Record, inflation: InflationParams | None = None, title: str = "aiobt demo"
) -> bytes:
    """The PNG bytes of ``record`` (which must hold the map), headed by ``title``."""
    if record.map is None:
        raise ValueError("no map was received: nothing to draw")
    grid = record.map
    info = grid.info
    geometry = GridGeometry(
        info.width, info.height, info.resolution, info.origin.position.x, info.origin.position.y
    )
    cells = np.asarray(grid.array)
    master = np.where(cells < 0, NO_INFORMATION, np.where(cells >= 65, LETHAL, 0)).astype(np.uint8)
    costs = inflate(master, geometry, inflation or InflationParams())
    image = Image.fromarray(_colours(cells, costs)[::-1], "RGB")
    image = image.resize((info.width * SCALE, info.height * SCALE), Image.Resampling.NEAREST)
    draw = ImageDraw.Draw(image)
    to_px = _projector(geometry, info.height * SCALE)
    for x, y, yaw, sx, sy in record.obstacles:
        c, s = math.cos(yaw), math.sin(yaw)
        corners = [(x + c * u - s * v, y + s * u + c * v) for u, v in _box(sx, sy)]
        draw.polygon([to_px(p) for p in corners], outline=OBSTACLE, width=3)
    for leg in record.legs:
        if len(leg.plan) > 1:
            draw.line([to_px(p) for p in leg.plan], fill=PLAN, width=2)
    if len(record.truth) > 1:  # wide, under the estimate: where they agree both show
        draw.line([to_px(p) for p in record.truth], fill=TRUTH, width=9, joint="curve")
    if len(record.trajectory) > 1:
        draw.line([to_px(p) for p in record.trajectory], fill=TRAIL, width=3)
    if record.trajectory:
        start_mark(draw, to_px(record.trajectory[0]))
    ring = GOAL_TOLERANCE / info.resolution * SCALE
    for number, leg in enumerate(record.legs, 1):
        _goal(draw, to_px(leg.goal[:2]), str(number), leg.reached, ring)
    for where in record.recoveries:
        cross(draw, to_px(where))
    scale_bar(draw, SCALE / info.resolution, image.height)
    out = io.BytesIO()
    framed(image, title, summary(record)).save(out, "PNG")
    return out.getvalue()


def _box(sx: float, sy: float) -> list[tuple[float, float]]:
    return [(-sx / 2, -sy / 2), (sx / 2, -sy / 2), (sx / 2, sy / 2), (-sx / 2, sy / 2)]


def _colours(cells: np.ndarray, costs: np.ndarray) -> np.ndarray:
    rgb = np.full((*cells.shape, 3), 255, np.uint8)
    shade = (costs.astype(np.float32) / 253.0).clip(0, 1)[..., None]
    rgb = (255 - shade * (255 - np.array(COST, np.float32))).astype(np.uint8)
    rgb[cells < 0] = UNKNOWN
    rgb[cells >= 65] = WALL
    return rgb


def _projector(geometry: GridGeometry, height_px: int):  # type: ignore[no-untyped-def]
    def to_px(point: XY | tuple[float, ...]) -> tuple[float, float]:
        col = (point[0] - geometry.origin_x) / geometry.resolution * SCALE
        row = (point[1] - geometry.origin_y) / geometry.resolution * SCALE
        return col, height_px - row

    return to_px


def _goal(
    draw: ImageDraw.ImageDraw, at: tuple[float, float], label: str, reached: bool, ring: float
) -> None:
    x, y = at
    fill = None if reached else OBSTACLE
    draw.ellipse((x - ring, y - ring, x + ring, y + ring), outline=GOAL, width=3, fill=fill)
    draw.text((x + ring + 3, y - ring - 3), label, fill=GOAL, font=ImageFont.load_default(16))
