"""The built-in node set: BehaviorTree.CPP v4's standard nodes."""

from __future__ import annotations

from typing import TYPE_CHECKING

from aiobt.core.node import TreeNode
from aiobt.nodes.actions.always import AlwaysFailure, AlwaysSuccess
from aiobt.nodes.actions.script import Script
from aiobt.nodes.actions.set_blackboard import SetBlackboard
from aiobt.nodes.actions.sleep import Sleep
from aiobt.nodes.actions.unset_blackboard import UnsetBlackboard
from aiobt.nodes.actions.was_entry_updated import WasEntryUpdated
from aiobt.nodes.conditions.script_condition import ScriptCondition
from aiobt.nodes.control.fallback import AsyncFallback, Fallback
from aiobt.nodes.control.if_then_else import IfThenElse
from aiobt.nodes.control.parallel import Parallel
from aiobt.nodes.control.parallel_all import ParallelAll
from aiobt.nodes.control.reactive_fallback import ReactiveFallback
from aiobt.nodes.control.reactive_sequence import ReactiveSequence
from aiobt.nodes.control.sequence import AsyncSequence, Sequence
from aiobt.nodes.control.sequence_with_memory import SequenceWithMemory
from aiobt.nodes.control.switch import Switch2, Switch3, Switch4, Switch5, Switch6
from aiobt.nodes.control.try_catch import TryCatch
from aiobt.nodes.control.while_do_else import WhileDoElse
from aiobt.nodes.decorators.delay import Delay
from aiobt.nodes.decorators.entry_updated import SkipUnlessUpdated, WaitValueUpdate
from aiobt.nodes.decorators.force import ForceFailure, ForceSuccess
from aiobt.nodes.decorators.inverter import Inverter
from aiobt.nodes.decorators.keep_running_until_failure import KeepRunningUntilFailure
from aiobt.nodes.decorators.loop import LoopBool, LoopDouble, LoopInt, LoopString
from aiobt.nodes.decorators.precondition import Precondition
from aiobt.nodes.decorators.repeat import Repeat
from aiobt.nodes.decorators.retry import RetryUntilSuccessful
from aiobt.nodes.decorators.run_once import RunOnce
from aiobt.nodes.decorators.timeout import Timeout

if TYPE_CHECKING:
    from aiobt.factory import BehaviorTreeFactory

BUILTINS: tuple[type[TreeNode], ...] = (
    # control
    Sequence, SequenceWithMemory, ReactiveSequence, AsyncSequence,
    Fallback, ReactiveFallback, AsyncFallback,
    Parallel, ParallelAll, IfThenElse, WhileDoElse,
    Switch2, Switch3, Switch4, Switch5, Switch6,
    # decorators
    Inverter, ForceSuccess, ForceFailure, KeepRunningUntilFailure,
    RetryUntilSuccessful, Repeat, Timeout, Delay, RunOnce,
    # leaves
    AlwaysSuccess, AlwaysFailure, SetBlackboard, UnsetBlackboard, Sleep,
    # scripting and the language's own nodes
    Script, ScriptCondition, Precondition, SkipUnlessUpdated, WaitValueUpdate,
    WasEntryUpdated, LoopInt, LoopDouble, LoopString, LoopBool, TryCatch,
)  # fmt: skip

# Built-ins registered under an ID other than their class name.
EXTENSIONS: list[tuple[str, type[TreeNode]]] = []


def register_builtins(factory: BehaviorTreeFactory) -> None:
    for node_class in BUILTINS:
        factory.register_node_type(node_class, builtin=True)
    for node_id, node_class in EXTENSIONS:
        factory.register_node_type(node_class, node_id, builtin=True)
