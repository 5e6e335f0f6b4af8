"""The navigator's tree status stream (``{ns}/bt/...``), for monitors.

Three keys, all JSON (see docs/navigator.md):

- ``{ns}/bt/tree`` (latched): :class:`BtTree`, the structure of the tree the
  navigator loaded last: one :class:`BtNode` per node, depth first in uid order,
  each with its parent's uid. Published when a navigation starts a new tree.
- ``{ns}/bt/transitions``: :class:`BtTransitions`, the status changes of one
  tick (one message per tick that changed something, never one per change).
- ``{ns}/bt/snapshot``: :class:`BtSnapshot`, every node's status and the
  navigation's state, periodically (1 Hz by default) and when a navigation
  ends, so that a monitor joining late catches up without replaying history.

``run`` ties the three together: it increases by one each time the navigator
instantiates a tree, and transitions or snapshots whose ``run`` differs from
the structure's ``run`` belong to another tree instance (drop them, or wait for
the structure, which is latched).
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from aiobt.msgs._base import Msg
from aiobt.msgs.geometry import PoseStamped

StatusName = Literal["IDLE", "RUNNING", "SUCCESS", "FAILURE", "SKIPPED"]
"""A node status as BT.CPP names it (``aiobt.core.Status`` member names)."""

NodeKindName = Literal["Action", "Condition", "Control", "Decorator", "SubTree"]
NavigationState = Literal["idle", "navigating", "succeeded", "aborted", "canceled"]


class BtNode(Msg):
    """One node of the instantiated tree.

    ``uid`` is the uid in ``.btlog`` files and Groot2 (unique in one tree
    instance); ``parent`` is the parent's uid (None for the root); ``path`` the
    node's path (``MainTree/NavigateRecovery/...``); ``id`` its registration ID
    (``ComputePathToPose``); ``name`` its XML ``name`` (the ID when unnamed).
    """

    uid: int = Field(ge=0)
    parent: int | None = None
    path: str
    id: str
    name: str
    kind: NodeKindName


class BtTree(Msg):
    """The structure of one tree instance (latched on ``{ns}/bt/tree``).

    ``tree_id`` is the main tree's ID, ``source`` the file it came from (or a
    registered tree ID), ``action`` the action the navigation came through
    (``navigate_to_pose`` or ``navigate_through_poses``), ``stamp`` the clock
    time the tree was loaded; ``xml`` the tree as instantiated with ``_uid``
    attributes (the XML a ``.btlog`` file carries, Groot2 reads it).
    """

    run: int = Field(ge=0)
    tree_id: str
    source: str = ""
    action: str = ""
    stamp: float = 0.0
    nodes: list[BtNode]
    xml: str = ""


class BtTransition(Msg):
    """One status change of one node, at clock time ``stamp``."""

    uid: int = Field(ge=0)
    previous: StatusName
    status: StatusName
    stamp: float = 0.0


class BtTransitions(Msg):
    """The status changes of one tick of tree instance ``run``, in order."""

    run: int = Field(ge=0)
    stamp: float = 0.0
    transitions: list[BtTransition]


class BtNodeStatus(Msg):
    """The current status of one node."""

    uid: int = Field(ge=0)
    status: StatusName


class BtSnapshot(Msg):
    """Every node's status and the navigation around it (``{ns}/bt/snapshot``).

    ``state`` is the navigation's state (``idle`` before the first goal);
    ``goal_id`` the navigation action's goal id (empty between navigations);
    ``ticks`` the number of root ticks of this run so far; ``error_code`` and
    ``error_msg`` the result of the navigation once it has ended; ``goals`` the
    pose(s) of the goal being driven to (or of the last one, once it ended).
    """

    run: int = Field(ge=0)
    tree_id: str = ""
    stamp: float = 0.0
    state: NavigationState = "idle"
    action: str = ""
    goal_id: str = ""
    ticks: int = Field(default=0, ge=0)
    number_of_recoveries: int = Field(default=0, ge=0)
    distance_remaining: float = Field(default=0.0, ge=0.0)
    error_code: int = Field(default=0, ge=0, le=65535)
    error_msg: str = ""
    goals: list[PoseStamped] = Field(default_factory=list)
    nodes: list[BtNodeStatus]
