"""``aiobt monitor --plain``: what the tree does, a line per change a person cares about.

Every transition of every node (a replanning tree makes some 30 a second) is
too much to read, so :class:`PlainLog` writes:

- the tree when a new one starts, and what the times mean;
- the navigation's state (a new goal, succeeded, aborted with Nav2's error);
- each recovery, as the navigator counts them;
- a leaf (action or condition) when it starts RUNNING after a failure or for
  the first time in this goal, and when it ends differently from its last end
  (a replanning every second that succeeds again says nothing new).

Nodes are named by ID (and XML name when it has one), times are seconds of
robot time since the goal began.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from aiobt.msgs.bt import BtNode, BtSnapshot, BtTree

LEAVES = ("Action", "Condition")


def label(node: BtNode) -> str:
    """``ComputePathToPose``, or ``ClearEntireCostmap [ClearGlobalCostmap-Context]``."""
    return node.id if node.name == node.id else f"{node.id} [{node.name}]"


@dataclass(slots=True)
class PlainLog:
    """Turns the status stream into the lines above (pure: the caller writes them)."""

    started: float | None = None  # robot time the current goal began
    goal_id: str = ""
    state: str = ""
    recoveries: int = 0
    _ended: dict[int, str] = field(default_factory=dict)  # uid -> last SUCCESS/FAILURE
    _running: set[int] = field(default_factory=set)

    def on_tree(self, tree: BtTree) -> list[str]:
        self._new_goal()
        source = f" from {tree.source}" if tree.source else ""
        return [
            f"tree {tree.tree_id} (run {tree.run}, {len(tree.nodes)} nodes){source}",
            "  (times: seconds since the goal began, robot time)",
        ]

    def on_transition(self, node: BtNode, status: str, stamp: float) -> str | None:
        if node.kind not in LEAVES:
            return None
        if self.started is None:
            self.started = stamp
        if status == "RUNNING":
            if node.uid in self._running or self._ended.get(node.uid) == "SUCCESS":
                return None
            self._running.add(node.uid)
        elif status in ("SUCCESS", "FAILURE"):
            self._running.discard(node.uid)
            if self._ended.get(node.uid) == status:
                return None
            self._ended[node.uid] = status
        else:
            return None  # IDLE (reset or halted), SKIPPED
        return self._line(stamp, f"{status:<8} {label(node)}")

    def on_snapshot(self, shot: BtSnapshot) -> list[str]:
        lines: list[str] = []
        if shot.goal_id != self.goal_id and shot.state == "navigating":
            self._new_goal(shot.stamp)
            self.goal_id = shot.goal_id
            lines.append(self._line(shot.stamp, f"navigating: {shot.action} goal {shot.goal_id}"))
        if shot.number_of_recoveries > self.recoveries and shot.state == "navigating":
            lines.append(self._line(shot.stamp, f"recovery {shot.number_of_recoveries}"))
        self.recoveries = shot.number_of_recoveries
        if shot.state != self.state and shot.state not in ("navigating", "idle"):
            error = f": error {shot.error_code} {shot.error_msg}" if shot.error_code else ""
            ended = f"navigation {shot.state}{error}"
            if self.started is None:  # it ended before this monitor saw it run
                lines.append(f"the last {ended}")
            else:
                lines.append(self._line(shot.stamp, ended))
        self.state = shot.state
        return lines

    def _new_goal(self, stamp: float | None = None) -> None:
        self.started = stamp
        self.recoveries = 0
        self._ended.clear()
        self._running.clear()

    def _line(self, stamp: float, text: str) -> str:
        since = stamp - self.started if self.started is not None else 0.0
        return f"{since:7.1f} s  {text}"
