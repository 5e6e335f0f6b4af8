"""Nav2's BtServiceNode leaves (costmap clearing, path validity) and the cancel leaves."""

from __future__ import annotations

import asyncio
import logging
from typing import Any

import pytest

from aiobt.core.errors import NodeError
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.msgs import (
    ClearCostmapAroundPose,
    ClearCostmapResponse,
    ClearEntireCostmap,
    Empty,
    FollowPath,
    IsPathValid,
    PoseStamped,
    ReinitializeGlobalLocalization,
)
from aiobt.nav import register_nav2_nodes
from aiobt.testing.stubs import tree_xml
from aiobt.transport import Bus

from .support import nav_tree, run_to_end, straight_path, tick_until

pytestmark = pytest.mark.timeout(30)
S, F, R = Status.SUCCESS, Status.FAILURE, Status.RUNNING
LOCAL_CLEAR = "local_costmap/clear_entirely_local_costmap"


def clearing(bus: Bus, name: str, success: bool = True) -> list[Any]:
    requests: list[Any] = []

    def handle(request: Any) -> ClearCostmapResponse:
        requests.append(request)
        return ClearCostmapResponse(success=success, message="" if success else "no map yet")

    bus.serve(name, ClearEntireCostmap.Request, ClearCostmapResponse, handle)
    return requests


async def test_clear_entire_costmap_calls_nav2s_service_name(local_bus: Bus) -> None:
    requests = clearing(local_bus, LOCAL_CLEAR)
    tree = nav_tree(
        local_bus,
        f'<ClearEntireCostmap service_name="{LOCAL_CLEAR}" plugins="obstacle_layer;voxel"/>',
    )
    assert await run_to_end(tree) is S
    assert requests[0].plugins == ["obstacle_layer", "voxel"]
    assert tree.root_blackboard["number_recoveries"] == 1


async def test_a_costmap_that_cannot_clear_fails_the_leaf(local_bus: Bus) -> None:
    clearing(local_bus, LOCAL_CLEAR, success=False)
    tree = nav_tree(local_bus, f'<ClearEntireCostmap service_name="/{LOCAL_CLEAR}"/>')
    assert await run_to_end(tree) is F


@pytest.mark.timeout(20)
async def test_without_a_service_it_fails_after_server_timeout(
    local_bus: Bus, caplog: pytest.LogCaptureFixture
) -> None:
    tree = nav_tree(
        local_bus, '<ClearEntireCostmap service_name="nobody/clears" server_timeout="200"/>'
    )
    loop = asyncio.get_running_loop()
    started = loop.time()
    assert await run_to_end(tree) is F
    assert 0.19 <= loop.time() - started < 3.0
    assert "nobody/clears" in caplog.text


async def test_a_clearing_leaf_without_service_name_is_an_error_naming_the_port(
    local_bus: Bus,
) -> None:
    tree = nav_tree(local_bus, "<ClearEntireCostmap/>")
    with pytest.raises(NodeError, match="service_name"):
        await run_to_end(tree)


async def test_clear_around_pose_sends_pose_and_distance(local_bus: Bus) -> None:
    seen: list[Any] = []

    def handle(request: Any) -> ClearCostmapResponse:
        seen.append(request)
        return ClearCostmapResponse()

    local_bus.serve("g/clear", ClearCostmapAroundPose.Request, ClearCostmapResponse, handle)
    pose = PoseStamped.from_xy_yaw(1.0, 2.0, 0.0)
    tree = nav_tree(local_bus, '<ClearCostmapAroundPose service_name="g/clear" pose="{p}" '
                    'reset_distance="0.5"/>', p=pose)  # fmt: skip
    assert await run_to_end(tree) is S
    assert (seen[0].pose, seen[0].reset_distance) == (pose, 0.5)


def validity(bus: Bus, invalid: list[int]) -> list[Any]:
    requests: list[Any] = []

    def handle(request: Any) -> Any:
        requests.append(request)
        return IsPathValid.Response(is_valid=not invalid, invalid_pose_indices=invalid)

    bus.serve("is_path_valid", IsPathValid.Request, IsPathValid.Response, handle)
    return requests


async def test_validate_path_succeeds_on_a_valid_path(local_bus: Bus) -> None:
    requests = validity(local_bus, [])
    path = straight_path(2.0)
    tree = nav_tree(local_bus, '<ValidatePath path="{p}" collision_poses="{c}"/>', p=path)
    assert await run_to_end(tree) is S
    assert requests[0].path == path
    assert requests[0].max_cost == 254
    assert tree.root_blackboard["c"] == []


