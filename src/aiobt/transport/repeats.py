"""One log line for an error that repeats: the first in full, then a count.

A subscriber callback that raises on every message, or a service handler that
fails on every request, would log a traceback per message (tens of thousands
of lines in seconds under a flood). :class:`RepeatedErrors` logs the first
error of a kind with its traceback, counts the later ones, and says how many
there were at most once per ``interval`` seconds (and when it is flushed).
A kind is the exception's type and where it was raised, not its text, which
often holds the failing value.

The interval is wall time: it paces log output, not robot behaviour.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from aiobt.msgs import MessageError

if TYPE_CHECKING:
    from aiobt.transport.bridge import PayloadTooLarge

Kind = tuple[str, str, int]


@dataclass(slots=True)
class _Tally:
    first: str
    count: int = 0  # since the last line about this kind
    since: float = 0.0


def kind_of(exc: BaseException) -> Kind:
    """The exception's type and the innermost frame it was raised in."""
    tb = exc.__traceback__
    while tb is not None and tb.tb_next is not None:
        tb = tb.tb_next
    if tb is None:
        return (type(exc).__qualname__, "", 0)
    return (type(exc).__qualname__, tb.tb_frame.f_code.co_filename, tb.tb_lineno)


class RepeatedErrors:
    """Logs errors of ``what`` (e.g. ``"robot/cmd_vel: subscriber callback"``) to ``logger``."""

    __slots__ = ("_clock", "_kinds", "interval", "logger", "what")

    def __init__(
        self,
        logger: logging.Logger,
        what: str,
        interval: float = 10.0,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.logger = logger
        self.what = what
        self.interval = interval
        self._clock = clock
        self._kinds: dict[Kind, _Tally] = {}

    def report(self, exc: BaseException) -> None:
        """Log ``exc`` in full if its kind is new, else count it (one line per interval)."""
        kind = kind_of(exc)
        now = self._clock()
        tally = self._kinds.get(kind)
        if tally is None:
            self._kinds[kind] = _Tally(first=f"{type(exc).__name__}: {exc}", since=now)
            self.logger.error(
                "%s failed (repeats of this error are counted, not logged each): %s",
                self.what,
                exc,
                exc_info=exc,
            )
            return
        tally.count += 1
        if now - tally.since >= self.interval:
            self._say(tally, now, exc)

    def flush(self) -> None:
        """Log the counts not yet said (e.g. when the subscription closes)."""
        now = self._clock()
        for tally in self._kinds.values():
            if tally.count:
                self._say(tally, now, None)

    def _say(self, tally: _Tally, now: float, latest: BaseException | None) -> None:
        last = f"; latest: {type(latest).__name__}: {latest}" if latest is not None else ""
        self.logger.error(
            "%s failed %d more %s in %.0f s with the same error (%s)%s",
            self.what,
            tally.count,
            "time" if tally.count == 1 else "times",
            now - tally.since,
            tally.first,
            last,
        )
        tally.count, tally.since = 0, now


class BadMessages:
    """Malformed messages dropped from one key: ``count`` of them; the first of each
    field (``<size>`` for one over the payload limit) logged as a warning on ``logger``,
    the later ones at debug level (a flood of bad messages is one line per field)."""

    __slots__ = ("_logger", "_said", "count")

    def __init__(self, logger: logging.Logger) -> None:
        self._logger = logger
        self._said: set[str] = set()
        self.count = 0

    def drop(self, exc: MessageError | PayloadTooLarge) -> None:
        self.count += 1
        tag = exc.field if isinstance(exc, MessageError) else "<size>"
        if tag in self._said:
            self._logger.debug("dropped bad message: %s", exc)
            return
        self._said.add(tag)
        self._logger.warning("dropped bad message (reported once per field): %s", exc)
