"""A navigator on stub trees: gate leaves the test opens, a fake robot, a list sink."""

from __future__ import annotations

import asyncio
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from aiobt.core.clock import Clock, SystemClock
from aiobt.core.leaves import AsyncActionNode
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.msgs import BtSnapshot, BtTransitions, BtTree, Msg, PoseStamped
from aiobt.nav import register_nav2_nodes
from aiobt_services.navigator import (
    NAVIGATE_THROUGH_POSES,
    NAVIGATE_TO_POSE,
    NavigatorOptions,
    NavRequest,
    TreeLibrary,
    TreeStatusStream,
)
from aiobt_services.navigator.navigator import Navigator

WAIT = 10.0  # s, bound of every wait on an event


class Gates:
    """Per-name events: a Gate leaf waits for its gate's result; starts and halts counted."""

    def __init__(self) -> None:
        self.results: dict[str, asyncio.Future[Status]] = {}
        self.started: dict[str, asyncio.Event] = {}
        self.halts: dict[str, int] = {}

    def _future(self, name: str) -> asyncio.Future[Status]:
        if name not in self.results or self.results[name].done():
            self.results[name] = asyncio.get_running_loop().create_future()
        return self.results[name]

    def started_event(self, name: str) -> asyncio.Event:
        return self.started.setdefault(name, asyncio.Event())

    async def wait_started(self, name: str) -> None:
        await asyncio.wait_for(self.started_event(name).wait(), WAIT)

    def open(self, name: str, status: Status = Status.SUCCESS) -> None:
        self.results[name].set_result(status)


def gate_factory(gates: Gates) -> BehaviorTreeFactory:
    class Gate(AsyncActionNode):
        """Waits until the test opens its gate (by the node's name)."""

        async def run(self) -> Status:
            result = gates._future(self.name)
            gates.started_event(self.name).set()
            try:
                return await result
            except asyncio.CancelledError:
                gates.halts[self.name] = gates.halts.get(self.name, 0) + 1
                gates.started.pop(self.name, None)
                raise

    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory)  # the trees use Nav2's conditions; no bus needed
    factory.register_node_type(Gate, "Gate")
    return factory


@dataclass
class ListSink:
    trees: list[BtTree] = field(default_factory=list)
    batches: list[BtTransitions] = field(default_factory=list)
    snapshots: list[BtSnapshot] = field(default_factory=list)

    def tree(self, message: BtTree) -> None:
        self.trees.append(message)

    def transitions(self, message: BtTransitions) -> None:
        self.batches.append(message)

    def snapshot(self, message: BtSnapshot) -> None:
        self.snapshots.append(message)


class FakeChannel:
    """The goal handle: newer goals the test pushes, the feedback the navigator publishes."""

    def __init__(self) -> None:
        self.newer: list[NavRequest] = []
        self.feedback: list[Msg] = []
        self.got_feedback = asyncio.Event()

    def take_new_request(self) -> NavRequest | None:
        return self.newer.pop() if self.newer else None

    def publish_feedback(self, feedback: Msg) -> None:
        self.feedback.append(feedback)
        self.got_feedback.set()

    async def next_feedback(self) -> Msg:
        self.got_feedback.clear()
        await asyncio.wait_for(self.got_feedback.wait(), WAIT)
        return self.feedback[-1]


def tree_xml(tree_id: str, body: str) -> str:
    return (
        f'<root BTCPP_format="4" main_tree_to_execute="{tree_id}">'
        f'<BehaviorTree ID="{tree_id}">{body}</BehaviorTree></root>'
    )


def write_trees(directory: Path, trees: dict[str, str]) -> Iterator[Path]:
    """One file per tree, named after its ID."""
    directory.mkdir(parents=True, exist_ok=True)
    for tree_id, body in trees.items():
        path = directory / f"{tree_id}.xml"
        path.write_text(tree_xml(tree_id, body))
        yield path


def pose(x: float, y: float) -> PoseStamped:
    return PoseStamped.model_validate({"x": x, "y": y, "yaw": 0.0})


@dataclass
class FakeRobot:
    pose: PoseStamped | None = field(default_factory=lambda: pose(0.0, 0.0))
    speed: float = 0.0

    def current_pose(self) -> PoseStamped | None:
        return self.pose

    def linear_speed(self) -> float:
        return self.speed

    async def wait_for_pose(self, timeout: float) -> bool:  # noqa: ASYNC109
        return self.pose is not None


def to_pose(goal_id: str, x: float = 1.0, y: float = 2.0, tree: str = "") -> NavRequest:
    return NavRequest(NAVIGATE_TO_POSE, goal_id, (pose(x, y),), tree)


def through(goal_id: str, *points: tuple[float, float], tree: str = "") -> NavRequest:
    return NavRequest(NAVIGATE_THROUGH_POSES, goal_id, tuple(pose(x, y) for x, y in points), tree)


@dataclass
class Rig:
    navigator: Navigator
    gates: Gates
    sink: ListSink
    robot: FakeRobot
    tree_dir: Path


def make_rig(
    tmp_path: Path,
    trees: dict[str, str],
    btlog_dir: Path | None = None,
    clock: Clock | None = None,
    clock_timeout: float | None = None,
) -> Rig:
    """A navigator whose trees (by ID; files in ``tmp_path/trees``) run Gate leaves.

    The default trees are ``ToPose`` and ``ThroughPoses`` (both must be in ``trees``).
    """
    gates, sink, robot = Gates(), ListSink(), FakeRobot()
    tree_dir = tmp_path / "trees"
    list(write_trees(tree_dir, trees))
    library = TreeLibrary(gate_factory(gates), [tree_dir])
    settings = NavigatorOptions(
        default_to_pose_tree="ToPose",
        default_through_poses_tree="ThroughPoses",
        btlog_dir=btlog_dir,
        clock_timeout=clock_timeout,
    )
    stream = TreeStatusStream(sink)
    navigator = Navigator(library, robot, clock or SystemClock(), stream, settings)
    return Rig(navigator, gates, sink, robot, tree_dir)
