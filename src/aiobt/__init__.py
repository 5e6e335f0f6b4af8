"""aiobt: an asyncio behavior-tree runtime with BehaviorTree.CPP v4 semantics.

The names most programs need::

    from aiobt import BehaviorTreeFactory, AsyncActionNode, Status, input_port

    class Say(AsyncActionNode):
        PORTS = (input_port("message", str),)

        async def run(self) -> Status:
            print(self.get_input("message"))
            return Status.SUCCESS

    factory = BehaviorTreeFactory()
    factory.register_node_type(Say)
    tree = factory.create_tree_from_text(XML)
    await tree.tick_while_running()
"""

from aiobt.core.blackboard import Blackboard
from aiobt.core.clock import Clock, ManualClock, ScaledClock, SystemClock
from aiobt.core.composite import ControlNode, DecoratorNode
from aiobt.core.errors import BlackboardError, LogicError, NodeError, PortError, TreeLoadError
from aiobt.core.leaves import AsyncActionNode, ConditionNode, StatefulActionNode, SyncActionNode
from aiobt.core.manifest import TestNodeConfig
from aiobt.core.node import TreeNode
from aiobt.core.ports import inout_port, input_port, output_port
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.script import ScriptError, compile_script

__all__ = [
    "AsyncActionNode",
    "BehaviorTreeFactory",
    "Blackboard",
    "BlackboardError",
    "Clock",
    "ConditionNode",
    "ControlNode",
    "DecoratorNode",
    "LogicError",
    "ManualClock",
    "NodeError",
    "PortError",
    "ScaledClock",
    "ScriptError",
    "StatefulActionNode",
    "Status",
    "SyncActionNode",
    "SystemClock",
    "TestNodeConfig",
    "Tree",
    "TreeLoadError",
    "TreeNode",
    "compile_script",
    "inout_port",
    "input_port",
    "output_port",
]
