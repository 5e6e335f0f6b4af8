"""A plain-Python Dijkstra on the same graph as GridBased: the baseline for tests and bench.

Deliberately straightforward (2-D lists, tuple cells, no heuristic), as one
would first write it.
"""

from __future__ import annotations

import heapq
import itertools
import math

import numpy as np

from aiobt.costmap import CostGrid

from .traversal import SearchParams, Traversal

MOVES = [(1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1)]


def step_weights(grid: CostGrid, params: SearchParams | None = None) -> list[list[float]]:
    """weights[row][col] as GridBased sees them (inf = blocked), without padding."""
    traversal = Traversal(grid, params or SearchParams())
    padded = np.asarray(traversal.weights).reshape(-1, traversal.stride)
    rows: list[list[float]] = padded[1:-1, 1:-1].tolist()
    return rows


def dijkstra(
    weights: list[list[float]], start: tuple[int, int], goal: tuple[int, int]
) -> tuple[float, list[tuple[int, int]]]:
    """Cost and cells (col, row) of the cheapest 8-connected path; (inf, []) if none."""
    height, width = len(weights), len(weights[0])
    best: dict[tuple[int, int], float] = {start: 0.0}
    parent: dict[tuple[int, int], tuple[int, int]] = {}
    heap = [(0.0, start)]
    done: set[tuple[int, int]] = set()
    while heap:
        cost, cell = heapq.heappop(heap)
        if cell in done:
            continue
        if cell == goal:
            path = [cell]
            while path[-1] in parent:
                path.append(parent[path[-1]])
            return cost, path[::-1]
        done.add(cell)
        for dc, dr in MOVES:
            col, row = cell[0] + dc, cell[1] + dr
            if not (0 <= col < width and 0 <= row < height):
                continue
            step = math.sqrt(2.0) if dc and dr else 1.0
            new = cost + step * weights[row][col]
            if new < best.get((col, row), math.inf):
                best[(col, row)] = new
                parent[(col, row)] = cell
                heapq.heappush(heap, (new, (col, row)))
    return math.inf, []


def path_cost(weights: list[list[float]], cells: list[tuple[int, int]]) -> float:
    """The GridBased metric of a cell path (entering each cell costs step * weight)."""
    total = 0.0
    for (c0, r0), (c1, r1) in itertools.pairwise(cells):
        step = math.sqrt(2.0) if c0 != c1 and r0 != r1 else 1.0
        total += step * weights[r1][c1]
    return total
