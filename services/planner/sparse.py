"""The 8-connected grid as a compiled graph: the planner's only door to scipy.

scipy ships no type stubs, so this narrow wrapper is the one module that
imports it (``[[tool.mypy.overrides]]`` for ``scipy.*``) and hands typed numpy
arrays in and out.

Nodes are a :class:`Traversal`'s padded flat indices. An edge ``u -> v`` exists
for every interior cell ``u`` and each of its 8 neighbours ``v`` that is
passable, weighted ``step_length * weight(v)`` (the GridBased metric: entering a
cell costs its weight). Edges leave blocked cells too, so a search may start in
a block opened for the start without rebuilding the graph.
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


class GridGraph:
    """A padded grid of step weights as a CSR graph for scipy's compiled Dijkstra."""

    __slots__ = ("_matrix", "passable", "stride")

    def __init__(self, padded: FloatArray) -> None:
        """``padded``: ``(rows + 2, cols + 2)`` weights, ``inf`` = blocked, border blocked."""
        rows, cols = padded.shape[0] - 2, padded.shape[1] - 2
        self.stride = int(padded.shape[1])
        nodes = padded.size
        self.passable: npt.NDArray[np.bool_] = np.isfinite(padded).ravel()
        weights = np.empty((rows, cols, len(MOVES)))
        for k, (dr, dc, length) in enumerate(MOVES):
            np.multiply(padded[1 + dr : rows + 1 + dr, 1 + dc : cols + 1 + dc], length,
                        out=weights[:, :, k])  # fmt: skip
        edge = np.isfinite(weights)
        interior = (np.arange(1, rows + 1, dtype=np.int32)[:, None] * self.stride
                    + np.arange(1, cols + 1, dtype=np.int32)[None, :])  # fmt: skip
        offsets = np.array([dr * self.stride + dc for dr, dc, _ in MOVES], dtype=np.int32)
        targets = (interior[:, :, None] + offsets)[edge]
        counts = np.zeros(nodes, dtype=np.int32)
        counts[interior.ravel()] = edge.sum(axis=2, dtype=np.int32).ravel()
        starts = np.zeros(nodes + 1, dtype=np.int32)
        np.cumsum(counts, out=starts[1:])
        self._matrix = csr_array((weights[edge], targets, starts), shape=(nodes, nodes))

    @property
    def edges(self) -> int:
        return int(self._matrix.nnz)

    def reach_from(self, source: int) -> Reach:
        """A complete Dijkstra from ``source`` (one compiled call: not interruptible)."""
        cost, parent = dijkstra(
            self._matrix, directed=True, indices=source, return_predecessors=True
        )
        return Reach(np.asarray(cost, dtype=np.float64), np.asarray(parent, dtype=np.int32))
