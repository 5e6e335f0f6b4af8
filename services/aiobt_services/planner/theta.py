"""ThetaStar: a lazy Theta* any-angle planner on a :class:`Traversal`.

A node inherits its parent's parent when the straight segment between them is
clear (line of sight on the costmap: every cell the segment touches is
passable), so paths are chains of straight legs.
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
    """Cost of the straight leg between the centres of cells a and b (inf if it touches
    a blocked cell): an integer supercover walk over flat indices, so every cell the leg
    passes through is checked, and where it passes exactly through a corner both cells
    beside that corner are too. The mean weight of the cells entered times the length."""
    ar, ac = divmod(a, stride)
    br, bc = divmod(b, stride)
    dr, dc = br - ar, bc - ac
    nx, ny = abs(dc), abs(dr)
    if nx + ny == 0:
        return 0.0
    col_step = 1 if dc > 0 else -1
    row_step = stride if dr > 0 else -stride
    ix = iy = 0
    index, total, entered, inf = a, 0.0, 0, math.inf
    while ix < nx or iy < ny:
        decision = (1 + 2 * ix) * ny - (1 + 2 * iy) * nx
        if decision == 0:  # through a corner: both cells beside it must be free too
            if weights[index + col_step] == inf or weights[index + row_step] == inf:
                return inf
            index += col_step + row_step
            ix += 1
            iy += 1
        elif decision < 0:
            index += col_step
            ix += 1
        else:
            index += row_step
            iy += 1
        w = weights[index]
        if w == inf:
            return inf
        total += w
        entered += 1
    return total / entered * math.hypot(dr, dc)


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
    # a start or goal block opened for this search (refused fine cells inside) is left
    # or entered by a grid step only, never by a long leg through it
    sealed = {c for c in (start, goal) if traversal.is_opened(c)}
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
            if sealed and (grand in sealed or nxt in sealed):
                via_grand = math.inf
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
