"""Errors of the script language: syntax errors (load time) and runtime errors."""

from __future__ import annotations

from aiobt.core.errors import BehaviorTreeError


class ScriptError(BehaviorTreeError):
    """A script failed while running: unknown key, bad types, bad assignment."""


class ScriptSyntaxError(ScriptError):
    """A script could not be parsed; ``column`` is 1-based."""

    def __init__(self, message: str, script: str, column: int) -> None:
        self.message = message
        self.script = script
        self.column = column
        super().__init__(f"column {column}: {message}")

    def pointer(self) -> str:
        """The script with a caret under the column, for display."""
        return f"{self.script}\n{' ' * (self.column - 1)}^"
