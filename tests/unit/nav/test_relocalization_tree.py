"""aiobt's relocalizing navigate-to-pose tree (issue 33's kidnapped robot) builds with
the real Nav2 nodes, relocalizes in its recovery round, and relocalizes again in the
next round when the first relocalization did not find the robot."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.msgs import (
    ActionResult,
    BackUp,
    ClearCostmapResponse,
    ClearEntireCostmap,
    ComputePathToPose,
    Empty,
    FollowPath,
    PoseStamped,
    ReinitializeGlobalLocalization,
    Spin,
    Wait,
)
from aiobt.msgs import Path as NavPath
from aiobt.nav import register_nav2_nodes
from aiobt.nav.conditions import AreErrorCodesPresent
from aiobt.transport import Bus
from aiobt.xml.model import UnimplementedControl, UnimplementedDecorator, UnimplementedNode

from .support import run_to_end, straight_path

TREE = (Path(__file__).resolve().parents[3] / "trees"
        / "navigate_to_pose_w_relocalization_and_recovery.xml")  # fmt: skip
PLACEHOLDERS = (UnimplementedNode, UnimplementedControl, UnimplementedDecorator)
LOST = 104  # PATIENCE_EXCEEDED: the controller's "collision ahead" at a wall the estimate lacks


def test_builds_with_real_nodes_and_relocalizes_turns_in_steps_then_clears_in_the_round() -> None:
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory)
    tree = factory.create_tree_from_file(TREE)
    nodes = list(tree.nodes())
    assert [n.path for n in nodes if isinstance(n, PLACEHOLDERS)] == []
    (round_robin,) = [n for n in nodes if n.config.registration_id == "RoundRobin"]
    (relocalize,) = [n for n in round_robin.children_nodes() if n.name == "Relocalize"]
    steps = relocalize.children_nodes()
    assert [s.config.registration_id for s in steps] == [
        "ReinitializeGlobalLocalization",
        "Repeat",
        "ClearEntireCostmap",
        "ClearEntireCostmap",
    ]
    # a whole turn (every side seen) in steps a little over update_min_a (0.1 rad),
    # still after each: one filter update per step, however slowly the service reads
    turn = steps[1]
    cycles = int(turn.config.inputs["num_cycles"].text)
    (step,) = turn.children_nodes()
    spin, wait = step.children_nodes()
    assert spin.config.registration_id == "Spin"
    assert wait.config.registration_id == "Wait"
    spin_dist = float(spin.config.inputs["spin_dist"].text)
    assert 0.1 < spin_dist <= 0.2
    assert cycles * spin_dist == pytest.approx(6.28, abs=0.05)
    assert float(wait.config.inputs["wait_duration"].text) >= 0.6
    # then the obstacles laid in map from the wrong estimate go, from both costmaps
    assert sorted(s.config.inputs["service_name"].text for s in steps[2:]) == [
        "global_costmap/clear_entirely_global_costmap",
        "local_costmap/clear_entirely_local_costmap",
    ]


def test_the_round_also_runs_on_start_or_goal_occupied() -> None:
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory)
    tree = factory.create_tree_from_file(TREE)
    (gate,) = [n for n in tree.nodes() if n.name == "LostRobotPlannerCodes"]
    assert isinstance(gate, AreErrorCodesPresent)
    for code, runs in ((205, True), (206, True), (204, False), (0, False)):
        tree.root_blackboard["compute_path_error_code"] = code
        assert gate.check() is runs, code


class LostRobot:
    """The stack's servers for a robot the filter has lost: the controller fails (a
    wall where the estimate has none) until the ``found_by``-th global
    relocalization has found it; every behavior, clear and relocalization succeeds.
    ``events`` is what the servers saw, in order."""

    def __init__(self, bus: Bus, found_by: int) -> None:
        self.found_by = found_by
        self.events: list[str] = []
        bus.action_server("compute_path_to_pose", ComputePathToPose, self._plan)
        bus.action_server("follow_path", FollowPath, self._follow)
        for action in (Spin, Wait, BackUp):
            bus.action_server(action.name, action, self._behavior(action.__name__))
        bus.serve("reinitialize_global_localization", Empty,
                  ReinitializeGlobalLocalization.Response, self._relocalize)  # fmt: skip
        for costmap in ("local", "global"):
            bus.serve(f"{costmap}_costmap/clear_entirely_{costmap}_costmap",
                      ClearEntireCostmap.Request, ClearCostmapResponse,
                      self._clear(costmap))  # fmt: skip

    @property
    def relocalizations(self) -> int:
        return self.events.count("Relocalize")

    def recoveries(self) -> list[str]:
        """The outer round's recoveries: each relocalization, back-up, and clearing of
        both costmaps (the controller's own retry clears only the local one)."""
        kinds = {"Relocalize", "BackUp", "Clearglobal"}
        return [e for e in self.events if e in kinds]

    async def _plan(self, goal: Any, handle: Any) -> Any:
        return ComputePathToPose.Result(path=straight_path(2.0))

    async def _follow(self, goal: Any, handle: Any) -> Any:
        if self.relocalizations >= self.found_by:
            return ActionResult()
        return ActionResult(error_code=LOST, error_msg="collision ahead")

    def _behavior(self, name: str) -> Any:
        async def run(goal: Any, handle: Any) -> Any:
            self.events.append(name)
            return Spin.Result()

        return run

    def _relocalize(self, request: Any) -> Any:
        self.events.append("Relocalize")
        return ReinitializeGlobalLocalization.Response(ok=True, message="")

    def _clear(self, costmap: str) -> Any:
        def handle(request: Any) -> Any:
            self.events.append(f"Clear{costmap}")
            return ClearCostmapResponse(success=True, message="")

        return handle


async def navigate(bus: Bus) -> Status:
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory, bus)
    tree = factory.create_tree_from_file(TREE)
    tree.root_blackboard["goal"] = PoseStamped.from_xy_yaw(2.0, 0.0, 0.0)
    tree.root_blackboard["path"] = NavPath()
    return await run_to_end(tree, 30.0)


ROUND = ["Clearglobal", "Relocalize", "Clearglobal", "BackUp"]  # clear, relocalize, back up


@pytest.mark.timeout(60)
@pytest.mark.parametrize("found_by", [1, 2])
async def test_a_lost_robot_is_relocalized_in_each_round_until_found(
    local_bus: Bus, found_by: int
) -> None:
    # found_by 2 is the CI failure of 86b1f8d: the turn settled on a look-alike place,
    # and the round, not wrapping around (Nav2's RoundRobin default), ended the goal
    robot = LostRobot(local_bus, found_by)
    assert await navigate(local_bus) is Status.SUCCESS
    assert robot.recoveries() == (found_by - 1) * ROUND + ROUND[:3]
    assert robot.events.count("Spin") == 42 * found_by  # each relocalizing turn's steps


@pytest.mark.timeout(60)
async def test_a_robot_never_found_ends_with_a_failure_after_the_retries(local_bus: Bus) -> None:
    robot = LostRobot(local_bus, found_by=1_000)
    assert await navigate(local_bus) is Status.FAILURE
    assert robot.recoveries() == ROUND + ROUND  # six retries of a round of three
