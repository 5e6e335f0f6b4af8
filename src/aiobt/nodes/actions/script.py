"""Script: run a piece of BT.CPP script code, always SUCCESS."""

from __future__ import annotations

from typing import Any

from aiobt.core.leaves import SyncActionNode
from aiobt.core.node import TreeNode
from aiobt.core.ports import input_port
from aiobt.core.status import Status
from aiobt.script import Script as CompiledScript
from aiobt.script import ScriptError, compile_script


class ScriptCode:
    """A script port (``code``, ``if``): compiled at load when it is a literal,
    else (a ``{key}``) compiled when first read and again whenever it changes.

    An action's empty code does nothing (BT.CPP); a ``condition``'s is an error.
    """

    __slots__ = ("_compiled", "_condition", "_literal", "_node", "_port", "_text")

    def __init__(self, node: TreeNode, *, condition: bool, port: str = "code") -> None:
        self._node = node
        self._port = port
        self._condition = condition
        self._text: str | None = None
        self._compiled: CompiledScript | None = None
        self._literal: str | None = None  # the code, when it is fixed at load
        binding = node.config.inputs.get(port)
        if binding is not None and binding.key is None:
            self._literal = text = str(binding.value)
            if text or condition:
                self._load(text)

    def _load(self, text: str) -> None:
        try:
            self._compiled = compile_script(text)
        except ScriptError as exc:
            raise ScriptError(f'{self._port}="{text}": {exc}') from exc
        self._text = text

    def run(self) -> Any:
        """Run the code; a condition's value, or None (empty code)."""
        node = self._node
        text = self._literal
        if text is None:
            text = str(node.get_input(self._port))
            if text != self._text and (text or self._condition):
                self._load(text)
        compiled = self._compiled
        if compiled is None or not text:
            return None
        bb, enums = node.config.blackboard, node.config.context.enums
        try:
            return compiled.check(bb, enums) if self._condition else compiled(bb, enums)
        except ScriptError as exc:
            raise node.logic_error(f'{self._port}="{text}": {exc}') from exc


class Script(SyncActionNode):
    """``<Script code="count := 0; msg := 'go'"/>``: run the code, SUCCESS.

    - the code is compiled when the tree is loaded (errors name the column);
    - an empty ``code`` does nothing, as in BT.CPP;
    - a runtime error (unknown key, bad types) raises, naming the node.
    """

    __slots__ = ("_code",)
    PORTS = (input_port("code", str, description="Piece of code that can be parsed"),)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._code = ScriptCode(self, condition=False)

    def on_tick(self) -> Status:
        self._code.run()
        return Status.SUCCESS
