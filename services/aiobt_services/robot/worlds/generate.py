"""Regenerate the shipped worlds: ``python -m aiobt_services.robot.worlds.generate``.

Fully deterministic (no randomness): running it again rewrites identical files.
"""

from __future__ import annotations

import argparse
import logging
import math
from pathlib import Path

import numpy as np

from ..mapfile import FREE, OCCUPIED, Dock, MapInfo, save_map
from . import WORLDS_DIR

log = logging.getLogger("aiobt_services.robot.worlds")
WALL = 0.15


class Canvas:
    """A free grid that walls and furniture are painted onto, in metres."""

    def __init__(self, width_m: float, height_m: float, resolution: float) -> None:
        self.resolution = resolution
        rows, cols = round(height_m / resolution), round(width_m / resolution)
        self.grid = np.full((rows, cols), FREE, dtype=np.int8)

    def _span(self, lo: float, hi: float) -> slice:
        return slice(round(lo / self.resolution), round(hi / self.resolution))

    def fill(self, x0: float, y0: float, x1: float, y1: float, value: int = OCCUPIED) -> None:
        self.grid[self._span(y0, y1), self._span(x0, x1)] = value

    def hwall(self, y: float, x0: float, x1: float, doors: tuple[float, ...] = ()) -> None:
        self.fill(x0, y - WALL / 2, x1, y + WALL / 2)
        for door in doors:
            self.fill(door - 0.5, y - WALL, door + 0.5, y + WALL, FREE)

    def vwall(self, x: float, y0: float, y1: float, doors: tuple[float, ...] = ()) -> None:
        self.fill(x - WALL / 2, y0, x + WALL / 2, y1)
        for door in doors:
            self.fill(x - WALL, door - 0.5, x + WALL, door + 0.5, FREE)

    def border(self, width_m: float, height_m: float) -> None:
        self.fill(0, 0, width_m, WALL)
        self.fill(0, height_m - WALL, width_m, height_m)
        self.fill(0, 0, WALL, height_m)
        self.fill(width_m - WALL, 0, width_m, height_m)

    def disc(self, cx: float, cy: float, radius: float) -> None:
        rows, cols = np.mgrid[0 : self.grid.shape[0], 0 : self.grid.shape[1]]
        xs, ys = (cols + 0.5) * self.resolution, (rows + 0.5) * self.resolution
        self.grid[np.hypot(xs - cx, ys - cy) <= radius] = OCCUPIED


def office() -> MapInfo:
    """A 20 x 20 m floor: a corridor, three rooms south, open plan and two rooms north."""
    c = Canvas(20.0, 20.0, 0.05)
    c.border(20.0, 20.0)
    c.hwall(8.5, 0.0, 20.0, doors=(3.5, 10.0, 16.5))  # south side of the corridor
    c.hwall(11.0, 0.0, 20.0, doors=(4.0, 9.0, 14.0, 17.5))  # north side
    c.vwall(7.0, 0.0, 8.5)
    c.vwall(13.0, 0.0, 8.5, doors=(4.0,))  # a door between the two east rooms
    c.vwall(12.0, 11.0, 20.0, doors=(18.0,))  # open plan <-> north-east room
    c.hwall(15.5, 12.0, 20.0, doors=(16.0,))
    c.fill(1.5, 2.0, 3.5, 3.0)  # tables in the west room
    c.fill(4.0, 5.0, 5.5, 6.0)
    c.fill(9.0, 2.5, 11.0, 5.0)  # meeting table
    c.fill(15.0, 1.0, 18.5, 1.8)  # a bench along the south-east wall
    for x in (3.0, 6.0, 9.0):  # desks in the open plan
        c.fill(x - 0.7, 16.0, x + 0.7, 16.8)
    c.disc(6.0, 13.5, 0.3)  # pillars
    c.disc(9.5, 13.5, 0.3)
    c.fill(13.5, 17.5, 14.5, 19.0)  # cabinets
    c.fill(17.5, 12.0, 19.0, 13.0)
    return MapInfo(
        grid=c.grid,
        resolution=c.resolution,
        origin=(0.0, 0.0, 0.0),
        start=(2.0, 9.75, 0.0),
        dock=Dock(0.49, 9.75, math.pi),  # the block on the west wall, facing east
    )


def small() -> MapInfo:
    """A 5 x 5 m room centred on the origin with a wall stub; start at the centre."""
    c = Canvas(5.0, 5.0, 0.05)
    c.border(5.0, 5.0)
    c.fill(0.5, 3.6, 1.5, 3.75)  # a short wall stub near the north-west corner
    return MapInfo(
        grid=c.grid,
        resolution=c.resolution,
        origin=(-2.5, -2.5, 0.0),
        start=(0.0, 0.0, 0.0),
        dock=Dock(-2.01, -1.2, math.pi),  # the block on the west wall
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", type=Path, default=WORLDS_DIR, help="output folder")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO)
    for name, build in (("office", office), ("small", small)):
        save_map(build(), args.out / f"{name}.yaml")
        log.info("wrote %s", args.out / f"{name}.yaml")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
