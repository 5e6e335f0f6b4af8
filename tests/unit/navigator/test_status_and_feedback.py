"""The tree status stream the navigator publishes, and its feedback numbers."""

from __future__ import annotations

import asyncio
from pathlib import Path

import pytest

from aiobt.core.clock import ManualClock
from aiobt.msgs import NavigateThroughPoses, NavigateToPose
from aiobt.msgs import Path as PathMsg
from aiobt_services.navigator.progress import PathProgress, time_remaining

from .harness import WAIT, FakeChannel, make_rig, pose, through, to_pose

TWO_GATES = '<Sequence name="both"><Gate name="drive"/><Gate name="park"/></Sequence>'
TREES = {"ToPose": TWO_GATES, "ThroughPoses": '<Gate name="drive"/>'}


def straight_path(*xs: float) -> PathMsg:
    return PathMsg(poses=[pose(x, 0.0) for x in xs])


async def test_the_structure_then_transitions_per_tick_then_a_snapshot(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    task = asyncio.create_task(rig.navigator.navigate(to_pose("g"), FakeChannel()))
    await rig.gates.wait_started("drive")
    (structure,) = rig.sink.trees
    assert structure.run == 1
    assert structure.tree_id == "ToPose"
    assert structure.action == "navigate_to_pose"
    by_name = {node.name: node for node in structure.nodes}
    assert by_name["both"].parent is None
    assert by_name["both"].kind == "Control"
    assert by_name["both"].id == "Sequence"
    assert by_name["drive"].parent == by_name["both"].uid
    assert by_name["park"].parent == by_name["both"].uid
    assert by_name["drive"].id == "Gate"
    assert 'ID="ToPose"' in structure.xml
    first = rig.sink.batches[0]
    assert first.run == 1
    changes = [(t.uid, t.previous, t.status) for t in first.transitions]
    assert (by_name["both"].uid, "IDLE", "RUNNING") in changes
    assert (by_name["drive"].uid, "IDLE", "RUNNING") in changes
    during = rig.navigator.snapshot()
    statuses = {s.uid: s.status for s in during.nodes}
    assert during.state == "navigating"
    assert during.goal_id == "g"
    assert [(g.x, g.y) for g in during.goals] == [(1.0, 2.0)]  # what the web view marks
    assert statuses[by_name["drive"].uid] == "RUNNING"
    assert statuses[by_name["park"].uid] == "IDLE"
    batches_before = len(rig.sink.batches)
    rig.gates.open("drive")
    await rig.gates.wait_started("park")
    # drive's SUCCESS and park's RUNNING came in one batch, for one tick
    moved = [b for b in rig.sink.batches[batches_before:] if len(b.transitions) >= 2]
    assert moved, rig.sink.batches[batches_before:]
    rig.gates.open("park")
    await asyncio.wait_for(task, WAIT)
    final = rig.sink.snapshots[-1]
    assert final.state == "succeeded"
    assert [(g.x, g.y) for g in final.goals] == [(1.0, 2.0)]  # the last goal, once ended
    assert final.run == 1
    assert {s.status for s in final.nodes} == {"IDLE"}  # the halted tree rests


async def test_feedback_distance_time_recoveries_and_poses_remaining(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    channel = FakeChannel()
    task = asyncio.create_task(rig.navigator.navigate(through("g", (4, 0), (8, 0)), channel))
    await rig.gates.wait_started("drive")
    navigation = rig.navigator.current
    assert navigation is not None
    assert navigation.tree is not None
    blackboard = navigation.tree.root_blackboard
    rig.robot.pose, rig.robot.speed = pose(1.0, 0.2), 0.5
    blackboard.set("path", straight_path(0, 2, 4, 6, 8))
    blackboard.set("number_recoveries", 2)
    feedback = await channel.next_feedback()
    assert isinstance(feedback, NavigateThroughPoses.Feedback)
    assert feedback.distance_remaining == pytest.approx(8.0)  # from the closest segment's start
    assert feedback.estimated_time_remaining == pytest.approx(16.0)
    assert feedback.number_of_recoveries == 2
    assert feedback.number_of_poses_remaining == 2
    assert feedback.current_pose == rig.robot.pose
    assert feedback.navigation_time >= 0.0
    rig.gates.open("drive")
    await asyncio.wait_for(task, WAIT)


class WallClock:
    """``time.monotonic`` as the navigation reads it, moved by the test."""

    def __init__(self) -> None:
        self.now = 1000.0

    def monotonic(self) -> float:
        return self.now


async def test_feedback_goes_out_at_most_once_per_loop_period_of_wall_time(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The loop turns on the robot's clock (ten times a wall period at a sim speed-up of
    10); feedback goes out once per period of wall time, and at once for a newer goal."""
    wall = WallClock()
    monkeypatch.setattr("aiobt_services.navigator.navigation.time", wall)
    clock = ManualClock()
    rig = make_rig(tmp_path, TREES, clock=clock)
    channel = FakeChannel()
    task = asyncio.create_task(rig.navigator.navigate(to_pose("g"), channel))
    await rig.gates.wait_started("drive")
    navigation = rig.navigator.current
    assert navigation is not None
    period = rig.navigator.options.bt_loop_duration

    async def turns(count: int) -> None:
        """``count`` turns of the loop, each a period of robot time."""
        for _ in range(count):
            ticks = navigation.ticks
            clock.advance(period)
            async with asyncio.timeout(WAIT):
                while navigation.ticks == ticks:  # noqa: ASYNC110 - the loop turns in this loop
                    await asyncio.sleep(0)

    await turns(20)  # no wall time passed: only the first turn's feedback
    assert len(channel.feedback) == 1
    wall.now += period
    await turns(20)
    assert len(channel.feedback) == 2
    wall.now += period / 2
    await turns(5)
    assert len(channel.feedback) == 2
    channel.newer.append(to_pose("h", 3.0, 3.0))
    await turns(2)  # a newer goal's feedback goes out at once, not a period later
    assert len(channel.feedback) == 3
    assert navigation.request.goal_id == "h"
    assert navigation.ticks >= 48
    rig.gates.open("drive")
    await rig.gates.wait_started("park")
    rig.gates.open("park")
    assert (await asyncio.wait_for(task, WAIT)).error_code == 0


async def test_a_goal_before_any_robot_pose_fails_with_tf_error(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    rig.robot.pose = None
    result = await rig.navigator.navigate(to_pose("early"), FakeChannel())
    assert result.error_code == 9002
    assert "robot pose is not available" in result.error_msg
    result = await rig.navigator.navigate(through("early", (1, 1)), FakeChannel())
    assert result.error_code == 9102
    assert rig.sink.trees == []


async def test_feedback_without_a_path_has_no_distance(tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    channel = FakeChannel()
    task = asyncio.create_task(rig.navigator.navigate(to_pose("g"), channel))
    feedback = await channel.next_feedback()
    assert isinstance(feedback, NavigateToPose.Feedback)
    assert feedback.distance_remaining == 0.0
    assert feedback.estimated_time_remaining == 0.0
    assert feedback.current_pose == rig.robot.pose
    task.cancel()
    with pytest.raises(asyncio.CancelledError):
        await task


def test_path_progress_follows_the_robot_and_restarts_on_a_new_path() -> None:
    progress = PathProgress(search_window=2.0)
    path = straight_path(0, 1, 2, 3, 4, 5)
    assert progress.distance_remaining(path, pose(0.2, 0.1)) == pytest.approx(5.0)
    assert progress.distance_remaining(path, pose(1.5, 0.0)) == pytest.approx(4.0)
    assert progress.distance_remaining(path, pose(2.5, 0.0)) == pytest.approx(3.0)
    # the search covers 2 m from the last closest segment: the last segment is not seen yet
    assert progress.distance_remaining(path, pose(4.9, 0.0)) == pytest.approx(2.0)
    # and it never goes back
    assert progress.distance_remaining(path, pose(0.5, 0.0)) == pytest.approx(2.0)
    assert progress.distance_remaining(straight_path(0, 1, 2), pose(0.2, 0.0)) == pytest.approx(2.0)
    assert progress.distance_remaining(straight_path(7), pose(4.0, 4.0)) == pytest.approx(5.0)
    # a path shorter than the search window: every segment is searched
    short = straight_path(0, 0.5, 1.0)
    assert progress.distance_remaining(short, pose(0.9, 0.0)) == pytest.approx(0.5)
    assert progress.distance_remaining(short, pose(1.5, 0.0)) == pytest.approx(0.5)
    assert progress.distance_remaining(PathMsg(), pose(0, 0)) is None
    assert progress.distance_remaining(None, pose(0, 0)) is None


def test_time_remaining_needs_speed_and_distance() -> None:
    assert time_remaining(4.0, -0.5) == pytest.approx(8.0)
    assert time_remaining(4.0, 0.005) == 0.0
    assert time_remaining(0.05, 1.0) == 0.0
