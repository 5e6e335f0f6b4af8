"""Incremental costmap updates equal full rebuilds (property tests over random maps)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from aiobt.costmap import (
    FREE,
    LETHAL,
    NO_INFORMATION,
    Costmap,
    GridGeometry,
    InflationParams,
    RollingCostmap,
    Scan,
    combine_max,
    inflate,
    inflate_window,
)
from aiobt.costmap.inflation import bounding_window, grown

VALUES = (FREE, 40, 200, LETHAL, NO_INFORMATION)
Cell = tuple[int, int, int]  # row, col, value


@st.composite
def maps(draw: st.DrawFn) -> np.ndarray:
    height, width = draw(st.integers(4, 24)), draw(st.integers(4, 24))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    weights = np.array(draw(st.lists(st.floats(0.0, 1.0), min_size=5, max_size=5))) + 1e-3
    chosen: np.ndarray = rng.choice(np.array(VALUES, dtype=np.uint8), size=(height, width),
                                    p=weights / weights.sum())  # fmt: skip
    return chosen


@st.composite
def params(draw: st.DrawFn) -> InflationParams:
    inscribed = draw(st.floats(0.0, 0.3))
    return InflationParams(
        inscribed_radius=inscribed,
        inflation_radius=draw(st.floats(0.0, 0.6)),
        cost_scaling_factor=draw(st.floats(0.5, 10.0)),
        inflate_unknown=draw(st.booleans()),
        inflate_around_unknown=draw(st.booleans()),
    )


def changes(shape: tuple[int, int]) -> st.SearchStrategy[list[Cell]]:
    cell = st.tuples(st.integers(0, shape[0] - 1), st.integers(0, shape[1] - 1),
                     st.sampled_from(VALUES))  # fmt: skip
    return st.lists(cell, min_size=1, max_size=12)


@settings(max_examples=150, deadline=None)
@given(data=st.data(), base=maps(), inflation=params())
def test_inflating_the_window_around_changes_equals_a_full_reinflation(
    data: st.DataObject, base: np.ndarray, inflation: InflationParams
) -> None:
    geometry = GridGeometry(base.shape[1], base.shape[0], 0.05)
    out = inflate(base, geometry, inflation)
    edited = base.copy()
    for row, col, value in data.draw(changes(base.shape)):
        edited[row, col] = value
    changed = np.flatnonzero(edited != base)
    if changed.size:
        bound = geometry.cell_distance(inflation.inflation_radius)
        window = grown(bounding_window(changed, base.shape[1]), bound, base.shape)
        inflate_window(edited, out, window, geometry, inflation)
    assert np.array_equal(out, inflate(edited, geometry, inflation))


def full_master(costmap: Costmap) -> np.ndarray:
    assert costmap.static is not None
    return inflate(combine_max(costmap.static, costmap.obstacles), costmap.geometry,
                   costmap.inflation)  # fmt: skip


@st.composite
def occupancies(draw: st.DrawFn) -> np.ndarray:
    height, width = draw(st.integers(6, 30)), draw(st.integers(6, 30))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    unknown, occupied = draw(st.floats(0.0, 0.5)), draw(st.floats(0.0, 0.3))
    values = np.array((-1, 0, 100), dtype=np.int8)
    odds = np.array((unknown, max(0.0, 1.0 - unknown - occupied), occupied))
    chosen: np.ndarray = rng.choice(values, size=(height, width), p=odds / odds.sum())
    return chosen


def random_scan(rng: np.random.Generator, geometry: GridGeometry) -> Scan:
    pose = (rng.uniform(0, geometry.size_x), rng.uniform(0, geometry.size_y),
            rng.uniform(-math.pi, math.pi))  # fmt: skip
    ranges = rng.uniform(0.05, 1.5, size=24)
    ranges[rng.random(24) < 0.2] = math.inf
    return Scan.create(pose, -math.pi, 2 * math.pi / 24, ranges, 0.0, 2.0)


@settings(max_examples=60, deadline=None)
@given(occupancy=occupancies(), inflation=params(), seed=st.integers(0, 2**32 - 1))
def test_scans_and_marks_update_the_master_as_a_rebuild_would(
    occupancy: np.ndarray, inflation: InflationParams, seed: int
) -> None:
    rng = np.random.default_rng(seed)
    geometry = GridGeometry(occupancy.shape[1], occupancy.shape[0], 0.1)
    costmap = Costmap.from_occupancy(occupancy, geometry, inflation=inflation)
    before = costmap.master.copy()
    version = costmap.version
    for step in range(6):
        if step % 3 == 2:
            costmap.mark_points(rng.uniform(0, geometry.size_x, 3), rng.uniform(0, 2, 3))
        else:
            costmap.update_from_scan(random_scan(rng, geometry))
        if rng.random() < 0.5:  # some reads in between, some changes folded together
            continue
        master = costmap.master
        assert np.array_equal(master, full_master(costmap))
        if costmap.version == version:
            assert np.array_equal(master, before)
        else:
            window = costmap.changed_since(version)
            assert window is not None
            outside = np.ones(master.shape, dtype=bool)
            outside[window[0] : window[1], window[2] : window[3]] = False
            assert np.array_equal(master[outside], before[outside])
        version, before = costmap.version, master.copy()
    assert np.array_equal(costmap.master, full_master(costmap))


def test_a_scan_that_changes_nothing_leaves_the_master_and_its_version() -> None:
    occupancy = np.zeros((30, 30), dtype=np.int8)
    occupancy[:, 25] = 100
    costmap = Costmap.from_occupancy(occupancy, GridGeometry(30, 30, 0.1))
    scan = Scan.create((1.0, 1.5, 0.0), -0.5, 0.1, [1.55] * 11, 0.0, 5.0)
    costmap.master  # noqa: B018 - the first read builds it
    assert costmap.update_from_scan(scan) > 0
    master = costmap.master
    version = costmap.version
    assert costmap.update_from_scan(scan) == 0
    assert costmap.master is master
    assert costmap.version == version
    assert costmap.changed_since(version - 1) is not None


def test_changes_from_before_a_rebuild_or_too_long_ago_are_unknown() -> None:
    costmap = Costmap.from_occupancy(np.zeros((10, 10), dtype=np.int8), GridGeometry(10, 10, 0.1))
    costmap.mark_points([0.05], [0.05])
    costmap.master  # noqa: B018 - built, with the mark
    start = costmap.version
    costmap.mark_points([0.55], [0.55])
    assert costmap.changed_since(start) is not None
    costmap.clear_entirely()
    assert costmap.changed_since(start) is None  # a clearing rebuilds
    for i in range(40):
        costmap.mark_points([0.05 + (i % 10) * 0.1], [0.05 + (i // 10) * 0.1])
        costmap.master  # noqa: B018 - one version per read
    assert costmap.changed_since(start + 2) is None  # history holds 32 versions
    assert costmap.changed_since(costmap.version - 1) is not None


def test_the_same_scan_again_is_skipped_until_another_change_to_the_obstacles() -> None:
    costmap = Costmap.from_occupancy(np.zeros((30, 30), dtype=np.int8), GridGeometry(30, 30, 0.1))
    scan = Scan.create((1.0, 1.5, 0.0), -0.5, 0.1, [1.05] * 11, 0.0, 5.0)
    marked = costmap.update_from_scan(scan)
    assert marked > 0
    assert costmap.update_from_scan(scan) == 0
    costmap.clear_entirely()  # the marks are gone: the same scan puts them back
    assert costmap.update_from_scan(scan) == marked
    assert costmap.mark_points([1.55], [1.55]) == 1  # on the middle ray's free stretch
    assert costmap.update_from_scan(scan) == 1  # applied again: clears that mark
    assert np.array_equal(costmap.master, full_master(costmap))


@settings(max_examples=80, deadline=None)
@given(
    inflation=params(),
    seed=st.integers(0, 2**32 - 1),
    unknown=st.booleans(),
    moves=st.lists(st.tuples(st.floats(-0.3, 0.3), st.floats(-0.3, 0.3)), max_size=6),
)
def test_a_rolling_window_moved_with_its_master_equals_a_rebuild(
    inflation: InflationParams,
    seed: int,
    unknown: bool,
    moves: list[tuple[float, float]],
) -> None:
    rng = np.random.default_rng(seed)
    window = RollingCostmap(2.0, 1.6, 0.05, inflation, track_unknown_space=unknown)
    x = y = 0.0
    for dx, dy in [(0.0, 0.0), *moves]:
        x, y = x + dx, y + dy
        window.update_origin(x, y)  # a master up to date is moved, not rebuilt (mostly)
        _assert_as_rebuilt(window)
        window.mark_points(x + rng.uniform(-1.0, 1.0, 4), y + rng.uniform(-0.8, 0.8, 4))
        _assert_as_rebuilt(window)


@settings(max_examples=80, deadline=None)
@given(
    inflation=params(),
    seed=st.integers(0, 2**32 - 1),
    unknown=st.booleans(),
    steps=st.lists(
        st.tuples(
            st.floats(-0.3, 0.3),
            st.floats(-0.3, 0.3),
            st.sampled_from(["mark", "scan"]),
            st.booleans(),
            st.booleans(),
        ),
        max_size=6,
    ),
)
def test_a_window_moved_then_scanned_before_a_read_equals_a_rebuild(
    inflation: InflationParams,
    seed: int,
    unknown: bool,
    steps: list[tuple[float, float, str, bool, bool]],
) -> None:
    """The moved window's edges are re-inflated at the next read, in one go with the
    cells a scan or a mark changed meanwhile (or after a second move, rebuilt)."""
    rng = np.random.default_rng(seed)
    window = RollingCostmap(2.0, 1.6, 0.05, inflation, track_unknown_space=unknown)
    window.update_origin(0.0, 0.0)
    window.mark_points(rng.uniform(-1.0, 1.0, 6), rng.uniform(-0.8, 0.8, 6))
    window.master  # noqa: B018 - built
    x = y = 0.0
    for dx, dy, change, move_again, read in steps:
        x, y = x + dx, y + dy
        window.update_origin(x, y)
        if change == "mark":
            window.mark_points(x + rng.uniform(-1.0, 1.0, 4), y + rng.uniform(-0.8, 0.8, 4))
        else:
            ranges = rng.uniform(0.05, 1.5, size=24)
            pose = (x + rng.uniform(-0.5, 0.5), y + rng.uniform(-0.5, 0.5), rng.uniform(-3, 3))
            window.update_from_scan(Scan.create(pose, -math.pi, math.pi / 12, ranges, 0.0, 2.0))
        if move_again:
            window.update_origin(x + 0.06, y - 0.06)
        if read:
            _assert_as_rebuilt(window)
    _assert_as_rebuilt(window)


def test_a_small_move_shifts_the_master_instead_of_rebuilding_it() -> None:
    window = RollingCostmap(2.0, 2.0, 0.05, InflationParams(0.1, 0.3, 3.0))
    window.update_origin(0.0, 0.0)
    window.mark_points([0.5, -0.9, 0.2], [0.3, 0.1, -0.95])  # one near each edge
    version = window.version
    assert window.master.any()  # read: the marks applied
    window.update_origin(0.23, -0.12)
    assert window.version == version + 2  # the marks, then the shift: no rebuild pending
    _assert_as_rebuilt(window)


def _assert_as_rebuilt(window: RollingCostmap) -> None:
    moved = window.master.copy()
    window.layers_replaced()
    np.testing.assert_array_equal(moved, window.master)
