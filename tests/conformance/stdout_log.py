"""BehaviorTree.CPP's StdCoutLogger, captured: every status change, in order.

The logger prints one line per transition, synchronously, to the process's
standard output (file descriptor 1), e.g.
``[1795430912.104]: seq        IDLE -> RUNNING`` (the statuses in ANSI
colours). :func:`capture_fd1` points descriptor 1 at a temporary file around
one operation; :func:`parse` turns the text into ``name:PREVIOUS>STATUS``.
"""

from __future__ import annotations

import ctypes
import os
import re
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager

_LIBC = ctypes.CDLL(None)
_ANSI = re.compile(r"\x1b\[\d+m")
_LINE = re.compile(r"^\[[\d.]+\]: (\S+)\s+(\w+) -> (\w+)$")


@contextmanager
def capture_fd1(lines: list[str]) -> Iterator[None]:
    """Collect what C/C++ code writes to descriptor 1 into ``lines``."""
    with tempfile.TemporaryFile() as sink:
        _LIBC.fflush(None)
        saved = os.dup(1)
        os.dup2(sink.fileno(), 1)
        try:
            yield
        finally:
            _LIBC.fflush(None)
            os.dup2(saved, 1)
            os.close(saved)
            sink.seek(0)
            lines.extend(sink.read().decode().splitlines())


def parse(lines: list[str]) -> list[str]:
    """``name:PREVIOUS>STATUS`` for every logger line (other output is an error)."""
    transitions = []
    for line in lines:
        match = _LINE.match(_ANSI.sub("", line))
        if match is None:
            raise ValueError(f"unexpected output from BehaviorTree.CPP: {line!r}")
        name, previous, status = match.groups()
        transitions.append(f"{name}:{previous}>{status}")
    return transitions
