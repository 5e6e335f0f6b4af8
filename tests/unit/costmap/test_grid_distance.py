"""Grid geometry and the bounded exact distance transform."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aiobt.costmap import GridGeometry, distance_transform


def test_world_cell_round_trip() -> None:
    g = GridGeometry(10, 5, 0.5, origin_x=-1.0, origin_y=2.0)
    assert g.world_to_cell(-1.0, 2.0) == (0, 0)
    assert g.world_to_cell(3.99, 4.49) == (9, 4)
    assert g.world_to_cell(4.0, 3.0) is None
    assert g.world_to_cell(-1.01, 3.0) is None
    assert g.world_to_cell(math.nan, 3.0) is None
    assert g.cell_to_world(0, 0) == (-0.75, 2.25)
    cols, rows, ok = g.world_to_cells(np.array([-0.9, 100.0, 0.3]), np.array([2.1, 2.1, 4.4]))
    assert ok.tolist() == [True, False, True]
    assert (cols[ok].tolist(), rows[ok].tolist()) == ([0, 2], [0, 4])


@pytest.mark.parametrize(("width", "height", "res"), [(0, 3, 0.1), (3, 3, 0.0), (3, 3, math.nan)])
def test_bad_geometry_is_rejected(width: int, height: int, res: float) -> None:
    with pytest.raises(ValueError, match="grid"):
        GridGeometry(width, height, res)


def brute_force(mask: np.ndarray) -> np.ndarray:
    rows, cols = np.nonzero(mask)
    yy, xx = np.mgrid[0 : mask.shape[0], 0 : mask.shape[1]]
    if len(rows) == 0:
        return np.full(mask.shape, np.inf)
    d: np.ndarray = np.hypot(yy[..., None] - rows, xx[..., None] - cols).min(axis=-1)
    return d


@settings(max_examples=40, deadline=None)
@given(
    st.integers(1, 18),
    st.integers(1, 18),
    st.floats(0.0, 0.2),
    st.integers(0, 8),
    st.integers(0, 2**31),
)
def test_distance_transform_is_exact_within_bound(
    height: int, width: int, density: float, bound: int, seed: int
) -> None:
    mask = np.random.default_rng(seed).random((height, width)) < density
    expected = brute_force(mask)
    got = distance_transform(mask, bound)
    near = expected <= bound
    np.testing.assert_allclose(got[near], expected[near])
    assert np.isinf(got[~near]).all()
