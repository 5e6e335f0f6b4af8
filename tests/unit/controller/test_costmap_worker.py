"""The local costmap's published view and its updates in the worker thread."""

from __future__ import annotations

import asyncio
import logging
import math
import threading

import numpy as np
import pytest

from aiobt.costmap import INSCRIBED, LETHAL, CostGrid, RollingCostmap
from aiobt.costmap.local import CostmapUpdate, LocalCostmap, clearing
from aiobt.costmap.worker import CostmapWorker
from aiobt.geometry import Pose2D

from .test_local_costmap import _scan_with_wall_ahead

WALL = np.array([[1.02, 0.0], [0.85, 0.0]])  # on the wall 1 m ahead, and within the radius
ROBOT = Pose2D(0.0, 0.0, 0.0)
pytestmark = pytest.mark.timeout(20)


def _walled(costmap: LocalCostmap) -> bool:
    on_wall, near = (int(c) for c in costmap.costs_at(WALL))
    return on_wall == LETHAL and near >= INSCRIBED


def test_an_update_is_seen_only_once_published():
    costmap = LocalCostmap()
    view = CostmapUpdate(_scan_with_wall_ahead(1.0), ROBOT, ROBOT).apply(costmap)
    assert costmap.costs_at(WALL).tolist() == [0, 0]  # made, not published
    assert costmap.grid() is not view
    costmap.publish(view)
    assert _walled(costmap)
    assert costmap.grid() is view


def test_an_update_without_a_scan_moves_the_window_only():
    costmap = LocalCostmap()
    costmap.add_scan(_scan_with_wall_ahead(1.0), ROBOT)
    costmap.publish(CostmapUpdate(None, None, Pose2D(1.0, 0.0, 0.0)).apply(costmap))
    assert costmap.grid().geometry.origin_x == pytest.approx(1.0 - 2.5)
    assert _walled(costmap)  # the wall kept: it is still inside the window


def test_a_scan_it_cannot_take_is_dropped_with_a_warning(caplog: pytest.LogCaptureFixture):
    costmap = LocalCostmap()
    bad_sensor = Pose2D(math.nan, 0.0, 0.0)
    with caplog.at_level(logging.WARNING, "aiobt.costmap.local"):
        view = CostmapUpdate(_scan_with_wall_ahead(1.0), bad_sensor, ROBOT).apply(costmap)
    assert "scan dropped" in caplog.text
    assert not np.any(view.costs[view.costs != 0])


async def test_a_started_update_is_published_on_the_loop_once_done():
    costmap = LocalCostmap()
    worker = CostmapWorker(costmap)
    release, took = threading.Event(), asyncio.get_running_loop().create_future()
    update = CostmapUpdate(_scan_with_wall_ahead(1.0), ROBOT, ROBOT)

    def slow() -> CostGrid:
        assert release.wait(10.0)
        return update.apply(costmap)

    try:
        worker.start(slow, took.set_result)
        assert worker.busy
        await asyncio.sleep(0)
        assert costmap.costs_at(WALL).tolist() == [0, 0]  # readers keep the old view meanwhile
        release.set()
        seconds = await asyncio.wait_for(took, 10.0)
        assert seconds > 0.0
        assert not worker.busy
        assert _walled(costmap)
    finally:
        release.set()
        worker.close()


async def test_changes_run_in_the_order_given():
    costmap = LocalCostmap()
    worker = CostmapWorker(costmap)
    update = CostmapUpdate(_scan_with_wall_ahead(1.0), ROBOT, ROBOT)
    try:
        worker.start(lambda: update.apply(costmap))
        await worker.run(lambda: costmap.staged(RollingCostmap.clear_entirely))
        assert costmap.costs_at(WALL).tolist() == [0, 0]  # marked, then cleared
        await worker.run(lambda: update.apply(costmap))
        await worker.run(lambda: costmap.staged(clearing(ROBOT, 0.5, keep_inside=False)))
        assert _walled(costmap)  # cleared around the robot: the wall 1 m away stays
        await worker.run(lambda: costmap.staged(clearing(ROBOT, 0.5, keep_inside=True)))
        assert costmap.costs_at(WALL).tolist() == [0, 0]
    finally:
        worker.close()


async def test_a_failing_update_is_logged_and_the_view_kept(caplog: pytest.LogCaptureFixture):
    costmap = LocalCostmap()
    costmap.add_scan(_scan_with_wall_ahead(1.0), ROBOT)
    worker = CostmapWorker(costmap)

    def broken() -> CostGrid:
        raise RuntimeError("broken update")

    try:
        with caplog.at_level(logging.ERROR, "aiobt.costmap.worker"):
            worker.start(broken)
            await worker.run(lambda: costmap.grid())  # after the broken one, in order
            for _ in range(10):  # its callback runs on the loop soon after
                if not worker.busy:
                    break
                await asyncio.sleep(0)
        assert "local costmap update failed" in caplog.text
        assert "broken update" in caplog.text
        assert _walled(costmap)
    finally:
        worker.close()


async def test_a_bad_clearing_is_raised_to_its_caller():
    costmap = LocalCostmap()
    worker = CostmapWorker(costmap)
    try:
        with pytest.raises(ValueError, match="clear region"):
            await worker.run(lambda: costmap.staged(clearing(ROBOT, math.nan, keep_inside=True)))
    finally:
        worker.close()