async def test_validate_path_fails_and_lists_the_first_collision(local_bus: Bus) -> None:
    validity(local_bus, [3, 4, 5])
    path = straight_path(2.0)
    body = '<ValidatePath path="{p}" collision_poses="{c}" stop_at_first_collision="{first}"/>'
    tree = nav_tree(local_bus, body, p=path, first=True)
    assert await run_to_end(tree) is F
    assert tree.root_blackboard["c"] == [path.poses[3]]
    tree.root_blackboard["first"] = False
    assert await run_to_end(tree) is F
    assert tree.root_blackboard["c"] == path.poses[3:6]


async def test_validate_path_asks_the_service_for_nav2s_whole_check(local_bus: Bus) -> None:
    requests = validity(local_bus, [])
    square = "[[0.1, 0.1], [0.1, -0.1], [-0.1, -0.1], [-0.1, 0.1]]"
    body = (
        '<ValidatePath path="{p}" max_lookahead_distance="0.55" layer_name="obstacle_layer" '
        f'footprint="{square}" stop_at_first_collision="false"/>'
    )
    path = straight_path(2.0)
    tree = nav_tree(local_bus, body, p=path)
    assert await run_to_end(tree) is S
    sent = requests[0]
    assert sent.path == path  # the service measures the lookahead, from the robot
    assert (sent.max_lookahead_distance, sent.stop_at_first_collision) == (0.55, False)
    assert (sent.layer_name, sent.footprint) == ("obstacle_layer", square)


async def test_validate_path_fails_when_the_service_cannot_check(
    local_bus: Bus, caplog: pytest.LogCaptureFixture
) -> None:
    def handle(request: Any) -> Any:
        return IsPathValid.Response(is_valid=False, success=False, message="no map received yet")

    local_bus.serve("is_path_valid", IsPathValid.Request, IsPathValid.Response, handle)
    tree = nav_tree(local_bus, '<ValidatePath path="{p}" collision_poses="{c}"/>',
                    p=straight_path(2.0))  # fmt: skip
    with caplog.at_level(logging.WARNING):
        assert await run_to_end(tree) is F
    assert tree.root_blackboard["c"] == []
    assert any("no map received yet" in r.getMessage() for r in caplog.records)


async def test_is_path_valid_is_a_condition_with_the_same_check(local_bus: Bus) -> None:
    validity(local_bus, [1])
    tree = nav_tree(local_bus, '<IsPathValid path="{path}" server_timeout="1000"/>',
                    path=straight_path())  # fmt: skip
    assert await run_to_end(tree) is F


async def test_reinitialize_global_localization(local_bus: Bus) -> None:
    calls: list[Any] = []

    def handle(request: Any) -> Any:
        calls.append(request)
        return ReinitializeGlobalLocalization.Response(ok=True, message="done")

    local_bus.serve("reinitialize_global_localization", Empty,
                    ReinitializeGlobalLocalization.Response, handle)  # fmt: skip
    tree = nav_tree(local_bus, "<ReinitializeGlobalLocalization/>")
    assert await run_to_end(tree) is S
    assert len(calls) == 1


async def test_cancel_control_cancels_the_controllers_goal(local_bus: Bus) -> None:
    started, cancelled = asyncio.Event(), asyncio.Event()

    async def execute(goal: Any, handle: Any) -> Any:
        started.set()
        try:
            await asyncio.Event().wait()
        finally:
            cancelled.set()
        raise AssertionError("unreachable")

    local_bus.action_server("follow_path", FollowPath, execute)
    follower = nav_tree(local_bus, '<FollowPath path="{p}"/>', p=straight_path())
    assert await tick_until(follower, started) is R
    canceller = nav_tree(local_bus, "<CancelControl/>")
    assert await run_to_end(canceller) is S
    assert cancelled.is_set()
    assert await run_to_end(follower) is S  # canceled by someone else: SUCCESS (Nav2)
    node: Any = follower.find("FollowPath")
    assert node._handle is None


@pytest.mark.timeout(20)
async def test_a_cancel_without_a_server_fails_after_server_timeout(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, '<CancelSpin server_name="nobody_spins" server_timeout="150"/>')
    loop = asyncio.get_running_loop()
    started = loop.time()
    assert await run_to_end(tree) is F
    assert 0.14 <= loop.time() - started < 3.0


async def test_a_factory_for_another_namespace_than_its_bus_is_refused(local_bus: Bus) -> None:
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory, local_bus, namespace="robot7")
    tree = factory.create_tree_from_text(tree_xml("<CancelSpin/>"))
    with pytest.raises(NodeError, match="robot7"):
        await run_to_end(tree)
