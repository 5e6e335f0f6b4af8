"""Nav2's corner smoothing of the dense path (``smooth_corners``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt_services.route.corners import corner_arc
from aiobt_services.route.dense import Smoothing, densify
from aiobt_services.route.intent import ReroutingState
from aiobt_services.route.scorers import DistanceScorer, EdgeScorer
from aiobt_services.route.search import Route, find_route

from .helpers import line, square

SMOOTH = Smoothing(smooth_corners=True, smoothing_radius=1.0)


def l_route() -> Route:
    graph = square()  # 1 (0,0) -> 2 (4,0) -> 3 (4,4), with 1 -> 4 blocked
    one, three = graph.node(1), graph.node(3)
    assert one is not None
    assert three is not None
    return find_route(graph, one, three, EdgeScorer([DistanceScorer()]), blocked=[4])


def test_a_right_angle_gets_an_arc_of_the_radius() -> None:
    arc = corner_arc((0.0, 0.0), (4.0, 0.0), (4.0, 4.0), 1.0, 2.9)
    assert arc is not None
    assert arc.start == pytest.approx((3.0, 0.0))
    assert arc.end == pytest.approx((4.0, 1.0))
    assert arc.center == pytest.approx((3.0, 1.0))
    points = arc.points(0.05)
    assert np.hypot(*(points - arc.center).T) == pytest.approx(1.0)
    assert np.hypot(*np.diff(points, axis=0).T).max() <= 0.05 + 1e-9


def test_no_arc_where_nav2_fits_none() -> None:
    assert corner_arc((0, 0), (4, 0), (8, 0.1), 1.0, 2.9) is None  # nearly straight
    assert corner_arc((0, 0), (4, 0), (0, 0), 1.0, 2.9) is None  # a U-turn
    assert corner_arc((3.5, 0), (4, 0), (4, 4), 1.0, 2.9) is None  # the tangent does not fit


def test_the_dense_path_rounds_the_corner_and_keeps_its_ends() -> None:
    route = l_route()
    sharp = densify(route, ReroutingState(), 0.05)
    round_ = densify(route, ReroutingState(), 0.05, SMOOTH)
    assert tuple(round_[0, :2]) == (0.0, 0.0)
    assert tuple(round_[-1, :2]) == (4.0, 4.0)
    corner_gap = np.hypot(round_[:, 0] - 4.0, round_[:, 1]).min()
    assert corner_gap == pytest.approx(math.sqrt(2) - 1, abs=0.01)  # the arc's middle
    assert np.hypot(sharp[:, 0] - 4.0, sharp[:, 1]).min() == 0.0
    assert np.hypot(*np.diff(round_[:, :2], axis=0).T).max() <= 0.05 + 1e-9
    assert round_[-1, 2] == pytest.approx(math.pi / 2)


def test_a_straight_route_is_unchanged_by_smoothing(caplog: pytest.LogCaptureFixture) -> None:
    graph = line(0.0, 2.0, 4.0)
    first, last = graph.node(1), graph.node(3)
    assert first is not None
    assert last is not None
    route = find_route(graph, first, last, EdgeScorer([DistanceScorer()]))
    smoothed = densify(route, ReroutingState(), 0.1, SMOOTH)
    assert np.array_equal(smoothed, densify(route, ReroutingState(), 0.1))
    assert "no corner arc between edge 101 and edge 102" in caplog.text
