"""Merging grid cells into boxes (the world's walls as few collision shapes)."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt


def row_runs(mask: npt.NDArray[np.bool_]) -> npt.NDArray[np.int64]:
    """Horizontal runs of True cells as rows of (row, start_col, end_col_exclusive)."""
    padded = np.zeros((mask.shape[0], mask.shape[1] + 2), dtype=np.int8)
    padded[:, 1:-1] = mask
    edges = np.diff(padded, axis=1)
    start_rows, starts = np.nonzero(edges == 1)
    _, ends = np.nonzero(edges == -1)
    # nonzero scans row-major, so the k-th start and k-th end belong to one run
    return np.stack([start_rows, starts, ends], axis=1).astype(np.int64)


def merge_boxes(mask: npt.NDArray[np.bool_]) -> npt.NDArray[np.int64]:
    """Cover the True cells of ``mask`` with disjoint rectangles.

    Greedy merge: cells are first joined into maximal horizontal runs, then
    runs with the same column span in consecutive rows are stacked. Returns
    rows of (row0, col0, n_rows, n_cols).
    """
    runs = row_runs(mask)
    if runs.size == 0:
        return np.zeros((0, 4), dtype=np.int64)
    order = np.lexsort((runs[:, 0], runs[:, 2], runs[:, 1]))
    runs = runs[order]
    same_span = (runs[1:, 1] == runs[:-1, 1]) & (runs[1:, 2] == runs[:-1, 2])
    continues = same_span & (runs[1:, 0] == runs[:-1, 0] + 1)
    group_start = np.concatenate([[True], ~continues])
    starts = np.flatnonzero(group_start)
    ends = np.concatenate([starts[1:], [len(runs)]])
    first = runs[starts]
    n_rows = runs[ends - 1, 0] - first[:, 0] + 1
    return np.stack([first[:, 0], first[:, 1], n_rows, first[:, 2] - first[:, 1]], axis=1)
