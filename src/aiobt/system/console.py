"""Prefixed, coloured output of the supervised services (one line per line)."""

from __future__ import annotations

import itertools
import os
import sys
from typing import TextIO

_COLOURS = ("36", "32", "33", "35", "34", "31", "96", "92")
_RESET = "\033[0m"


def wants_colour(out: TextIO, choice: str = "auto") -> bool:
    """``always``/``never``, or ``auto``: a terminal and no ``NO_COLOR`` in the environment."""
    if choice != "auto":
        return choice == "always"
    return out.isatty() and "NO_COLOR" not in os.environ


class ConsoleSink:
    """Writes ``name | text`` lines; each name gets its own colour when ``colour``."""

    def __init__(self, out: TextIO | None = None, *, colour: bool = False, width: int = 10) -> None:
        self.out = out or sys.stdout
        self.colour = colour
        self.width = width
        self._palette = itertools.cycle(_COLOURS)
        self._colours: dict[str, str] = {}

    def _prefix(self, name: str, mark: str) -> str:
        label = f"{name:>{self.width}} {mark}"
        if not self.colour:
            return label
        code = self._colours.setdefault(name, next(self._palette))
        return f"\033[{code}m{label}{_RESET}"

    def line(self, name: str, text: str) -> None:
        self.out.write(f"{self._prefix(name, '|')} {text}\n")
        self.out.flush()

    def event(self, name: str, text: str) -> None:
        """A supervisor event about ``name`` (up, crashed, restarting), marked ``*``."""
        body = f"\033[1m{text}{_RESET}" if self.colour else text
        self.out.write(f"{self._prefix(name, '*')} {body}\n")
        self.out.flush()
