"""Per-scan cost of the planner's world model: incremental update vs full rebuild.

Run: ``.venv/bin/python -m bench.system.costmap_update --scans 200``

The office world's global costmap (400 x 400 cells, the planner's defaults: 2x2
search blocks) receives scans taken along a straight drive (360 beams, a box
moving across the view); after each scan the planner's traversal and compiled
graph are brought up to date. Incremental: the costmap's changed window, then
``Traversal.updated`` (what the planner does). Baseline in the same run: the
same scans, then a full re-inflation, a new Traversal and a new graph (what the
planner did before). Also: a scan that changes nothing. Both end states are
checked equal. Prints ms per scan (median, p90) and the ratio.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import numpy as np

from aiobt.costmap import CostGrid, Costmap, GridGeometry, Scan
from aiobt_services.planner.traversal import SearchParams, Traversal
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.worlds import OFFICE

PARAMS = SearchParams(downsample=2)


def scans(count: int) -> list[Scan]:
    """Along y = 9.75 from x = 2 at 1 cm per scan, a box 1.5 m ahead sliding sideways."""
    angles = -math.pi + np.arange(360) * (2 * math.pi / 360)
    out = []
    for i in range(count):
        ranges = np.full(360, 6.0)
        ahead = np.abs(angles - 0.3 * math.sin(i / 20)) < 0.15
        ranges[ahead] = 1.5
        out.append(Scan.create((2.0 + 0.01 * i, 9.75, 0.0), -math.pi, 2 * math.pi / 360,
                               ranges, 0.1, 12.0))  # fmt: skip
    return out


def world() -> Costmap:
    info = load_map(OFFICE)
    geometry = GridGeometry(info.width, info.height, info.resolution, *info.origin[:2])
    costmap = Costmap.from_occupancy(info.grid, geometry)
    costmap.master  # noqa: B018 - built before timing
    return costmap


def incremental(costmap: Costmap, batch: list[Scan]) -> tuple[list[float], Traversal]:
    traversal = Traversal(costmap.snapshot(), PARAMS)
    traversal.graph()
    version, times = costmap.version, []
    for scan in batch:
        began = time.perf_counter()
        costmap.update_from_scan(scan)
        master = costmap.master
        if costmap.version != version:
            window = costmap.changed_since(version)
            grid = CostGrid(costmap.geometry, master.copy())
            traversal = (traversal.updated(grid, window) if window is not None
                         else Traversal(grid, PARAMS))  # fmt: skip
            traversal.graph()
            version = costmap.version
        times.append(time.perf_counter() - began)
    return times, traversal


def rebuild(costmap: Costmap, batch: list[Scan]) -> tuple[list[float], Traversal]:
    times, traversal = [], Traversal(costmap.snapshot(), PARAMS)
    for scan in batch:
        began = time.perf_counter()
        costmap.update_from_scan(scan)
        costmap.layers_replaced()  # the old behaviour: every scan marks the master dirty
        traversal = Traversal(costmap.snapshot(), PARAMS)
        traversal.graph()
        times.append(time.perf_counter() - began)
    return times, traversal


def line(name: str, times: list[float]) -> str:
    ordered = sorted(times)
    p90 = ordered[int(0.9 * (len(ordered) - 1))]
    return f"| {name} | {statistics.median(times) * 1e3:.2f} | {p90 * 1e3:.2f} |"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--scans", type=int, default=200)
    args = parser.parse_args(argv)
    batch = scans(args.scans)
    fast, fast_end = incremental(world(), batch)
    slow, slow_end = rebuild(world(), batch)
    if fast_end.weights != slow_end.weights:
        raise SystemExit("incremental and rebuilt traversals differ")
    same, _ = incremental(world(), [batch[0]] * args.scans)
    print("| per scan | ms median | ms p90 |\n|---|---|---|")
    print(line("full rebuild (before)", slow))
    print(line("incremental (after)", fast))
    print(line("incremental, scan changes nothing", same[1:]))
    ratio = statistics.median(slow) / statistics.median(fast)
    print(f"\nrebuild / incremental (median): {ratio:.1f}x; traversals equal")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
