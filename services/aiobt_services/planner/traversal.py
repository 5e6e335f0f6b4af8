"""A cost grid prepared for search: padded flat arrays of step weights.

Flat indices address a grid padded by one blocked cell on every side, so the
search never bounds-checks: cell (col, row) is ``(row + 1) * stride + col + 1``.
With ``downsample`` > 1 the search runs on blocks of that many cells a side,
each as costly as its worst cell (Nav2's costmap downsampler).
"""

from __future__ import annotations

import copy
import math
import threading
import time
from collections import OrderedDict
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from aiobt.costmap import INSCRIBED, NO_INFORMATION, CostGrid, GridGeometry, Window

from .errors import PlanningCancelled, PlanningError
from .sparse import GridGraph, Reach

SQRT2 = math.sqrt(2.0)
CHECK_EVERY = 1024
KEPT_GOALS = 8  # goal-rooted searches kept per traversal (least recently used dropped)


@dataclass(frozen=True, slots=True)
class SearchParams:
    """Smac-2D-like knobs: a cell of cost ``c`` weighs ``1 + cost_penalty * c / 252``."""

    cost_penalty: float = 2.0
    allow_unknown: bool = True
    downsample: int = 1
    use_astar: bool = False  # GridBased: the CPython A* instead of the compiled Dijkstra

    def __post_init__(self) -> None:
        if not (math.isfinite(self.cost_penalty) and self.cost_penalty >= 0.0):
            raise ValueError(f"cost_penalty must be finite and >= 0, got {self.cost_penalty!r}")
        if self.downsample < 1:
            raise ValueError(f"downsample must be >= 1, got {self.downsample!r}")


@dataclass(slots=True)
class Budget:
    """Cancellation flag and a compute-time deadline (wall time: it bounds CPU work)."""

    max_seconds: float = math.inf
    cancel: threading.Event = field(default_factory=threading.Event)
    started: float = field(default_factory=time.monotonic)
    reused: int = 0  # searches served by a kept goal-rooted search (set by the search)
    searched: int = 0  # searches run

    def check(self) -> None:
        if self.cancel.is_set():
            raise PlanningCancelled
        if time.monotonic() - self.started > self.max_seconds:
            raise PlanningError(
                "TIMEOUT", f"planning exceeded its time budget of {self.max_seconds:.3f} s"
            )


