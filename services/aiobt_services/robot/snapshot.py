"""Top-down PNG of the world: map, obstacles, dock, robot and (optionally) a scan."""

from __future__ import annotations

import io
import math

import numpy as np
from PIL import Image, ImageDraw

from aiobt.geometry import Pose2D

from .mapfile import FREE, OCCUPIED
from .sim import Scan, Simulation

COLOURS = {"free": 250, "occupied": 20, "unknown": 160}


def _map_image(sim: Simulation, scale: int) -> Image.Image:
    grid = sim.world.grid
    pixels = np.full(grid.shape, COLOURS["unknown"], dtype=np.uint8)
    pixels[grid == FREE] = COLOURS["free"]
    pixels[grid == OCCUPIED] = COLOURS["occupied"]
    image = Image.fromarray(np.ascontiguousarray(np.flipud(pixels))).convert("RGB")
    return image.resize((image.width * scale, image.height * scale), Image.Resampling.NEAREST)


def render(sim: Simulation, *, scale: int = 2, scan: Scan | None = None) -> Image.Image:
    """Render the current state; one map cell is ``scale`` pixels."""
    image = _map_image(sim, scale)
    draw = ImageDraw.Draw(image)
    world = sim.world
    px_per_m = scale / world.resolution

    def to_px(x: float, y: float) -> tuple[float, float]:
        row, col = world.world_to_cell(x, y)
        return col * scale, image.height - row * scale

    def disc(x: float, y: float, radius: float, fill: tuple[int, int, int]) -> None:
        u, v = to_px(x, y)
        r = radius * px_per_m
        draw.ellipse((u - r, v - r, u + r, v + r), fill=fill)

    def box(pose: Pose2D, hx: float, hy: float, fill: tuple[int, int, int]) -> None:
        c, s = math.cos(pose.yaw), math.sin(pose.yaw)
        corners = [
            (pose.x + c * a - s * b, pose.y + s * a + c * b)
            for a, b in ((hx, hy), (-hx, hy), (-hx, -hy), (hx, -hy))
        ]
        draw.polygon([to_px(x, y) for x, y in corners], fill=fill)

    if sim.dock_station is not None:
        centre, (hx, hy, _) = sim.dock_station.block()
        box(centre, hx, hy, (60, 170, 60))
    for oid, spec in sim.obstacles.items():
        pose = sim.obstacle_pose(oid)
        if spec.shape == "cylinder":
            disc(pose.x, pose.y, spec.radius, (220, 60, 60))
            continue
        box(pose, spec.size_x / 2, spec.size_y / 2, (220, 60, 60))
    if scan is not None:
        _draw_scan(draw, sim, scan, to_px)
    robot = sim.true_pose
    disc(robot.x, robot.y, sim.config.robot.radius, (40, 80, 220))
    tip = (
        robot.x + sim.config.robot.radius * math.cos(robot.yaw),
        robot.y + sim.config.robot.radius * math.sin(robot.yaw),
    )
    draw.line([to_px(robot.x, robot.y), to_px(*tip)], fill=(255, 255, 255), width=max(1, scale))
    return image


def _draw_scan(draw: ImageDraw.ImageDraw, sim: Simulation, scan: Scan, to_px: object) -> None:
    pose = sim.true_pose
    finite = np.isfinite(scan.ranges)
    angles = pose.yaw + scan.config.angles()[finite]
    xs = pose.x + scan.ranges[finite] * np.cos(angles)
    ys = pose.y + scan.ranges[finite] * np.sin(angles)
    convert = to_px if callable(to_px) else None
    assert convert is not None
    for x, y in zip(xs, ys, strict=True):
        u, v = convert(float(x), float(y))
        draw.rectangle((u - 1, v - 1, u + 1, v + 1), fill=(250, 160, 0))


def render_png(sim: Simulation, *, scale: int = 2, with_scan: bool = True) -> bytes:
    image = render(sim, scale=scale, scan=sim.scan() if with_scan else None)
    buffer = io.BytesIO()
    image.save(buffer, format="PNG")
    return buffer.getvalue()
