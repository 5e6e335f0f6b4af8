"""Boustrophedon coverage of a polygon field (ComputeCoveragePath, simplified F2C).

Rows run along the field's longest boundary edge, ``row_spacing`` apart,
starting half a spacing inside the headland. Each row is cut by the field
(outer boundary minus cut-outs, even-odd rule) and shortened by the headland
width at both ends. Row pieces are grouped into boustrophedon cells (a cut-out
splits a row: a new cell starts). Each cell is covered back and forth, turning
at a corner on the longer of two rows (not across a notch). Cells follow one
another nearest-first, joined along covered rows (a corner along one row, or a
chain of rows stepping where they overlap, e.g. between the arms of a U), so
the route stays in the field and off the cut-outs. Limit: parts of a field
whose rows share no such chain are joined by a straight leg.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

Point2D = tuple[float, float]


class CoverageError(ValueError):
    """A field that cannot be covered; ``reason`` is opennav_coverage's code name."""

    def __init__(self, reason: str, message: str) -> None:
        super().__init__(message)
        self.reason = reason


@dataclass(frozen=True, slots=True)
class CoverageParams:
    row_spacing: float = 0.5
    headland_width: float = 0.5
    spacing: float = 0.05  # distance between poses of the dense path


@dataclass(frozen=True, slots=True)
class Coverage:
    swaths: list[tuple[Point2D, Point2D]]
    path: list[tuple[float, float, float]]


def _check(polygons: Sequence[Sequence[Point2D]]) -> list[np.ndarray]:
    if not polygons:
        raise CoverageError("INVALID_REQUEST", "no polygons given: need the field boundary")
    rings = []
    for i, polygon in enumerate(polygons):
        ring = np.array(polygon, dtype=np.float64).reshape(-1, 2)
        if len(ring) > 1 and np.allclose(ring[0], ring[-1]):
            ring = ring[:-1]
        if len(ring) < 3:
            raise CoverageError("INVALID_COORDS", f"polygon {i} has {len(ring)} points, needs 3")
        if not np.isfinite(ring).all():
            raise CoverageError("INVALID_COORDS", f"polygon {i} has a non-finite coordinate")
        rings.append(ring)
    return rings


def _row_angle(outer: np.ndarray) -> float:
    edges = np.roll(outer, -1, axis=0) - outer
    longest = int(np.argmax(np.hypot(edges[:, 0], edges[:, 1])))
    return math.atan2(edges[longest, 1], edges[longest, 0])


def _crossings(rings: list[np.ndarray], y: float) -> list[float]:
    xs: list[float] = []
    for ring in rings:
        a, b = ring, np.roll(ring, -1, axis=0)
        spans = (a[:, 1] <= y) != (b[:, 1] <= y)
        t = (y - a[spans, 1]) / (b[spans, 1] - a[spans, 1])
        xs.extend((a[spans, 0] + t * (b[spans, 0] - a[spans, 0])).tolist())
    return sorted(xs)


def plan_coverage(
    polygons: Sequence[Sequence[Point2D]], params: CoverageParams | None = None
) -> Coverage:
    """Swaths and a dense path (x, y, yaw) covering the field; raises CoverageError."""
    params = params or CoverageParams()
    rings = _check(polygons)
    angle = _row_angle(rings[0])
    c, s = math.cos(angle), math.sin(angle)
    to_local = np.array([[c, -s], [s, c]])  # row direction becomes +x
    local = [ring @ to_local for ring in rings]
    low, high = local[0][:, 1].min(), local[0][:, 1].max()
    first = low + params.headland_width + params.row_spacing / 2
    rows: list[tuple[float, list[tuple[float, float]]]] = []
    for y in np.arange(first, high - params.headland_width + 1e-9, params.row_spacing):
        xs = _crossings(local, float(y))
        pieces = [
            (x0 + params.headland_width, x1 - params.headland_width)
            for x0, x1 in zip(xs[::2], xs[1::2], strict=False)
            if x1 - x0 > 2 * params.headland_width + 1e-9
        ]
        if pieces:
            rows.append((float(y), pieces))
    swaths, route = _ordered_swaths(_cells(rows))
    if not swaths:
        raise CoverageError("INVALID_REQUEST", "the field is too small for one swath")
    back = to_local.T
    world = [
        (tuple((np.array(a) @ back).tolist()), tuple((np.array(b) @ back).tolist()))
        for a, b in swaths
    ]
    path = [tuple((np.array(p) @ back).tolist()) for p in route]
    return Coverage(world, _dense(path, params.spacing))


Row = tuple[float, float, float]  # y, x from, x to (row-local coordinates)


def _cells(rows: list[tuple[float, list[tuple[float, float]]]]) -> list[list[Row]]:
    """Boustrophedon cells: runs of row pieces that overlap one-to-one row after row.

    Where a cut-out splits a row (or pieces merge again) a new cell starts, so
    a cell's rows can be joined by short turns that never cross a cut-out.
    """
    done: list[list[Row]] = []
    current: list[list[Row]] = []
    for y, pieces in rows:
        continued: list[list[Row]] = []
        for x0, x1 in pieces:
            touching = [c for c in current if c[-1][1] < x1 and x0 < c[-1][2]]
            cell: list[Row] = []
            if len(touching) == 1:
                prev = touching[0][-1]
                if sum(prev[1] < b and a < prev[2] for a, b in pieces) == 1:
                    cell = touching[0]
            cell.append((y, x0, x1))
            continued.append(cell)
        done.extend(c for c in current if all(c is not n for n in continued))
        current = continued
    return done + current


