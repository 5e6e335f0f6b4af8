"""Nav2's BtActionNode leaves against in-test action servers on an in-process bus."""

from __future__ import annotations

import asyncio
import contextlib
from typing import Any

import pytest

from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.msgs import (
    ComputePathToPose,
    ComputePathToPoseError,
    FollowPath,
    GoalState,
    Path,
    PoseStamped,
    Spin,
    TrackingFeedback,
)
from aiobt.nav import register_nav2_nodes
from aiobt.testing.stubs import tree_xml
from aiobt.transport import Bus, GoalHandle

from .support import nav_tree, run_to_end, straight_path, tick_until, tick_until_true

pytestmark = pytest.mark.timeout(30)
S, F, R = Status.SUCCESS, Status.FAILURE, Status.RUNNING
GOAL = PoseStamped.from_xy_yaw(2.0, 1.0, 0.0)


def planner(bus: Bus, error: int = 0, seen: list[Any] | None = None) -> None:
    async def execute(goal: Any, handle: Any) -> Any:
        if seen is not None:
            seen.append(goal)
        if error:
            return ComputePathToPose.Result(error_code=error, error_msg="no path in this test")
        return ComputePathToPose.Result(path=straight_path(goal.goal.x))

    bus.action_server("compute_path_to_pose", ComputePathToPose, execute)


async def test_compute_path_to_pose_writes_the_path_and_a_zero_error_code(local_bus: Bus) -> None:
    seen: list[Any] = []
    planner(local_bus, seen=seen)
    tree = nav_tree(
        local_bus,
        '<ComputePathToPose goal="{goal}" path="{path}" planner_id="GridBased" '
        'error_code_id="{code}" error_msg="{msg}"/>',
        goal=GOAL,
    )
    assert await run_to_end(tree) is S
    bb = tree.root_blackboard
    assert len(bb["path"].poses) == 21
    assert (bb["code"], bb["msg"]) == (0, "")
    assert seen[0].goal == GOAL
    assert seen[0].planner_id == "GridBased"
    assert not seen[0].use_start


async def test_a_start_pose_is_used_when_given(local_bus: Bus) -> None:
    seen: list[Any] = []
    planner(local_bus, seen=seen)
    start = PoseStamped.from_xy_yaw(0.5, 0.5, 0.0)
    tree = nav_tree(local_bus, '<ComputePathToPose goal="{goal}" start="{start}"/>',
                    goal=GOAL, start=start)  # fmt: skip
    assert await run_to_end(tree) is S
    assert seen[0].use_start
    assert seen[0].start == start


async def test_viapoints_are_sent_with_the_goal(local_bus: Bus) -> None:
    seen: list[Any] = []
    planner(local_bus, seen=seen)
    via = [PoseStamped.from_xy_yaw(1.0, 0.0, 0.0), PoseStamped.from_xy_yaw(1.5, 1.0, 0.0)]
    tree = nav_tree(local_bus, '<ComputePathToPose goal="{goal}" viapoints="{via}"/>',
                    goal=GOAL, via=via)  # fmt: skip
    assert await run_to_end(tree) is S
    assert seen[0].viapoints == via
    assert seen[0].goal == GOAL


async def test_a_planner_error_goes_to_the_error_ports_and_empties_the_path(
    local_bus: Bus,
) -> None:
    planner(local_bus, error=int(ComputePathToPoseError.NO_VALID_PATH))
    tree = nav_tree(
        local_bus,
        '<ComputePathToPose goal="{goal}" path="{path}" error_code_id="{code}" error_msg="{msg}"/>',
        goal=GOAL,
        path=straight_path(),
    )
    assert await run_to_end(tree) is F
    bb = tree.root_blackboard
    assert (bb["code"], bb["msg"]) == (208, "no path in this test")
    assert bb["path"] == Path()


