"""A console transition logger (BT.CPP's StdCoutLogger), through ``logging``."""

from __future__ import annotations

import logging
from typing import TextIO

from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.loggers.observer import StatusObserver

_COLORS = {
    Status.IDLE: "\x1b[36m",
    Status.RUNNING: "\x1b[33m",
    Status.SUCCESS: "\x1b[32m",
    Status.FAILURE: "\x1b[31m",
    Status.SKIPPED: "\x1b[34m",
}
_RESET = "\x1b[0m"


def status_text(status: Status, color: bool = False) -> str:
    return f"{_COLORS[status]}{status.name}{_RESET}" if color else status.name


class ConsoleLogger(StatusObserver):
    """One line per transition: ``[stamp]: name  PREVIOUS -> STATUS``.

    Lines go to ``stream`` if given, else to the ``aiobt.transitions`` logger
    at INFO. ``show_idle=False`` leaves out transitions back to IDLE;
    ``color=True`` adds ANSI colors as BT.CPP does.
    """

    def __init__(
        self,
        tree: Tree,
        stream: TextIO | None = None,
        *,
        show_idle: bool = True,
        color: bool = False,
        logger: logging.Logger | None = None,
    ) -> None:
        self.stream = stream
        self.show_idle = show_idle
        self.color = color
        self.logger = logger or logging.getLogger("aiobt.transitions")
        super().__init__(tree)

    def on_transition(self, stamp: float, node: TreeNode, previous: Status, status: Status) -> None:
        if status is Status.IDLE and not self.show_idle:
            return
        line = (
            f"[{stamp:.3f}]: {node.name:<25} "
            f"{status_text(previous, self.color)} -> {status_text(status, self.color)}"
        )
        if self.stream is not None:
            self.stream.write(line + "\n")
        else:
            self.logger.info("%s", line)

    def flush(self) -> None:
        if self.stream is not None:
            self.stream.flush()
