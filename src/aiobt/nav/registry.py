"""Nav2's node set, bound to a bus: one readable list, one registration call."""

from __future__ import annotations

import functools
import inspect
from typing import TYPE_CHECKING, Any, cast

from aiobt.core.clock import Clock
from aiobt.core.manifest import NodeBuilder, NodeManifest, ports_dict
from aiobt.core.node import TreeNode
from aiobt.nav.actions import ACTION_NODES
from aiobt.nav.cancel import CANCEL_NODES
from aiobt.nav.conditions import CONDITION_NODES
from aiobt.nav.context import NavContext, NavNode
from aiobt.nav.control import CONTROL_NODES
from aiobt.nav.decorators import DECORATOR_NODES
from aiobt.nav.path import PATH_NODES
from aiobt.nav.selectors import SELECTOR_NODES
from aiobt.nav.services import SERVICE_NODES
from aiobt.nav.state import STATE_NODES

if TYPE_CHECKING:
    from aiobt.factory import BehaviorTreeFactory
    from aiobt.transport import Bus

# Every Nav2 node class, registered under its class name (the XML ID).
# Families add their classes here as they land: actions, services, cancels,
# selectors, conditions, path utilities, decorators.
NAV2_NODES: tuple[type[TreeNode], ...] = (
    *ACTION_NODES,
    *SERVICE_NODES,
    *CANCEL_NODES,
    *SELECTOR_NODES,
    *STATE_NODES,
    *PATH_NODES,
    *DECORATOR_NODES,
    *CONTROL_NODES,
    *CONDITION_NODES,
)

# Registered under an ID other than the class name (e.g. Nav2 aliases).
NAV2_ALIASES: tuple[tuple[str, type[TreeNode]], ...] = ()


def register_nav2_nodes(
    factory: BehaviorTreeFactory,
    bus: Bus | None = None,
    *,
    namespace: str | None = None,
    clock: Clock | None = None,
    server_timeout: float | None = None,
    replace: bool = False,
) -> NavContext:
    """Register Nav2's node set on ``factory``, talking over ``bus``.

    Without a bus the trees still load and validate (``aiobt validate``), but
    a node that needs the robot's services fails on its first tick. Returns
    the shared :class:`NavContext` (its ``shared`` holds the robot-state provider).
    """
    nav = NavContext(bus=bus, namespace=namespace)
    if clock is not None:
        nav.clock = clock
    if server_timeout is not None:
        nav.server_timeout = server_timeout
    for node_id, node_class in (*((c.__name__, c) for c in NAV2_NODES), *NAV2_ALIASES):
        factory.register_manifest(_manifest(node_id, node_class, nav), replace=replace)
    return nav


def _manifest(node_id: str, node_class: type[TreeNode], nav: NavContext) -> NodeManifest:
    builder: NodeBuilder = node_class
    if issubclass(node_class, NavNode):
        builder = functools.partial(cast(Any, node_class), nav=nav)
    return NodeManifest(
        id=node_id,
        kind=node_class.KIND,
        ports=ports_dict(node_class.provided_ports()),
        builder=builder,
        description=(inspect.getdoc(node_class) or "").split("\n")[0],
        node_class=node_class,
    )