@pytest.mark.timeout(20)
async def test_without_a_server_it_fails_after_server_timeout_naming_the_server(
    local_bus: Bus,
) -> None:
    tree = nav_tree(
        local_bus,
        '<ComputePathToPose goal="{goal}" server_name="nobody_plans" server_timeout="300" '
        'error_code_id="{code}" error_msg="{msg}"/>',
        goal=GOAL,
    )
    loop = asyncio.get_running_loop()
    started = loop.time()
    assert await run_to_end(tree) is F
    assert 0.29 <= loop.time() - started < 3.0
    bb = tree.root_blackboard
    assert bb["code"] == ComputePathToPoseError.TIMEOUT
    assert "nobody_plans" in bb["msg"]
    assert "0.3 s" in bb["msg"]


async def test_a_server_that_is_not_running_fails_the_leaf_before_a_long_server_timeout(
    local_bus: Bus,
) -> None:
    """server_timeout (5 s here, as the navigator's) is for a busy server to accept; a
    server with no liveliness token (killed, restarting) fails the leaf after
    wait_for_service_timeout (1 s), so the tree's recoveries run."""
    tree = nav_tree(
        local_bus,
        '<ComputePathToPose goal="{goal}" server_name="dead_planner" '
        'error_code_id="{code}" error_msg="{msg}"/>',
        server_timeout=5.0,
        goal=GOAL,
    )
    loop = asyncio.get_running_loop()
    started = loop.time()
    assert await run_to_end(tree) is F
    assert loop.time() - started < 4.0  # the 5 s server_timeout was not waited out
    bb = tree.root_blackboard
    assert bb["code"] == ComputePathToPoseError.TIMEOUT
    assert "dead_planner is not running" in bb["msg"]


class SlowSpin:
    """A spin server whose goals run until canceled; records what happened."""

    def __init__(self, bus: Bus) -> None:
        self.started = asyncio.Event()
        self.cancelled = asyncio.Event()
        self.goals: list[Any] = []
        bus.action_server("spin", Spin, self.execute)

    async def execute(self, goal: Any, handle: GoalHandle[Any, Any, Any]) -> Any:
        self.goals.append(goal)
        self.started.set()
        try:
            await asyncio.Event().wait()
        except asyncio.CancelledError:
            self.cancelled.set()
            raise
        raise AssertionError("unreachable")


async def test_halt_while_running_cancels_the_goal_on_the_server(local_bus: Bus) -> None:
    server = SlowSpin(local_bus)
    tree = nav_tree(local_bus, '<Spin spin_dist="3.0" error_code_id="{code}"/>')
    assert await tick_until(tree, server.started) is R
    assert server.goals[0].target_yaw == 3.0
    client = local_bus.action_client("spin", Spin)
    await tree.halt_tree("test")  # awaits the cleanup: the cancel is acknowledged by then
    assert server.cancelled.is_set()
    assert tree.root_blackboard["code"] == 0
    assert await client.cancel_all() == []  # nothing left running on the server


async def test_spin_counts_a_recovery_per_activation(local_bus: Bus) -> None:
    async def execute(goal: Any, handle: Any) -> Any:
        return Spin.Result(total_elapsed_time=0.1)

    local_bus.action_server("spin", Spin, execute)
    tree = nav_tree(local_bus, "<Spin/>", number_recoveries=2)
    assert await run_to_end(tree) is S
    assert tree.root_blackboard["number_recoveries"] == 3
    tree = nav_tree(local_bus, '<Spin is_recovery="false"/>', number_recoveries=2)
    assert await run_to_end(tree) is S
    assert tree.root_blackboard["number_recoveries"] == 2


class Controller:
    """A follow_path server that takes newer goals over (replace) and finishes on demand."""

    def __init__(self, bus: Bus) -> None:
        self.paths: list[Path] = []
        self.got_goal = asyncio.Event()
        self.finish = asyncio.Event()
        self.executions = 0
        self.cancelled = False
        bus.action_server("follow_path", FollowPath, self.execute, preemption="replace")

    async def execute(self, goal: Any, handle: GoalHandle[Any, Any, Any]) -> Any:
        self.executions += 1
        self._take(goal.path)
        try:
            while not self.finish.is_set():
                waiter = asyncio.ensure_future(handle.wait_new_goal())
                done, _ = await asyncio.wait(
                    (waiter, asyncio.ensure_future(self.finish.wait())),
                    return_when=asyncio.FIRST_COMPLETED,
                )
                if waiter in done:
                    self._take(waiter.result().path)
                else:
                    waiter.cancel()
        except asyncio.CancelledError:
            self.cancelled = True
            raise
        return FollowPath.Result()

    def _take(self, path: Path) -> None:
        self.paths.append(path)
        self.got_goal.set()


