"""Point-in-zone counts and the refusals of zones that cannot work."""

from __future__ import annotations

import numpy as np
import pytest

from aiobt_services.collision_monitor import ShapeError, circle, inside_polygon, polygon

SQUARE = np.array([[1.0, 1.0], [1.0, -1.0], [-1.0, -1.0], [-1.0, 1.0]])


def test_points_inside_a_square_and_a_concave_polygon() -> None:
    points = np.array([[0.0, 0.0], [0.99, 0.5], [1.01, 0.0], [0.0, -1.5], [-0.5, 0.9]])
    assert inside_polygon(points, SQUARE).tolist() == [True, True, False, False, True]
    u_shape = np.array([[0, 0], [3, 0], [3, 3], [2, 3], [2, 1], [1, 1], [1, 3], [0, 3]], float)
    probe = np.array([[0.5, 2.0], [1.5, 2.0], [2.5, 2.0], [1.5, 0.5]])
    assert inside_polygon(probe, u_shape).tolist() == [True, False, True, True]


def test_matches_a_point_by_point_ray_cast_on_random_points() -> None:
    rng = np.random.default_rng(3)
    angles = np.linspace(0, 2 * np.pi, 10, endpoint=False)
    radii = np.array([1.0, 0.4] * 5)
    star = np.column_stack((np.cos(angles) * radii, np.sin(angles) * radii))
    points = rng.uniform(-1.2, 1.2, size=(500, 2))

    def one(x: float, y: float) -> bool:
        inside = False
        for (x1, y1), (x2, y2) in zip(star, np.roll(star, -1, axis=0), strict=True):
            if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
                inside = not inside
        return inside

    expected = [one(x, y) for x, y in points]
    assert inside_polygon(points, star).tolist() == expected
    assert 50 < sum(expected) < 450  # the probe really hits both sides


def test_a_circle_counts_points_strictly_within_its_radius() -> None:
    shape = circle("c", 0.5)
    points = np.array([[0.0, 0.49], [0.5, 0.0], [0.3, 0.3]])
    assert shape.inside(points).tolist() == [True, False, True]
    assert shape.outline().shape == (16, 2)


@pytest.mark.parametrize(
    ("points", "message"),
    [
        ([[0, 0], [1, 0]], "'z' has 2 points: a polygon needs at least 3"),
        ([[0, 0], [1, 1], [1, 0], [0, 1]], "'z' is self-intersecting: edge 0"),
        ([[0, 0], [1, 0], [2, 0]], "'z' has no area"),
        ([[0, 0], [1, 0], [float("nan"), 1]], "points must be finite"),
        ("not points", "points must be [[x, y], ...]"),
    ],
)
def test_a_bad_polygon_is_refused_by_name(points: object, message: str) -> None:
    with pytest.raises(ShapeError, match=message.replace("[", r"\[").replace("]", r"\]")):
        polygon("z", points)


def test_a_bad_circle_is_refused_by_name() -> None:
    with pytest.raises(ShapeError, match="circle 'c': radius must be a number > 0"):
        circle("c", -1.0)


def test_a_zone_looks_only_within_its_reach_and_decides_as_the_full_cast() -> None:
    rng = np.random.default_rng(5)
    star = polygon("star", [[1.0, 0.0], [0.2, 0.2], [0.0, 1.0], [-0.2, 0.2], [-1.0, 0.0],
                            [-0.2, -0.2], [0.0, -1.0], [0.2, -0.2]])  # fmt: skip
    assert star.reach == pytest.approx(1.0)
    points = rng.uniform(-3.0, 3.0, size=(2000, 2))
    full = inside_polygon(points, np.asarray(star.vertices))
    assert star.inside(points).tolist() == full.tolist()
    assert full.any()
    assert circle("c", 0.5).reach == 0.5
