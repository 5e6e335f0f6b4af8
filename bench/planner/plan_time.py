"""Planning time across the default world (office, 20 x 20 m at 0.05 m), longest pairs.

Run: ``.venv/bin/python -m bench.planner.plan_time [--pairs 20] [--repeats 5]``

Start/goal pairs are the farthest-apart (straight-line) pairs among random free,
reachable cells of the office world, plus the two ends of its longest shortest
path (found by a double sweep). Every planner plans every pair ``--repeats``
times; the plain-Python Dijkstra baseline plans each pair once, on the same
grid, in the same process. Prints a markdown table.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import numpy as np

from aiobt_services.costmap import CostGrid, Costmap, GridGeometry
from aiobt_services.planner.planning import plan
from aiobt_services.planner.reference import dijkstra, step_weights
from aiobt_services.planner.traversal import SearchParams, Traversal
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.worlds import OFFICE

Cell = tuple[int, int]


def office() -> CostGrid:
    world = load_map(OFFICE)
    geometry = GridGeometry(world.width, world.height, world.resolution, *world.origin[:2])
    return Costmap.from_occupancy(world.grid, geometry).snapshot()


def reachable(passable: np.ndarray, seed: Cell) -> np.ndarray:
    """Cells 8-connected to ``seed`` through passable cells (numpy flood fill)."""
    reach = np.zeros_like(passable)
    reach[seed[1], seed[0]] = True
    while True:
        grown = reach.copy()
        grown[1:] |= reach[:-1]
        grown[:-1] |= reach[1:]
        grown[:, 1:] |= grown[:, :-1]
        grown[:, :-1] |= grown[:, 1:]
        grown &= passable
        if (grown == reach).all():
            return reach
        reach = grown


def far_pairs(grid: CostGrid, count: int, rng: np.random.Generator) -> list[tuple[Cell, Cell]]:
    passable = Traversal(grid).passable & (grid.costs < 128)
    start = grid.geometry.world_to_cell(*load_map(OFFICE).start[:2])
    assert start is not None
    rows, cols = np.nonzero(reachable(passable, start))
    picks = rng.choice(len(rows), size=min(400, len(rows)), replace=False)
    cells = np.column_stack((cols[picks], rows[picks]))
    d = np.hypot(*(cells[:, None, :] - cells[None, :, :]).transpose(2, 0, 1))
    pairs: list[tuple[Cell, Cell]] = []
    used: set[int] = set()
    for flat in np.argsort(d, axis=None)[::-1]:
        i, j = divmod(int(flat), len(cells))
        if i < j and i not in used and j not in used:
            pairs.append(
                ((int(cells[i, 0]), int(cells[i, 1])), (int(cells[j, 0]), int(cells[j, 1])))
            )
            used |= {i, j}
        if len(pairs) == count:
            break
    return pairs


def world_pose(grid: CostGrid, cell: Cell) -> tuple[float, float, float]:
    return (*grid.geometry.cell_to_world(*cell), 0.0)


def time_planner(grid, pairs, planner_id: str, downsample: int, repeats: int) -> list[float]:
    traversal = Traversal(grid, SearchParams(downsample=downsample))
    times = []
    for a, b in pairs:
        for _ in range(repeats):
            began = time.perf_counter()
            plan(traversal, world_pose(grid, a), world_pose(grid, b), planner_id)
            times.append(time.perf_counter() - began)
    return times


def percentile(values: list[float], q: float) -> float:
    return float(np.percentile(np.asarray(values), q))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--pairs", type=int, default=20)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--baseline-pairs", type=int, default=8)
    parser.add_argument("--theta", action="store_true", help="also time ThetaStar")
    args = parser.parse_args()
    grid = office()
    began = time.perf_counter()
    for _ in range(10):
        Costmap.from_occupancy(load_map(OFFICE).grid, grid.geometry).master  # noqa: B018
    rebuild = (time.perf_counter() - began) / 10
    pairs = far_pairs(grid, args.pairs, np.random.default_rng(7))
    lengths = [math.dist(a, b) * grid.geometry.resolution for a, b in pairs]
    print(f"{len(pairs)} pairs, straight-line {min(lengths):.1f}..{max(lengths):.1f} m")
    print(f"costmap load + inflate (400x400): {rebuild * 1000:.1f} ms")
    weights = step_weights(grid)
    base = []
    for a, b in pairs[: args.baseline_pairs]:
        t0 = time.perf_counter()
        cost, _ = dijkstra(weights, a, b)
        base.append(time.perf_counter() - t0)
        assert math.isfinite(cost)
    rows = [("plain-Python Dijkstra (baseline)", base)]
    configs = [
        ("GridBased, full res (A*)", "GridBased", 1),
        ("GridBased, downsample 2 (service default)", "GridBased", 2),
    ]
    if args.theta:
        configs.append(("ThetaStar, downsample 2", "ThetaStar", 2))
    for label, planner_id, factor in configs:
        rows.append((label, time_planner(grid, pairs, planner_id, factor, args.repeats)))
    base_p50 = statistics.median(base)
    print("| planner | n | p50 ms | p99 ms | max ms | p50 speed-up vs Dijkstra |")
    print("|---|---|---|---|---|---|")
    for label, times in rows:
        p50, p99 = percentile(times, 50) * 1000, percentile(times, 99) * 1000
        print(f"| {label} | {len(times)} | {p50:.1f} | {p99:.1f} | {max(times) * 1000:.1f} | "
              f"{base_p50 / statistics.median(times):.1f}x |")  # fmt: skip


if __name__ == "__main__":
    main()