async def test_a_new_path_while_running_goes_to_the_controller_without_a_halt(
    local_bus: Bus,
) -> None:
    controller = Controller(local_bus)
    first, second = straight_path(1.0), straight_path(2.0, y=0.5)
    tree = nav_tree(local_bus, '<FollowPath path="{path}" error_code_id="{code}"/>', path=first)
    assert await tick_until(tree, controller.got_goal) is R
    controller.got_goal.clear()
    tree.root_blackboard["path"] = first.model_copy()  # rewritten, equal: no new goal
    tree.root_blackboard["path"] = second
    assert await tick_until(tree, controller.got_goal) is R
    assert controller.paths == [first, second]
    controller.finish.set()
    assert await run_to_end(tree) is S
    assert controller.executions == 1
    assert not controller.cancelled
    assert tree.root_blackboard["code"] == 0


async def test_an_empty_new_path_keeps_the_current_one(local_bus: Bus) -> None:
    controller = Controller(local_bus)
    tree = nav_tree(local_bus, '<FollowPath path="{path}"/>', path=straight_path())
    assert await tick_until(tree, controller.got_goal) is R
    tree.root_blackboard["path"] = Path()
    for _ in range(5):
        assert await tree.tick_once() is R
    controller.finish.set()
    assert await run_to_end(tree) is S
    assert len(controller.paths) == 1


async def test_a_new_goal_while_planning_preempts_the_planner(local_bus: Bus) -> None:
    seen: list[Any] = []
    release = asyncio.Event()
    got = asyncio.Event()

    async def execute(goal: Any, handle: Any) -> Any:
        seen.append(goal.goal)
        got.set()
        await release.wait()
        return ComputePathToPose.Result(path=straight_path(goal.goal.x))

    local_bus.action_server("compute_path_to_pose", ComputePathToPose, execute)
    tree = nav_tree(local_bus, '<ComputePathToPose goal="{goal}" path="{path}"/>', goal=GOAL)
    assert await tick_until(tree, got) is R
    got.clear()
    tree.root_blackboard["goal"] = PoseStamped.from_xy_yaw(3.0, 0.0, 0.0)
    assert await tick_until(tree, got) is R
    release.set()
    assert await run_to_end(tree) is S
    assert [pose.x for pose in seen] == [2.0, 3.0]
    assert len(tree.root_blackboard["path"].poses) == 31  # the second goal's path


async def test_a_goal_the_server_rejects_fails_with_the_reason(local_bus: Bus) -> None:
    async def execute(goal: Any, handle: Any) -> Any:
        return Spin.Result()

    local_bus.action_server("spin", Spin, execute, accept=lambda goal: "busy docking")
    tree = nav_tree(local_bus, '<Spin error_code_id="{code}" error_msg="{msg}"/>')
    assert await run_to_end(tree) is F
    assert "busy docking" in tree.root_blackboard["msg"]
    assert tree.root_blackboard["code"] == 700  # Spin's UNKNOWN: our table has no GOAL_REJECTED


async def test_a_goal_canceled_by_someone_else_is_a_success(local_bus: Bus) -> None:
    server = SlowSpin(local_bus)
    tree = nav_tree(local_bus, "<Spin/>")
    assert await tick_until(tree, server.started) is R
    await local_bus.action_client("spin", Spin).cancel_all()
    assert await run_to_end(tree) is S
    assert server.cancelled.is_set()


async def test_a_bad_goal_port_fails_with_a_message_naming_it(local_bus: Bus) -> None:
    SlowSpin(local_bus)
    tree = nav_tree(local_bus, '<Spin time_allowance="-1" error_msg="{msg}"/>')
    assert await run_to_end(tree) is F
    assert "time_allowance" in tree.root_blackboard["msg"]


