"""GridBased's default search: scipy's compiled Dijkstra on a :class:`Traversal`'s graph.

The metric is the A*'s (``astar.py``): a step into a cell costs ``step_length *
weight(cell)``, so both return a cheapest 8-connected path (equal cost; ties
may be broken differently). Like Nav2 NavFn's default (``use_astar: false``)
the search expands the whole reachable grid: its time hardly depends on how
far the goal is (a ``limit`` cut-off bought nothing on the default world's
pairs; see bench/RESULTS.md), which makes it predictable.

A goal the graph holds passable is searched from: a Dijkstra on the reversed
graph rooted at the goal, kept with the traversal (``Traversal.reach_to``), so
the next request to the same goal on unchanged weights (a navigator replanning
every second while the robot moves) only walks the kept tree from its start.
A goal only this traversal opened is searched to from the start, as before.

A compiled call cannot be interrupted (and holds the GIL): the budget is
checked before and after it, so one search overruns its budget or a cancel by
at most its own duration (~6 ms on the default world's 200 x 200 blocks,
~30 ms at its full 400 x 400 resolution, on this machine).
"""

from __future__ import annotations

import math

from .astar import NO_PATH
from .errors import PlanningError
from .sparse import MOVES, GridGraph, Reach
from .traversal import Budget, Traversal


def compiled_dijkstra(
    traversal: Traversal, start: int, goal: int, budget: Budget | None = None
) -> list[int]:
    """Flat indices from ``start`` to ``goal`` (both included); raises PlanningError."""
    budget = budget or Budget()
    budget.check()
    if start == goal:
        return [start]
    graph = traversal.graph()
    budget.check()
    budget.searched += 1
    if graph.passable[goal]:
        rooted, kept = traversal.reach_to(goal)
        budget.reused += kept
        budget.check()
        if graph.passable[start]:
            if math.isinf(rooted.cost[start]):
                raise PlanningError("NO_VALID_PATH", NO_PATH)
            return rooted.path_from(start, goal)
        return _out_of_opened(traversal, rooted, start, goal)
    reach = graph.reach_from(start)
    budget.check()
    return _into_opened(graph, reach, start, goal, traversal.weights[goal])


def _out_of_opened(traversal: Traversal, rooted: Reach, start: int, goal: int) -> list[int]:
    """The cheapest path out of a start the graph has blocked (this traversal opened
    it), on the goal-rooted ``rooted``: the step into the best neighbour, then its path."""
    best, exit_to = math.inf, -1
    for dr, dc, length in MOVES:
        neighbour = start + dr * traversal.stride + dc
        cost = length * traversal.weights[neighbour] + float(rooted.cost[neighbour])
        if cost < best:
            best, exit_to = cost, neighbour
    if exit_to < 0:
        raise PlanningError("NO_VALID_PATH", NO_PATH)
    return [start, *rooted.path_from(exit_to, goal)]


def _into_opened(graph: GridGraph, reach: Reach, start: int, goal: int, weight: float) -> list[int]:
    """The cheapest path into a goal the graph has blocked but this traversal opened
    (``weight`` finite): the best reached neighbour plus the step into the goal."""
    best, entry = math.inf, -1
    if math.isfinite(weight):
        for dr, dc, length in MOVES:
            neighbour = goal - (dr * graph.stride + dc)
            cost = float(reach.cost[neighbour]) + length * weight
            if cost < best:
                best, entry = cost, neighbour
    if entry < 0:
        raise PlanningError("NO_VALID_PATH", NO_PATH)
    return [*reach.path_to(start, entry), goal]
