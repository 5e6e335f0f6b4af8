"""Planning time across the default world (office, 20 x 20 m at 0.05 m), longest pairs.

Run: ``.venv/bin/python -m bench.planner.plan_time [--pairs 20] [--repeats 5] [--theta]``

Start/goal pairs are the farthest-apart (straight-line) pairs among random free,
reachable cells of the office world. Every planner configuration plans every
pair ``--repeats`` times on a traversal built beforehand (the service caches it
per costmap version); one row also rebuilds the traversal and its compiled graph
before every plan (a costmap that changed since the last plan, e.g. a new scan).
The plain-Python Dijkstra baseline plans the first ``--baseline-pairs`` pairs
once, on the same full-resolution grid and metric, in the same process.
Prints what a costmap change costs, then a markdown table.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import numpy as np

from aiobt.costmap import CostGrid, Costmap, GridGeometry
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


def time_planner(grid, pairs, planner_id: str, params: SearchParams, repeats: int) -> list[float]:
    traversal = Traversal(grid, params)
    traversal.graph()  # built once per costmap version in the service
    times = []
    for a, b in pairs:
        for _ in range(repeats):
            began = time.perf_counter()
            plan(traversal, world_pose(grid, a), world_pose(grid, b), planner_id)
            times.append(time.perf_counter() - began)
    return times


def time_with_rebuild(grid, pairs, params: SearchParams, repeats: int) -> list[float]:
    """GridBased as the first plan after a costmap change: traversal and graph included."""
    times = []
    for a, b in pairs:
        for _ in range(repeats):
            began = time.perf_counter()
            plan(Traversal(grid, params), world_pose(grid, a), world_pose(grid, b))
            times.append(time.perf_counter() - began)
    return times


def change_costs(grid: CostGrid) -> None:
    """Print what one costmap change costs: master grid, traversal, compiled graph."""
    occupancy = load_map(OFFICE).grid
    began = time.perf_counter()
    for _ in range(10):
        Costmap.from_occupancy(occupancy, grid.geometry).master  # noqa: B018
    rebuild = (time.perf_counter() - began) / 10
    print(f"costmap load + inflate (400x400): {rebuild * 1000:.1f} ms")
    for factor in (2, 1):
        build, graph = [], []
        for _ in range(5):
            t0 = time.perf_counter()
            traversal = Traversal(grid, SearchParams(downsample=factor))
            t1 = time.perf_counter()
            traversal.graph()
            build.append(t1 - t0)
            graph.append(time.perf_counter() - t1)
        print(
            f"downsample {factor}: traversal {statistics.median(build) * 1000:.1f} ms, "
            f"compiled graph {statistics.median(graph) * 1000:.1f} ms "
            f"({traversal.graph().edges} edges)"
        )


def percentile(values: list[float], q: float) -> float:
    return float(np.percentile(np.asarray(values), q))


def baseline(grid: CostGrid, pairs: list[tuple[Cell, Cell]]) -> list[float]:
    weights = step_weights(grid)
    times = []
    for a, b in pairs:
        began = time.perf_counter()
        cost, _ = dijkstra(weights, a, b)
        times.append(time.perf_counter() - began)
        assert math.isfinite(cost)
    return times


CONFIGS = [
    ("GridBased, downsample 2 (service default: compiled Dijkstra)", "GridBased", 2, False),
    ("GridBased, full res (compiled Dijkstra)", "GridBased", 1, False),
    ("GridBased --use-astar, downsample 2 (CPython A*)", "GridBased", 2, True),
    ("GridBased --use-astar, full res (CPython A*)", "GridBased", 1, True),
]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--pairs", type=int, default=20)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--baseline-pairs", type=int, default=8)
    parser.add_argument("--theta", action="store_true", help="also time ThetaStar")
    args = parser.parse_args()
    with open("/proc/loadavg") as loadavg:
        print(f"load average at start: {loadavg.read().split()[:3]}")
    grid = office()
    pairs = far_pairs(grid, args.pairs, np.random.default_rng(7))
    lengths = [math.dist(a, b) * grid.geometry.resolution for a, b in pairs]
    print(f"{len(pairs)} pairs, straight-line {min(lengths):.1f}..{max(lengths):.1f} m")
    change_costs(grid)
    rows = [
        ("plain-Python Dijkstra (baseline, full res)", baseline(grid, pairs[: args.baseline_pairs]))
    ]
    for label, planner_id, factor, use_astar in CONFIGS:
        params = SearchParams(downsample=factor, use_astar=use_astar)
        rows.append((label, time_planner(grid, pairs, planner_id, params, args.repeats)))
    rows.append(
        (
            "GridBased, downsample 2, rebuilding traversal + graph per plan",
            time_with_rebuild(grid, pairs, SearchParams(downsample=2), args.repeats),
        )
    )
    if args.theta:
        params = SearchParams(downsample=2)
        rows.append(
            (
                "ThetaStar, downsample 2",
                time_planner(grid, pairs, "ThetaStar", params, args.repeats),
            )
        )
    table(rows)
    with open("/proc/loadavg") as loadavg:
        print(f"load average at end: {loadavg.read().split()[:3]}")


def table(rows: list[tuple[str, list[float]]]) -> None:
    base_p50 = statistics.median(rows[0][1])
    print("| planner | n | p50 ms | p99 ms | max ms | p50 speed-up vs Dijkstra |")
    print("|---|---|---|---|---|---|")
    for label, times in rows:
        p50, p99 = percentile(times, 50) * 1000, percentile(times, 99) * 1000
        print(f"| {label} | {len(times)} | {p50:.1f} | {p99:.1f} | {max(times) * 1000:.1f} | "
              f"{base_p50 / statistics.median(times):.1f}x |")  # fmt: skip


if __name__ == "__main__":
    main()