async def test_goal_status_on_the_server_is_canceled_after_halt(local_bus: Bus) -> None:
    server = SlowSpin(local_bus)
    statuses: list[GoalState] = []
    tree = nav_tree(local_bus, "<Spin/>")
    assert await tick_until(tree, server.started) is R
    node: Any = tree.find("Spin")
    handle = node._handle
    await tree.halt_tree()
    statuses.append(handle.status)
    assert statuses == [GoalState.CANCELED]


async def test_follow_path_writes_the_controllers_tracking_feedback(local_bus: Bus) -> None:
    finish = asyncio.Event()
    tracking = TrackingFeedback(cross_track_error=0.12, distance_to_goal=0.8)
    publisher = local_bus.publisher("tracking_feedback", TrackingFeedback)

    async def execute(goal: Any, handle: GoalHandle[Any, Any, Any]) -> Any:
        while not finish.is_set():  # as the controller: tracking, then feedback, each cycle
            publisher.put(tracking)
            handle.publish_feedback(FollowPath.Feedback(distance_to_goal=0.8))
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(finish.wait(), 0.02)
        return FollowPath.Result()

    local_bus.action_server("follow_path", FollowPath, execute)
    tree = nav_tree(local_bus, '<FollowPath path="{p}" tracking_feedback="{tf}"/>',
                    p=straight_path())  # fmt: skip
    seen = await tick_until_true(tree, lambda: "tf" in tree.root_blackboard)
    assert seen is R
    assert tree.root_blackboard["tf"] == tracking
    finish.set()
    assert await run_to_end(tree) is S
    assert tree.root_blackboard["tf"] == TrackingFeedback()  # reset when the goal ends


async def test_watching_goal_ports_creates_no_blackboard_entries(local_bus: Bus) -> None:
    controller = Controller(local_bus)
    tree = nav_tree(local_bus, '<FollowPath path="{p}"/>', p=straight_path())
    assert await tick_until(tree, controller.got_goal) is R
    assert sorted(tree.root_blackboard.keys()) == ["p"]  # no controller_id & co.
    controller.finish.set()
    assert await run_to_end(tree) is S


async def test_a_recovery_in_a_subtree_counts_on_the_root(local_bus: Bus) -> None:
    async def execute(goal: Any, handle: Any) -> Any:
        return Spin.Result()

    local_bus.action_server("spin", Spin, execute)
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory, local_bus)
    text = tree_xml('<SubTree ID="Recover"/>', "MainTree",
                    '<BehaviorTree ID="Recover"><Spin/></BehaviorTree>')  # fmt: skip
    tree = factory.create_tree_from_text(text)
    tree.root_blackboard["number_recoveries"] = 4
    assert await run_to_end(tree) is S
    assert tree.root_blackboard["number_recoveries"] == 5


async def test_a_goal_port_rewritten_with_the_same_text_builds_no_new_goal(
    local_bus: Bus, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A selector rewrites controller_id on every tick; only a change is a new goal."""
    from aiobt.nav.actions.follow_path import FollowPath as FollowPathNode

    built: list[str] = []
    make_goal = FollowPathNode.make_goal

    def counting(self: FollowPathNode) -> Any:
        built.append(self.get_input("controller_id"))
        return make_goal(self)

    monkeypatch.setattr(FollowPathNode, "make_goal", counting)
    controller = Controller(local_bus)
    xml = '<FollowPath path="{path}" controller_id="{c}"/>'
    tree = nav_tree(local_bus, xml, path=straight_path(), c="FollowPath")
    assert await tick_until(tree, controller.got_goal) is R
    controller.got_goal.clear()
    tree.root_blackboard["c"] = "FollowPath"
    assert await tree.tick_once() is R
    before = len(built)
    for _ in range(5):
        tree.root_blackboard["c"] = "FollowPath"
        assert await tree.tick_once() is R
    assert len(built) == before  # equal rewrites: no goal built
    tree.root_blackboard["c"] = "FollowPathB"
    assert await tick_until(tree, controller.got_goal) is R
    assert built[before:] == ["FollowPathB"]
    assert controller.executions == 1  # the running goal was updated, not restarted
    controller.finish.set()
    assert await run_to_end(tree) is S
