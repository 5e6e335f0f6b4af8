"""Where one ComputePathToPose's CPU goes, part by part, on the office world (issue 17).

Run: ``.venv/bin/python -m bench.planner.plan_parts [--pairs 40] [--repeats 3]``

A component figure (one process, CPU time of this thread, no Zenoh): for start/goal
pairs of the office world (downsample 2, as the service), the parts a planner round
trip pays besides the transport:

- ``search, whole grid``: GridBased's compiled Dijkstra from the start (the
  service's search before it kept goal-rooted ones);
- ``search, goal-rooted``: the same on the reversed graph, rooted at the goal (what
  the service runs on a miss: no kept search for this goal on these weights), its
  cost to the start checked equal; ``plan on a kept search``: the whole ``plan()``
  call when the goal's search is kept (a hit: the walk from the start and the poses);
- ``search, A* bounded``: an A* tried as a goal-directed replacement, run as the same
  compiled Dijkstra on weights reduced by the octile heuristic with a bound on the
  excess over the straight-line cost (0.4 x it + 8 cells, x4 while the goal is not
  reached, at last unbounded); and the same with the bound known in advance (the
  optimum's excess + 10 %: the best any bounding could do). Costs are checked equal
  to the whole-grid search's;
- ``path to message``: the planned poses as the Result's ``Path`` (``to_path``);
- ``result encode`` / ``decode``: the Result to JSON (server) and back (client).

The per-scan fold and traversal update: ``python -m bench.system.costmap_update``.
Pairs: half the farthest-apart pairs (``plan_time``), half random passable pairs.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
from collections.abc import Callable
from functools import partial
from typing import TypeVar

import numpy as np
from scipy.sparse import csr_array
from scipy.sparse.csgraph import dijkstra

from aiobt.msgs import ComputePathToPose, decode
from aiobt_services.planner.actions import to_path
from aiobt_services.planner.planning import plan
from aiobt_services.planner.sparse import MOVES, GridGraph
from aiobt_services.planner.traversal import SQRT2, SearchParams, Traversal

from .plan_time import far_pairs, office, world_pose

Pair = tuple[int, int]
T = TypeVar("T")


def octile(graph: GridGraph, goal: int, shape: tuple[int, int]) -> np.ndarray:
    """The octile distance to ``goal`` of every padded cell, as a padded 2-D array."""
    grow, gcol = divmod(goal, graph.stride)
    dy = np.abs(np.arange(shape[0]) - grow)[:, None].astype(np.float64)
    dx = np.abs(np.arange(shape[1]) - gcol)[None, :].astype(np.float64)
    h: np.ndarray = dx + dy + (SQRT2 - 2.0) * np.minimum(dx, dy)
    return h


def bounded_astar(graph: GridGraph, start: int, goal: int, excess: float) -> float:
    """A* as a compiled Dijkstra on reduced weights, settling nothing beyond ``excess``
    (reduced cost); the goal's true cost, ``inf`` if not reached within it."""
    weights = graph._weights
    rows, cols = weights.shape[:2]
    h = octile(graph, goal, (rows + 2, cols + 2))
    reduced = weights - h[1:-1, 1:-1, None]
    for k, (dr, dc, _) in enumerate(MOVES):
        reduced[:, :, k] += h[1 + dr : rows + 1 + dr, 1 + dc : cols + 1 + dc]
    np.maximum(reduced, 0.0, out=reduced)  # rounding below 0 (the heuristic is consistent)
    m = graph._matrix
    matrix = csr_array((reduced.ravel(), m.indices, m.indptr), shape=m.shape)
    cost = dijkstra(matrix, directed=True, indices=start, limit=excess)
    return float(cost[goal]) + float(h.flat[start])


def growing(graph: GridGraph, start: int, goal: int) -> float:
    excess = 0.4 * _octile_between(graph, start, goal) + 8.0
    for attempt in range(4):
        cost = bounded_astar(graph, start, goal, excess if attempt < 3 else math.inf)
        if math.isfinite(cost):
            return cost
        excess *= 4.0
    return math.inf


