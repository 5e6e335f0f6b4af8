"""The 8-connected grid as a compiled graph: the planner's only door to scipy.

scipy ships no type stubs, so this narrow wrapper is the one module that
imports it (``[[tool.mypy.overrides]]`` for ``scipy.*``) and hands typed numpy
arrays in and out.

Nodes are a :class:`Traversal`'s padded flat indices. An edge ``u -> v`` exists
for every interior cell ``u`` and each of its 8 neighbours ``v``, weighted
``step_length * weight(v)`` (the GridBased metric: entering a cell costs its
weight; ``inf`` into a blocked cell, never taken). Edges leave blocked cells
too, so a search may start in a block opened for the start without rebuilding
the graph, and a changed cell only rewrites the weights of the edges into it.

The reversed graph (every edge between passable cells turned round: ``v -> u``
weighs ``step_length * weight(v)``, its source's own weight) has the same layout;
a Dijkstra on it rooted at a goal gives the cheapest cost and next step from
every passable node to that goal, so one search serves any start while the
weights stay as they are (a start in a blocked block steps to its best neighbour).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from scipy.sparse import csr_array
from scipy.sparse.csgraph import dijkstra

FloatArray = npt.NDArray[np.float64]
IndexArray = npt.NDArray[np.int32]

# (row step, col step, length) of the 8 moves
MOVES = ((0, 1, 1.0), (0, -1, 1.0), (1, 0, 1.0), (-1, 0, 1.0),
         (1, 1, math.sqrt(2.0)), (1, -1, math.sqrt(2.0)),
         (-1, 1, math.sqrt(2.0)), (-1, -1, math.sqrt(2.0)))  # fmt: skip


@dataclass(frozen=True, slots=True)
class Reach:
    """Costs from one source to every node (``inf`` = unreached) and each node's
    predecessor on a cheapest path (the source and unreached nodes: negative)."""

    cost: FloatArray
    parent: IndexArray

    def path_to(self, source: int, node: int) -> list[int]:
        """Nodes from ``source`` to a reached ``node``, both included."""
        path = [node]
        parent = self.parent
        while node != source:
            node = int(parent[node])
            path.append(node)
        path.reverse()
        return path

    def path_from(self, node: int, root: int) -> list[int]:
        """Nodes from a reached ``node`` to ``root``, both included, on a reach of the
        reversed graph rooted at ``root`` (each node's parent is its next step)."""
        path = [node]
        parent = self.parent
        while node != root:
            node = int(parent[node])
            path.append(node)
            if node < 0 or len(path) > len(parent):  # never, on a sound reach
                raise ValueError(f"the reach's parents from node {path[0]} never lead to {root}")
        return path


class GridGraph:
    """A padded grid of step weights as a CSR graph for scipy's compiled Dijkstra.

    Every interior cell holds its 8 edges in :data:`MOVES` order (an edge into a
    blocked cell weighs ``inf``, which the search never relaxes), so the layout
    is fixed by the grid's shape and :meth:`updated` rewrites weights in place
    of rebuilding the graph.
    """

    __slots__ = ("_matrix", "_padded", "_reversed", "_reversed_weights", "_weights", "passable",
                 "stride")  # fmt: skip

    def __init__(self, padded: FloatArray) -> None:
        """``padded``: ``(rows + 2, cols + 2)`` weights, ``inf`` = blocked, border blocked."""
        rows, cols = padded.shape[0] - 2, padded.shape[1] - 2
        self.stride = int(padded.shape[1])
        self.passable: npt.NDArray[np.bool_] = np.isfinite(padded).ravel()
        self._weights = np.empty((rows, cols, len(MOVES)))
        _edge_weights(padded, self._weights, (0, rows, 0, cols))
        targets, starts = _layout_of(rows, cols, self.stride, padded.size)
        nodes = padded.size
        self._matrix = csr_array((self._weights.ravel(), targets, starts), shape=(nodes, nodes))
        self._padded = padded
        self._reversed: csr_array | None = None  # built on first use, then kept updated
        self._reversed_weights: FloatArray | None = None

    def updated(self, padded: FloatArray, window: tuple[int, int, int, int]) -> GridGraph:
        """A graph of ``padded``, which differs from this graph's weights only in
        the interior cells ``(row0, row1, col0, col1)`` (half-open; this graph is unchanged)."""
        row0, row1, col0, col1 = window
        clone = GridGraph.__new__(GridGraph)
        clone.stride = self.stride
        clone.passable = np.isfinite(padded).ravel()
        clone._weights = self._weights.copy()
        rows, cols = self._weights.shape[:2]
        sources = (max(0, row0 - 1), min(rows, row1 + 1), max(0, col0 - 1), min(cols, col1 + 1))
        _edge_weights(padded, clone._weights, sources)
        m = self._matrix
        clone._matrix = csr_array((clone._weights.ravel(), m.indices, m.indptr), shape=m.shape)
        clone._padded = padded
        clone._reversed, clone._reversed_weights = None, None
        if self._reversed_weights is not None:
            clone._reversed_weights = self._reversed_weights.copy()
            _reversed_edge_weights(padded, clone._reversed_weights, sources)
            clone._reversed = csr_array(
                (clone._reversed_weights.ravel(), m.indices, m.indptr), shape=m.shape
            )
        return clone

    @property
    def edges(self) -> int:
        """Edges into passable cells."""
        return int(np.isfinite(self._weights).sum())

    def reach_from(self, source: int) -> Reach:
        """A complete Dijkstra from ``source`` (one compiled call: not interruptible)."""
        cost, parent = dijkstra(
            self._matrix, directed=True, indices=source, return_predecessors=True
        )
        return Reach(np.asarray(cost, dtype=np.float64), np.asarray(parent, dtype=np.int32))

    def reach_to(self, target: int) -> Reach:
        """A complete Dijkstra on the reversed graph rooted at ``target``: from every
        passable node, the cheapest cost to ``target`` and the next step on that path
        (see :meth:`Reach.path_from`; one compiled call: not interruptible)."""
        if self._reversed is None:
            m = self._matrix
            weights = np.empty_like(self._weights)
            rows, cols = self._weights.shape[:2]
            _reversed_edge_weights(self._padded, weights, (0, rows, 0, cols))
            # published only once filled: updated() on another thread copies them (an
            # unfilled np.empty copied there would give a later graph garbage weights, the
            # likely cause of a CI run's 'negative weights' and silent planner)
            self._reversed_weights = weights
            self._reversed = csr_array((weights.ravel(), m.indices, m.indptr), shape=m.shape)
        cost, parent = dijkstra(
            self._reversed, directed=True, indices=target, return_predecessors=True
        )
        return Reach(np.asarray(cost, dtype=np.float64), np.asarray(parent, dtype=np.int32))


def _edge_weights(padded: FloatArray, out: FloatArray, window: tuple[int, int, int, int]) -> None:
    """``out[r, c, k]`` = the weight of move ``k`` from interior cell ``(r, c)``,
    for the sources in ``window`` (interior rows/cols, half-open)."""
    row0, row1, col0, col1 = window
    for k, (dr, dc, length) in enumerate(MOVES):
        np.multiply(padded[1 + dr + row0 : 1 + dr + row1, 1 + dc + col0 : 1 + dc + col1],
                    length, out=out[row0:row1, col0:col1, k])  # fmt: skip


def _reversed_edge_weights(
    padded: FloatArray, out: FloatArray, window: tuple[int, int, int, int]
) -> None:
    """``out[r, c, k]`` = the weight of the reversed edge from interior cell ``(r, c)``
    along move ``k``: the forward step from that neighbour into ``(r, c)``, its length
    times ``(r, c)``'s own weight; ``inf`` from or to a blocked cell (as forward)."""
    row0, row1, col0, col1 = window
    own = padded[1 + row0 : 1 + row1, 1 + col0 : 1 + col1]
    for k, (dr, dc, length) in enumerate(MOVES):
        into = padded[1 + dr + row0 : 1 + dr + row1, 1 + dc + col0 : 1 + dc + col1]
        out[row0:row1, col0:col1, k] = np.where(np.isfinite(into), own * length, np.inf)


def _layout_of(rows: int, cols: int, stride: int, nodes: int) -> tuple[IndexArray, IndexArray]:
    """CSR column indices and row pointers: 8 edges per interior cell, none elsewhere."""
    interior = (np.arange(1, rows + 1, dtype=np.int32)[:, None] * stride
                + np.arange(1, cols + 1, dtype=np.int32)[None, :])  # fmt: skip
    offsets = np.array([dr * stride + dc for dr, dc, _ in MOVES], dtype=np.int32)
    targets: IndexArray = (interior[:, :, None] + offsets).ravel()
    counts = np.zeros(nodes, dtype=np.int32)
    counts[interior.ravel()] = len(MOVES)
    starts: IndexArray = np.zeros(nodes + 1, dtype=np.int32)
    np.cumsum(counts, out=starts[1:])
    return targets, starts
