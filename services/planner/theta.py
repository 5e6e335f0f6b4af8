"""ThetaStar: a lazy Theta* any-angle planner on a :class:`Traversal`.

A node inherits its parent's parent when the straight segment between them is
clear (line of sight on the costmap), so paths are chains of straight legs.
The check is lazy: made once when a node is expanded, not for every neighbour.
A leg costs its length times the mean weight of the cells it crosses, so legs
still prefer low-cost space. Not optimal; any-angle and short.
"""

from __future__ import annotations

import heapq
import math

from .astar import NO_PATH
from .errors import PlanningError
from .traversal import CHECK_EVERY, SQRT2, Budget, Traversal, trace_back

MOVES = ((0, 1, 1.0), (0, -1, 1.0), (1, 0, 1.0), (-1, 0, 1.0),
         (1, 1, SQRT2), (1, -1, SQRT2), (-1, 1, SQRT2), (-1, -1, SQRT2))  # fmt: skip


def line_cost(weights: list[float], stride: int, a: int, b: int) -> float:
    """Cost of the straight leg a -> b (inf if any cell on it is blocked): an integer
    Bresenham walk over flat indices, the mean weight of the cells times the length."""
    ar, ac = divmod(a, stride)
    br, bc = divmod(b, stride)
    dr, dc = br - ar, bc - ac
    row_step = stride if dr > 0 else -stride
    col_step = 1 if dc > 0 else -1
    if abs(dc) >= abs(dr):
        major, minor, major_step, minor_step = abs(dc), abs(dr), col_step, row_step
    else:
        major, minor, major_step, minor_step = abs(dr), abs(dc), row_step, col_step
    if major == 0:
        return 0.0
    error, index, total, inf = major // 2, a, 0.0, math.inf
    for _ in range(major):
        index += major_step
        error -= minor
        if error < 0:
            index += minor_step
            error += major
        w = weights[index]
        if w == inf:
            return inf
        total += w
    return total / major * math.hypot(dr, dc)


def theta_star(
    traversal: Traversal, start: int, goal: int, budget: Budget | None = None
) -> list[int]:
    """Vertices of an any-angle path from ``start`` to ``goal``; raises PlanningError."""
    budget = budget or Budget()
    weights, s = traversal.weights, traversal.stride
    h = traversal.heuristic(goal)
    n = len(weights)
    cost = [math.inf] * n
    parents = [-1] * n
    closed = bytearray(n)
    cost[start], parents[start] = 0.0, start
    heap: list[tuple[float, int]] = [(h[start], start)]
    steps = tuple((dr * s + dc, step) for dr, dc, step in MOVES)
    countdown = CHECK_EVERY
    while heap:
        node = heapq.heappop(heap)[1]
        if closed[node]:
            continue
        _settle(node, weights, s, cost, parents, closed, steps)
        if node == goal:
            return trace_back(parents, goal)
        closed[node] = 1
        countdown -= 1
        if not countdown:
            budget.check()
            countdown = CHECK_EVERY
        grand = parents[node]
        gr, gc = divmod(grand, s)
        nr, nc = divmod(node, s)
        reach = math.hypot(nr - gr, nc - gc)
        here = cost[node]
        for dr, dc, step in MOVES:
            nxt = node + dr * s + dc
            w = weights[nxt]
            if w == math.inf or closed[nxt]:
                continue
            # optimistic: the leg from ``grand`` extended to ``nxt``; checked on expansion
            via_grand = here + (math.hypot(nr + dr - gr, nc + dc - gc) - reach) * w
            via_node = here + step * w
            c = via_grand if via_grand < via_node else via_node
            if c < cost[nxt]:
                cost[nxt] = c
                parents[nxt] = grand if via_grand < via_node else node
                heapq.heappush(heap, (c + h[nxt], nxt))
    raise PlanningError("NO_VALID_PATH", NO_PATH)


def _settle(
    node: int,
    weights: list[float],
    stride: int,
    cost: list[float],
    parents: list[int],
    closed: bytearray,
    steps: tuple[tuple[int, float], ...],
) -> None:
    """Lazy Theta*'s SetVertex: verify the leg from the parent, else take the best
    expanded neighbour as parent."""
    parent = parents[node]
    if parent == node:
        return
    leg = line_cost(weights, stride, parent, node)
    if leg < math.inf:
        cost[node] = cost[parent] + leg
        return
    best, best_parent = math.inf, parent
    for offset, step in steps:
        other = node - offset
        if closed[other]:
            candidate = cost[other] + step * weights[node]
            if candidate < best:
                best, best_parent = candidate, other
    cost[node], parents[node] = best, best_parent