def _ordered_swaths(
    cells: list[list[Row]],
) -> tuple[list[tuple[Point2D, Point2D]], list[Point2D]]:
    """Cell after cell (nearest entry corner next), each covered back and forth.

    Returns the swaths and the route through them: between cells the route
    turns a corner along a covered row (see :func:`_transfer`), not across a cut-out.
    """
    swaths: list[tuple[Point2D, Point2D]] = []
    route: list[Point2D] = []
    spans: dict[float, list[tuple[float, float]]] = {}
    for y, x0, x1 in (row for cell in cells for row in cell):
        spans.setdefault(y, []).append((x0, x1))
    left = list(cells)
    while left:
        options = [(c, up, east) for c in left for up in (True, False) for east in (True, False)]
        here = route[-1] if route else None
        cell, up, east = options[0] if here is None else min(
            options, key=lambda o: math.dist(here, _entry(*o))
        )  # fmt: skip
        left = [c for c in left if c is not cell]
        if here is not None:
            route.extend(_transfer(here, _entry(cell, up, east), spans))
        for k, (y, x0, x1) in enumerate(cell if up else reversed(cell)):
            forward = east == (k % 2 == 0)
            swaths.append(((x0, y), (x1, y)) if forward else ((x1, y), (x0, y)))
            if k:  # the turn: a corner on the longer of the two rows, not a diagonal
                route.extend(_transfer(route[-1], swaths[-1][0], spans))
            route.extend(swaths[-1])
    return swaths, route


def _transfer(
    here: Point2D, there: Point2D, spans: dict[float, list[tuple[float, float]]]
) -> list[Point2D]:
    """The corners of a route between cells that stays on covered rows.

    A single corner when one piece of ``here``'s or ``there``'s row spans both;
    otherwise (e.g. from one arm of a U to the other) a route along row pieces,
    stepping between pieces of neighbouring rows where they overlap, with the
    fewest row changes (:func:`_through_rows`).
    """
    low, high = sorted((here[0], there[0]))
    for y in (here[1], there[1]):
        if any(x0 - 1e-9 <= low and high <= x1 + 1e-9 for x0, x1 in spans.get(y, [])):
            corner = (there[0], y) if y == here[1] else (here[0], y)
            return [] if corner in (here, there) else [corner]
    return _through_rows(here, there, spans)


def _through_rows(
    here: Point2D, there: Point2D, spans: dict[float, list[tuple[float, float]]]
) -> list[Point2D]:
    """Breadth-first over row pieces: a piece links to the pieces of the next row up
    or down (one row spacing away) that overlap it, stepping across inside the
    overlap. Empty if ``here`` and ``there`` share no such chain (a straight leg)."""
    ys = sorted(spans)
    step = min((b - a for a, b in itertools.pairwise(ys)), default=math.inf) * 1.5

    def piece_at(point: Point2D) -> tuple[int, int] | None:
        for row, y in enumerate(ys):
            if abs(y - point[1]) < 1e-9:
                for k, (x0, x1) in enumerate(spans[y]):
                    if x0 - 1e-9 <= point[0] <= x1 + 1e-9:
                        return row, k
        return None

    start, goal = piece_at(here), piece_at(there)
    if start is None or goal is None:
        return []
    came: dict[tuple[int, int], tuple[int, int] | None] = {start: None}
    frontier = [start]
    while frontier and goal not in came:
        reached = []
        for row, k in frontier:
            x0, x1 = spans[ys[row]][k]
            for other in (row - 1, row + 1):
                if not 0 <= other < len(ys) or abs(ys[other] - ys[row]) > step:
                    continue
                for j, (a, b) in enumerate(spans[ys[other]]):
                    if (other, j) not in came and max(x0, a) <= min(x1, b):
                        came[other, j] = (row, k)
                        reached.append((other, j))
        frontier = reached
    if goal not in came:
        return []
    chain = [goal]
    while (previous := came[chain[-1]]) is not None:
        chain.append(previous)
    chain.reverse()
    corners: list[Point2D] = []
    x = here[0]
    for (row, k), (other, j) in itertools.pairwise(chain):
        (x0, x1), (a, b) = spans[ys[row]][k], spans[ys[other]][j]
        x = min(max(x, max(x0, a)), min(x1, b))  # into the overlap
        corners += [(x, ys[row]), (x, ys[other])]
    corners.append((there[0], ys[goal[0]]))
    return [p for p in corners if math.dist(p, here) > 1e-9 and math.dist(p, there) > 1e-9]


def _entry(cell: list[Row], up: bool, east: bool) -> Point2D:
    y, x0, x1 = cell[0] if up else cell[-1]
    return (x0 if east else x1, y)


def _dense(points: list[Point2D], spacing: float) -> list[tuple[float, float, float]]:
    out: list[tuple[float, float, float]] = []
    for (x0, y0), (x1, y1) in itertools.pairwise(points):
        length = math.hypot(x1 - x0, y1 - y0)
        if length < 1e-9:
            continue
        yaw = math.atan2(y1 - y0, x1 - x0)
        pieces = max(1, math.ceil(length / spacing))
        out.extend(
            (x0 + (x1 - x0) * i / pieces, y0 + (y1 - y0) * i / pieces, yaw) for i in range(pieces)
        )
    last_yaw = out[-1][2] if out else 0.0
    out.append((points[-1][0], points[-1][1], last_yaw))
    return out
