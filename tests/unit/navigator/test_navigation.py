"""The navigator's goal intake, preemption, cancel and results, on stub trees."""

from __future__ import annotations

import asyncio
import logging
from dataclasses import replace
from pathlib import Path

import pytest

from aiobt.core.clock import ManualClock
from aiobt.core.status import Status
from aiobt.msgs import ActionResult, OccupancyGrid, Point, Pose, PoseStamped
from aiobt_services.navigator import NAVIGATE_TO_POSE, MapBounds, NavRequest

from .harness import WAIT, FakeChannel, Rig, make_rig, through, to_pose

GATED = '<Gate name="drive"/>'
TREES = {"ToPose": GATED, "ThroughPoses": GATED}


def start(
    rig: Rig, request: NavRequest, channel: FakeChannel | None = None
) -> asyncio.Task[ActionResult]:
    return asyncio.create_task(rig.navigator.navigate(request, channel or FakeChannel()))


async def test_a_goal_runs_its_tree_to_success(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    task = start(rig, to_pose("g1"))
    await rig.gates.wait_started("drive")
    assert rig.navigator.tree_of(to_pose("x")) == "ToPose"
    rig.gates.open("drive")
    result = await asyncio.wait_for(task, WAIT)
    assert result == ActionResult()
    assert rig.sink.snapshots[-1].state == "succeeded"
    assert rig.navigator.current is None


async def test_the_goal_is_on_the_blackboard(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    task = start(rig, through("g1", (1, 2), (3, 4)))
    await rig.gates.wait_started("drive")
    navigation = rig.navigator.current
    assert navigation is not None
    assert navigation.tree is not None
    goals = navigation.tree.root_blackboard.get("goals")
    assert [(g.pose.position.x, g.pose.position.y) for g in goals.goals] == [(1, 2), (3, 4)]
    assert navigation.tree.root_blackboard.get("number_recoveries") == 0
    statuses = navigation.tree.root_blackboard.get("waypoint_statuses")
    assert [(s.waypoint_index, s.waypoint_status) for s in statuses] == [(0, 0), (1, 0)]
    assert statuses[1].waypoint_pose == goals.goals[1]
    rig.gates.open("drive")
    assert (await asyncio.wait_for(task, WAIT)).error_code == 0


ERRORS = (
    "<Sequence><Script code=\"compute_path_error_code := 207; compute_path_error_msg := 'no plan'; "
    "follow_path_error_code := 104; follow_path_error_msg := 'no progress'\"/>"
    "<AlwaysFailure/></Sequence>"
)


async def test_a_failed_tree_reports_the_lowest_error_code(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, {**TREES, "Failing": ERRORS})
    result = await asyncio.wait_for(
        rig.navigator.navigate(to_pose("g", tree="Failing"), FakeChannel()), WAIT
    )
    assert result == ActionResult(error_code=104, error_msg="no progress")
    assert rig.sink.snapshots[-1].state == "aborted"
    assert rig.sink.snapshots[-1].error_code == 104


@pytest.mark.parametrize(
    ("goal", "code"),
    [(to_pose("g", tree="Fails"), 9000), (through("g", (1, 1), tree="Fails"), 9100)],
)
async def test_a_failure_without_error_code_is_unknown(
    tmp_path: Path, goal: NavRequest, code: int
) -> None:
    rig = make_rig(tmp_path, {**TREES, "Fails": "<AlwaysFailure/>"})
    result = await asyncio.wait_for(rig.navigator.navigate(goal, FakeChannel()), WAIT)
    assert result.error_code == code
    assert "Fails failed without an error code" in result.error_msg


async def test_bad_trees_fail_to_load_and_the_next_goal_runs(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    broken = tmp_path / "broken.xml"
    broken.write_text(
        '<root BTCPP_format="4"><BehaviorTree ID="B"><NoSuchNode/></BehaviorTree></root>'
    )
    cases = {
        "NoSuchTree": "behavior tree ID 'NoSuchTree' is not registered",
        str(tmp_path / "missing.xml"): "missing.xml does not exist",
        str(broken): "NoSuchNode",
    }
    for tree, expected in cases.items():
        result = await asyncio.wait_for(
            rig.navigator.navigate(to_pose("g", tree=tree), FakeChannel()), WAIT
        )
        assert result.error_code == 9001, tree
        assert expected in result.error_msg
    result = await asyncio.wait_for(
        rig.navigator.navigate(through("t", (1, 1), tree="Nope"), FakeChannel()), WAIT
    )
    assert result.error_code == 9101
    task = start(rig, to_pose("good"))
    await rig.gates.wait_started("drive")
    rig.gates.open("drive")
    assert (await asyncio.wait_for(task, WAIT)).error_code == 0


async def test_goals_outside_the_map_or_in_another_frame_are_refused(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    origin = Pose(position=Point(x=-1.0, y=-2.0))
    grid = OccupancyGrid.from_array([[0] * 20] * 10, resolution=0.5, origin=origin)
    rig.navigator.map_bounds = MapBounds.of(grid)
    result = await rig.navigator.navigate(to_pose("far", x=9.5, y=0.0), FakeChannel())
    assert result.error_code == 204
    assert "(9.5, 0) is outside the map (x [-1, 9), y [-2, 3))" in result.error_msg
    result = await rig.navigator.navigate(through("t", (0, 0), (0, 3)), FakeChannel())
    assert result.error_code == 204
    assert "pose 1 (0, 3) is outside the map" in result.error_msg
    in_odom = PoseStamped.model_validate({"header": {"frame_id": "odom"}, "pose": {}})
    request = NavRequest(NAVIGATE_TO_POSE, "odom", (in_odom,))
    result = await rig.navigator.navigate(request, FakeChannel())
    assert result.error_code == 9000
    assert "frame 'odom'" in result.error_msg
    assert rig.sink.trees == []  # no tree was loaded for them


async def test_a_newer_goal_for_the_same_tree_updates_the_running_tree(tmp_path: Path) -> None:
    replanning = (
        "<ReactiveSequence><Fallback><Inverter><GlobalUpdatedGoal/></Inverter>"
        '<Script code="replanned := 1"/></Fallback><Gate name="drive"/></ReactiveSequence>'
    )
    rig = make_rig(tmp_path, {**TREES, "ToPose": replanning})
    channel = FakeChannel()
    task = start(rig, to_pose("first", 1.0, 1.0), channel)
    await rig.gates.wait_started("drive")
    navigation = rig.navigator.current
    assert navigation is not None
    assert navigation.tree is not None
    tree = navigation.tree
    channel.newer.append(to_pose("second", 5.0, 6.0))
    for _ in range(100):
        if tree.root_blackboard.get("replanned"):
            break
        await channel.next_feedback()
    assert tree.root_blackboard.get("replanned") == 1
    assert tree.root_blackboard.get("goal").pose.position.x == 5.0
    assert navigation.tree is tree
    assert len(rig.sink.trees) == 1
    assert rig.gates.halts.get("drive", 0) == 0  # not halted
    assert navigation.request.goal_id == "second"
    rig.gates.open("drive")
    assert (await asyncio.wait_for(task, WAIT)).error_code == 0


async def test_a_newer_goal_for_another_tree_halts_the_running_one(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, {**TREES, "Other": '<Gate name="other"/>'})
    channel = FakeChannel()
    task = start(rig, to_pose("first"), channel)
    await rig.gates.wait_started("drive")
    channel.newer.append(to_pose("second", tree="Other"))
    await rig.gates.wait_started("other")
    assert rig.gates.halts["drive"] == 1
    assert [t.tree_id for t in rig.sink.trees] == ["ToPose", "Other"]
    assert [t.run for t in rig.sink.trees] == [1, 2]
    rig.gates.open("other", Status.SUCCESS)
    assert (await asyncio.wait_for(task, WAIT)).error_code == 0


async def test_a_goal_of_the_other_action_preempts_the_running_navigation(tmp_path: Path) -> None:
    rig = make_rig(
        tmp_path, {"ToPose": '<Gate name="drive"/>', "ThroughPoses": '<Gate name="tour"/>'}
    )
    first = start(rig, to_pose("first"))
    await rig.gates.wait_started("drive")
    second = start(rig, through("second", (1, 1), (2, 2)))
    result = await asyncio.wait_for(first, WAIT)
    assert result.error_code == 9000
    assert result.error_msg == "preempted by navigate_through_poses goal second"
    await rig.gates.wait_started("tour")
    assert rig.gates.halts["drive"] == 1
    rig.gates.open("tour")
    assert (await asyncio.wait_for(second, WAIT)).error_code == 0


async def test_cancel_halts_the_tree(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    task = start(rig, to_pose("g"))
    await rig.gates.wait_started("drive")
    task.cancel()
    with pytest.raises(asyncio.CancelledError):
        await asyncio.wait_for(task, WAIT)
    assert rig.gates.halts["drive"] == 1
    assert rig.sink.snapshots[-1].state == "canceled"
    task = start(rig, to_pose("next"))
    await rig.gates.wait_started("drive")
    rig.gates.open("drive")
    assert (await asyncio.wait_for(task, WAIT)).error_code == 0


async def test_a_cancel_landing_as_the_loop_wakes_up_still_halts_the_tree(tmp_path: Path) -> None:
    # the cancel comes after the wake-up wait has finished but before the navigation's
    # task resumes (at a speed-up the loop wakes every millisecond): asyncio.wait_for on
    # Python 3.11 swallowed such a cancel and the canceled goal ran on (a bounded wait:
    # on --sim-time the loop's wait is bounded by clock_timeout)
    rig = make_rig(tmp_path, TREES, clock_timeout=30.0)
    task = start(rig, to_pose("g"))
    await rig.gates.wait_started("drive")
    navigation = rig.navigator.current
    assert navigation is not None
    assert navigation.tree is not None
    tree = navigation.tree
    wake_up = tree.wait_for_wake_up

    async def cancel_then_wake(period: float) -> bool:
        tree.wait_for_wake_up = wake_up  # type: ignore[method-assign]
        task.cancel()  # the wake-up is in: the wait ends as the cancel lands
        return True

    tree.wait_for_wake_up = cancel_then_wake  # type: ignore[method-assign]
    tree.emit_wake_up()
    with pytest.raises(asyncio.CancelledError):
        await asyncio.wait_for(asyncio.shield(task), 2.0)
    assert rig.gates.halts["drive"] == 1
    assert rig.sink.snapshots[-1].state == "canceled"


async def test_shutdown_aborts_the_running_navigation(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    task = start(rig, to_pose("g"))
    await rig.gates.wait_started("drive")
    await rig.navigator.shutdown("navigator shutting down")
    result = await asyncio.wait_for(task, WAIT)
    assert result.error_msg == "navigator shutting down"
    assert rig.gates.halts["drive"] == 1


async def test_a_btlog_per_navigation(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES, btlog_dir=tmp_path / "logs")
    for goal_id in ("a", "b"):
        task = start(rig, to_pose(goal_id))
        await rig.gates.wait_started("drive")
        rig.gates.open("drive")
        await asyncio.wait_for(task, WAIT)
    files = sorted((tmp_path / "logs").glob("*.btlog"))
    assert [f.name.split("_", 2)[-1] for f in files] == [
        "navigate_to_pose_a.btlog",
        "navigate_to_pose_b.btlog",
    ]
    assert all(f.read_bytes().startswith(b"BTCPP4-FileLogger2") for f in files)


async def test_a_recording_per_navigation_closed_at_its_end(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    rig.navigator.options = replace(rig.navigator.options, mcap_dir=tmp_path / "runs")
    opened: list[Path] = []
    closed: list[Path] = []

    class Recorder:
        def __init__(self, path: Path) -> None:
            self.path = path
            opened.append(path)

        def close(self) -> None:
            closed.append(self.path)

    rig.navigator.recorder = Recorder
    for goal_id in ("a", "b"):
        task = start(rig, to_pose(goal_id))
        await rig.gates.wait_started("drive")
        assert len(opened) == len(closed) + 1  # recording while the tree runs
        rig.gates.open("drive")
        await asyncio.wait_for(task, WAIT)
    assert closed == opened
    assert [p.name.split("_", 2)[-1] for p in opened] == [
        "navigate_to_pose_a.mcap",
        "navigate_to_pose_b.mcap",
    ]
    assert all(p.parent == tmp_path / "runs" for p in opened)
    assert (tmp_path / "runs").is_dir()


async def test_a_stalled_clock_does_not_stall_the_loop(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    rig = make_rig(tmp_path, TREES, clock=ManualClock(), clock_timeout=0.1)
    channel = FakeChannel()
    task = start(rig, to_pose("first"), channel)
    await rig.gates.wait_started("drive")
    navigation = rig.navigator.current
    assert navigation is not None
    channel.newer.append(to_pose("second", 4.0, 4.0))  # no wake-up: seen on the next loop
    with caplog.at_level(logging.WARNING, "aiobt_services.navigator.navigation"):
        await channel.next_feedback()
        await channel.next_feedback()
    assert navigation.request.goal_id == "second"
    assert "the clock has not moved for 0.1 s" in caplog.text
    rig.gates.open("drive")
    assert (await asyncio.wait_for(task, WAIT)).error_code == 0


async def test_error_codes_start_cleared_and_a_node_error_fails_only_that_goal(
    tmp_path: Path,
) -> None:
    reads_codes = (
        '<Fallback><WouldAControllerRecoveryHelp error_code="{follow_path_error_code}"/>'
        '<Gate name="drive"/></Fallback>'
    )
    broken = '<WouldAControllerRecoveryHelp error_code="{never_set}"/>'
    rig = make_rig(tmp_path, {**TREES, "Reads": reads_codes, "Broken": broken})
    task = start(rig, to_pose("reads", tree="Reads"))
    await rig.gates.wait_started("drive")  # the condition read 0: no recovery would help
    rig.gates.open("drive")
    assert (await asyncio.wait_for(task, WAIT)).error_code == 0
    result = await asyncio.wait_for(start(rig, to_pose("broken", tree="Broken")), WAIT)
    assert result.error_code == 9000
    assert "WouldAControllerRecoveryHelp" in result.error_msg
    assert "never_set" in result.error_msg
    task = start(rig, to_pose("after"))
    await rig.gates.wait_started("drive")
    rig.gates.open("drive")
    assert (await asyncio.wait_for(task, WAIT)).error_code == 0