def downsample_costs(costs: npt.NDArray[np.uint8], factor: int) -> npt.NDArray[np.uint8]:
    """Block maximum (unknown counts as unknown only where the block is all unknown)."""
    if factor == 1:
        return costs
    height, width = costs.shape
    rows, cols = -(-height // factor), -(-width // factor)
    padded = np.full((rows * factor, cols * factor), NO_INFORMATION, dtype=np.uint8)
    padded[:height, :width] = costs
    blocks = padded.reshape(rows, factor, cols, factor).swapaxes(1, 2).reshape(rows, cols, -1)
    known = np.where(blocks == NO_INFORMATION, 0, blocks).max(axis=2)
    all_unknown = (blocks == NO_INFORMATION).all(axis=2)
    result: npt.NDArray[np.uint8] = np.where(all_unknown, NO_INFORMATION, known).astype(np.uint8)
    return result


class _GraphCache:
    """The compiled graph of a traversal's weights, built on first use, and the last
    goal-rooted searches on it, shared by its opened copies (they describe the
    weights before any block was opened)."""

    __slots__ = ("graph", "lock", "reaches")

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.graph: GridGraph | None = None
        self.reaches: OrderedDict[int, Reach] = OrderedDict()


class Traversal:
    """Step weights of a :class:`CostGrid` (``inf`` = impassable), padded and flat."""

    __slots__ = ("_base", "_coords", "_graph", "costs", "fine", "geometry", "params", "passable",
                 "stride", "weights")  # fmt: skip

    def __init__(self, grid: CostGrid, params: SearchParams | None = None) -> None:
        self.params = params or SearchParams()
        self.fine = grid
        factor = self.params.downsample
        g = grid.geometry
        self.costs = downsample_costs(grid.costs, factor)
        self.geometry = GridGeometry(
            self.costs.shape[1], self.costs.shape[0], g.resolution * factor, g.origin_x, g.origin_y
        )
        self.passable = self._passable(self.costs)
        padded = np.full((self.costs.shape[0] + 2, self.costs.shape[1] + 2), math.inf)
        padded[1:-1, 1:-1] = self._step_weights(self.costs, self.passable)
        self.stride = int(padded.shape[1])
        self.weights: list[float] = padded.ravel().tolist()
        padded.flags.writeable = False
        self._base: npt.NDArray[np.float64] = padded
        self._graph = _GraphCache()
        self._coords: tuple[npt.NDArray[np.intp], npt.NDArray[np.intp]] | None = None

    def _step_weights(
        self, costs: npt.NDArray[np.uint8], passable: npt.NDArray[np.bool_]
    ) -> npt.NDArray[np.float64]:
        weight = 1.0 + self.params.cost_penalty * np.minimum(costs, 252) / 252.0
        stepped: npt.NDArray[np.float64] = np.where(passable, weight, math.inf)
        return stepped

    def updated(self, grid: CostGrid, window: Window) -> Traversal:
        """The traversal of ``grid``, which differs from :attr:`fine` only inside the
        fine-cell ``window``: the blocks it touches are recomputed, the rest (and
        a built graph's layout) kept; this traversal is left as it was."""
        if grid.costs.shape != self.fine.costs.shape:
            raise ValueError(f"grid shape {grid.costs.shape} != {self.fine.costs.shape}")
        f = self.params.downsample
        row0, row1, col0, col1 = (
            window[0] // f,
            -(-window[1] // f),
            window[2] // f,
            -(-window[3] // f),
        )
        block = downsample_costs(grid.costs[row0 * f : row1 * f, col0 * f : col1 * f], f)
        clone = copy.copy(self)
        clone.fine = grid
        clone.costs = self.costs.copy()
        clone.costs[row0:row1, col0:col1] = block
        clone.passable = self.passable.copy()
        clone.passable[row0:row1, col0:col1] = self._passable(block)
        padded = self._base.copy()
        padded[row0 + 1 : row1 + 1, col0 + 1 : col1 + 1] = self._step_weights(
            block, clone.passable[row0:row1, col0:col1]
        )
        padded.flags.writeable = False
        clone._base = padded
        clone.weights = list(self.weights)
        for row in range(row0 + 1, row1 + 1):
            at = row * self.stride
            clone.weights[at + col0 + 1 : at + col1 + 1] = padded[row, col0 + 1 : col1 + 1].tolist()
        clone._graph = _GraphCache()
        with self._graph.lock:
            built = self._graph.graph
        if built is not None:
            clone._graph.graph = built.updated(padded, (row0, row1, col0, col1))
        return clone

    def graph(self) -> GridGraph:
        """The compiled search graph of these weights, built once (thread-safe).

        Blocks opened by :meth:`opened` are not in it: the compiled search
        handles an opened goal itself, and edges already leave blocked cells.
        """
        cache = self._graph
        with cache.lock:
            if cache.graph is None:
                cache.graph = GridGraph(self._base)
            return cache.graph

    def reach_to(self, goal: int) -> tuple[Reach, bool]:
        """The graph's reversed search rooted at ``goal`` (:meth:`GridGraph.reach_to`),
        and whether it was kept from an earlier call: the last :data:`KEPT_GOALS`
        goals' are kept while these weights are (an updated traversal starts afresh)."""
        cache = self._graph
        with cache.lock:
            kept = cache.reaches.get(goal)
            if kept is not None:
                cache.reaches.move_to_end(goal)
                return kept, True
        reach = self.graph().reach_to(goal)
        with cache.lock:
            cache.reaches[goal] = reach
            while len(cache.reaches) > KEPT_GOALS:
                cache.reaches.popitem(last=False)
        return reach, False

    def _passable(self, costs: npt.NDArray[np.uint8]) -> npt.NDArray[np.bool_]:
        unknown = costs == NO_INFORMATION
        passable: npt.NDArray[np.bool_] = (costs < INSCRIBED) | (
            unknown & self.params.allow_unknown
        )
        return passable

    def index(self, col: int, row: int) -> int:
        return (row + 1) * self.stride + col + 1

    def cell(self, index: int) -> tuple[int, int]:
        row, col = divmod(index, self.stride)
        return (col - 1, row - 1)

    def heuristic(self, goal: int) -> list[float]:
        """Octile distance to ``goal`` for every padded cell (admissible: weight >= 1)."""
        if self._coords is None:
            self._coords = np.divmod(np.arange(len(self.weights)), self.stride)
        rows, cols = self._coords
        grow, gcol = divmod(goal, self.stride)
        dx = np.abs(cols - gcol)
        dy = np.abs(rows - grow)
        h: list[float] = ((dx + dy) + (SQRT2 - 2.0) * np.minimum(dx, dy)).tolist()
        return h

    def locate(self, x: float, y: float, which: str) -> int:
        """Flat index of a world point, or a PlanningError naming start or goal.

        Occupancy is judged on the full-resolution grid; a downsampled block
        that is worse than its free fine cell is opened for this search.
        """
        is_start = which.lower() == "start"
        fine_cell = self.fine.geometry.world_to_cell(x, y)
        if fine_cell is None:
            reason = "START_OUTSIDE_MAP" if is_start else "GOAL_OUTSIDE_MAP"
            raise PlanningError(reason, f"{which} ({x:.3f}, {y:.3f}) is outside the costmap")
        fine_cost = self.fine.costs[fine_cell[1], fine_cell[0]]
        if not bool(self._passable(np.asarray(fine_cost))):
            reason = "START_OCCUPIED" if is_start else "GOAL_OCCUPIED"
            raise PlanningError(
                reason, f"{which} ({x:.3f}, {y:.3f}) is in an occupied cell (cost {fine_cost})"
            )
        factor = self.params.downsample
        return self.index(fine_cell[0] // factor, fine_cell[1] // factor)

    def opened(self, x: float, y: float) -> Traversal:
        """This traversal with the block holding (x, y) passable (a copy if it changes).

        After downsampling a block can be blocked while the fine cell of the
        start or goal is free; the search opens just that block, on a copy, so
        a cached traversal is never modified (it may serve several threads).
        """
        cell = self.fine.geometry.world_to_cell(x, y)
        if cell is None:
            return self
        factor = self.params.downsample
        index = self.index(cell[0] // factor, cell[1] // factor)
        if self.weights[index] != math.inf:
            return self
        clone = copy.copy(self)
        clone.weights = list(self.weights)
        fine_cost = min(int(self.fine.costs[cell[1], cell[0]]), 252)
        clone.weights[index] = 1.0 + self.params.cost_penalty * fine_cost / 252
        return clone

    def is_opened(self, index: int) -> bool:
        """True if the cell at ``index`` is passable only because :meth:`opened` opened it."""
        return bool(self._base.flat[index] == math.inf) and self.weights[index] != math.inf

    def to_world(self, indices: list[int]) -> list[tuple[float, float]]:
        return [self.geometry.cell_to_world(*self.cell(i)) for i in indices]


def trace_back(parents: list[int], goal: int) -> list[int]:
    """Follow parent links from ``goal`` to the start (whose parent is itself)."""
    path = [goal]
    while parents[path[-1]] != path[-1]:
        path.append(parents[path[-1]])
    path.reverse()
    return path
