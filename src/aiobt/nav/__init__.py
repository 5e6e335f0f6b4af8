"""Nav2's behavior-tree nodes bound to the Zenoh transport.

factory = BehaviorTreeFactory()
register_nav2_nodes(factory, bus)      # every node of Nav2's nav2_tree_nodes.xml
tree = factory.create_tree_from_file("navigate_to_pose_w_replanning_and_recovery.xml")
"""

from aiobt.nav.context import NavContext, NavNode
from aiobt.nav.registry import NAV2_NODES, register_nav2_nodes

__all__ = ["NAV2_NODES", "NavContext", "NavNode", "register_nav2_nodes"]
