"""Compiled scripts and the condition-attribute compiler the factory installs."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

from aiobt.core.blackboard import Blackboard
from aiobt.core.errors import NodeError
from aiobt.script.compiler import Compiled, compile_expr
from aiobt.script.errors import ScriptError
from aiobt.script.parser import parse
from aiobt.script.values import truth

if TYPE_CHECKING:
    from aiobt.core.node import TreeNode

NO_ENUMS: Mapping[str, int] = MappingProxyType({})
PRE_CONDITIONS = frozenset({"_failureIf", "_successIf", "_skipIf", "_while"})


class Script:
    """A script compiled once; calling it runs every statement, returns the last value."""

    __slots__ = ("_run", "source")

    def __init__(self, source: str) -> None:
        self.source = source
        steps = [compile_expr(expr) for expr in parse(source)]
        self._run = steps[0] if len(steps) == 1 else _sequence(steps)

    def __call__(self, blackboard: Blackboard, enums: Mapping[str, int] = NO_ENUMS) -> Any:
        return self._run(blackboard, enums)

    def check(self, blackboard: Blackboard, enums: Mapping[str, int] = NO_ENUMS) -> bool:
        """Run and read the result as a condition (BT.CPP's ``cast<bool>``)."""
        return truth(self._run(blackboard, enums))

    def __repr__(self) -> str:
        return f"Script({self.source!r})"


def _sequence(steps: list[Compiled]) -> Compiled:
    *head, last = steps

    def run(bb: Blackboard, enums: Mapping[str, int]) -> Any:
        for step in head:
            step(bb, enums)
        return last(bb, enums)

    return run


def compile_script(source: str) -> Script:
    """Parse and compile ``source``; raises :class:`ScriptSyntaxError` with the column."""
    return Script(source)


def run_script(source: str, blackboard: Blackboard, enums: Mapping[str, int] = NO_ENUMS) -> Any:
    """Compile and run ``source`` once (tests, REPL); prefer :func:`compile_script`."""
    return Script(source)(blackboard, enums)


def node_error(node: TreeNode, where: str, exc: ScriptError) -> NodeError:
    return NodeError(node.path, ScriptError(f"{where}: {exc}"))


def compile_condition(source: str, attribute: str) -> Callable[[TreeNode], Any]:
    """The factory's ``script_compiler``: a node attribute such as ``_skipIf``.

    Pre-conditions give a bool (BT.CPP's cast rules); post-conditions give the
    script's value. Runtime errors name the node, the attribute and the script.
    """
    script = Script(source)
    where = f'{attribute}="{source}"'
    if attribute in PRE_CONDITIONS:

        def check(node: TreeNode) -> bool:
            try:
                return script.check(node.config.blackboard, node.config.context.enums)
            except ScriptError as exc:
                raise node_error(node, where, exc) from exc

        return check

    def run(node: TreeNode) -> Any:
        try:
            return script(node.config.blackboard, node.config.context.enums)
        except ScriptError as exc:
            raise node_error(node, where, exc) from exc

    return run
