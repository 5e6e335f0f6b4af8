"""The demo's PNG: map, inflated costmap, planned paths, driven trajectory, goals, recoveries."""

from __future__ import annotations

import io
import math

import numpy as np
from PIL import Image, ImageDraw

from aiobt.costmap.grid import LETHAL, NO_INFORMATION, GridGeometry
from aiobt.costmap.inflation import InflationParams, inflate
from aiobt.demo.record import XY, Record

SCALE = 6  # pixels per map cell
_LEGEND_HEIGHT = 30  # px under the map
PLAN, TRAIL, GOAL, RECOVERY, OBSTACLE = (
    (40, 90, 220), (220, 40, 40), (20, 150, 60), (245, 140, 0), (140, 60, 170)
)  # fmt: skip


def render(record: Record, inflation: InflationParams | None = None) -> bytes:
    """The PNG bytes of ``record`` (which must hold the map)."""
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
    if len(record.trajectory) > 1:
        draw.line([to_px(p) for p in record.trajectory], fill=TRAIL, width=3)
    for number, leg in enumerate(record.legs, 1):
        _goal(draw, to_px(leg.goal[:2]), str(number), leg.reached)
    for where in record.recoveries:
        _cross(draw, to_px(where))
    framed = Image.new("RGB", (image.width, image.height + _LEGEND_HEIGHT), (255, 255, 255))
    framed.paste(image, (0, 0))
    _legend(ImageDraw.Draw(framed), image.height)
    out = io.BytesIO()
    framed.save(out, "PNG")
    return out.getvalue()


def _box(sx: float, sy: float) -> list[tuple[float, float]]:
    return [(-sx / 2, -sy / 2), (sx / 2, -sy / 2), (sx / 2, sy / 2), (-sx / 2, sy / 2)]


def _colours(cells: np.ndarray, costs: np.ndarray) -> np.ndarray:
    rgb = np.full((*cells.shape, 3), 255, np.uint8)
    shade = (costs.astype(np.float32) / 253.0).clip(0, 1)[..., None]
    tint = np.array([120, 170, 255], np.float32)
    rgb = (255 - shade * (255 - tint)).astype(np.uint8)  # inflation in light blue
    rgb[cells < 0] = (180, 180, 180)
    rgb[cells >= 65] = (0, 0, 0)
    return rgb


def _projector(geometry: GridGeometry, height_px: int):  # type: ignore[no-untyped-def]
    def to_px(point: XY | tuple[float, ...]) -> tuple[float, float]:
        col = (point[0] - geometry.origin_x) / geometry.resolution * SCALE
        row = (point[1] - geometry.origin_y) / geometry.resolution * SCALE
        return col, height_px - row

    return to_px


def _goal(draw: ImageDraw.ImageDraw, at: tuple[float, float], label: str, reached: bool) -> None:
    x, y = at
    draw.ellipse(
        (x - 9, y - 9, x + 9, y + 9), outline=GOAL, width=3, fill=None if reached else OBSTACLE
    )
    draw.text((x + 11, y - 7), label, fill=GOAL)


def _cross(draw: ImageDraw.ImageDraw, at: tuple[float, float]) -> None:
    x, y = at
    draw.line((x - 8, y - 8, x + 8, y + 8), fill=RECOVERY, width=4)
    draw.line((x - 8, y + 8, x + 8, y - 8), fill=RECOVERY, width=4)


def _legend(draw: ImageDraw.ImageDraw, top: int) -> None:
    entries = [
        (PLAN, "planned path"), (TRAIL, "driven"), (GOAL, "goal"),
        (RECOVERY, "recovery"), (OBSTACLE, "obstacle"),
    ]  # fmt: skip
    for column, (colour, text) in enumerate(entries):
        x, y = 8 + column * 120, top + 10
        draw.rectangle((x, y, x + 10, y + 10), fill=colour)
        draw.text((x + 16, y - 1), text, fill=(0, 0, 0))