def _octile_between(graph: GridGraph, a: int, b: int) -> float:
    (ar, ac), (br, bc) = divmod(a, graph.stride), divmod(b, graph.stride)
    dx, dy = abs(ac - bc), abs(ar - br)
    return dx + dy + (SQRT2 - 2.0) * min(dx, dy)


def cpu(work: Callable[[], T], repeats: int) -> tuple[float, T]:
    """Median thread CPU seconds of ``work`` over ``repeats`` calls, and its last result."""
    times = []
    for _ in range(repeats):
        began = time.thread_time()
        out = work()
        times.append(time.thread_time() - began)
    return statistics.median(times), out


def pairs_of(traversal: Traversal, count: int, rng: np.random.Generator) -> list[Pair]:
    grid = traversal.fine
    far = [
        (traversal.locate(*world_pose(grid, a)[:2], "start"),
         traversal.locate(*world_pose(grid, b)[:2], "goal"))
        for a, b in far_pairs(grid, count // 2, rng)
    ]  # fmt: skip
    graph = traversal.graph()
    reach = graph.reach_from(far[0][0])
    cells = np.flatnonzero(np.isfinite(reach.cost))  # passable and connected
    picks = rng.choice(cells, size=(count - len(far), 2))
    return far + [(int(a), int(b)) for a, b in picks]


def measure(count: int, repeats: int, seed: int) -> dict[str, list[float]]:
    traversal = Traversal(office(), SearchParams(downsample=2))
    graph = traversal.graph()
    parts: dict[str, list[float]] = {}
    for start, goal in pairs_of(traversal, count, np.random.default_rng(seed)):
        whole, reach = cpu(partial(graph.reach_from, start), repeats)
        best = float(reach.cost[goal])
        rooted, to_goal = cpu(partial(graph.reach_to, goal), repeats)
        assert math.isclose(float(to_goal.cost[start]), best, rel_tol=1e-9)
        grown, cost = cpu(partial(growing, graph, start, goal), repeats)
        bound = 1.1 * (best - _octile_between(graph, start, goal)) + 1e-6
        known, known_cost = cpu(partial(bounded_astar, graph, start, goal, bound), repeats)
        for got in (cost, known_cost):
            assert math.isclose(got, best, rel_tol=1e-9), (got, best)
        ends = [(*traversal.to_world([i])[0], 0.0) for i in (start, goal)]
        poses = plan(traversal, ends[0], ends[1])  # keeps the goal's search
        kept, _ = cpu(partial(plan, traversal, ends[0], ends[1]), repeats)
        build, path = cpu(partial(to_path, poses, 1.0), repeats)
        result = ComputePathToPose.Result(path=path, planning_time=0.01)
        encode, payload = cpu(result.to_json, repeats)
        back, _ = cpu(partial(decode, ComputePathToPose.Result, payload), repeats)
        for name, seconds in (
            ("search, whole grid from the start (before)", whole),
            ("search, goal-rooted on the reversed graph (a miss)", rooted),
            ("plan() on a kept goal-rooted search (a hit)", kept),
            ("search, A* bounded, growing bound", grown),
            ("search, A* bounded, bound known (best case)", known),
            ("path to message (to_path)", build),
            ("result encode (to_json)", encode),
            ("result decode (client)", back),
        ):
            parts.setdefault(name, []).append(seconds)
        parts.setdefault("path poses", []).append(len(poses))
    return parts


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--pairs", type=int, default=40)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--seed", type=int, default=3)
    args = parser.parse_args(argv)
    parts = measure(args.pairs, args.repeats, args.seed)
    print("| part (CPU ms per plan, this thread) | median | p90 | max |")
    print("|---|---|---|---|")
    for name, values in parts.items():
        scale = 1.0 if name == "path poses" else 1e3
        q50, q90 = np.percentile(np.asarray(values) * scale, [50, 90])
        print(f"| {name} | {q50:.2f} | {q90:.2f} | {max(values) * scale:.2f} |")
    with open("/proc/loadavg") as f:
        print(f"\nload average: {' '.join(f.read().split()[:3])}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
