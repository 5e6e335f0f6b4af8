"""Sessions the router refused, in its log: read back from Zenoh's own log.

Zenoh (Rust) decides whether a session's user and password are good and tells
only its log (``tracing`` lines on the process's stdout, off by default). The
router turns on just the lines about accepted TCP links and their session
handshakes, reads its stdout back (:mod:`log_tail`), and logs each refused session
with the peer's address: the first at once, then one counted line at most
every ``interval`` seconds. Zenoh's warnings and errors (every line, when
``RUST_LOG`` chose them) are passed on to the real stdout, without the Rust
source places they carry.
"""

from __future__ import annotations

import logging
import os
import re
import sys
import time
from collections.abc import Callable
from functools import partial
from typing import IO

import zenoh

from aiobt.transport.access_refusals import ACL_LOG_FILTER, TLS_LOG_FILTER, AccessRefusals
from aiobt.transport.diagnose import clean
from aiobt.transport.log_tail import LogTail

# Zenoh's warnings and errors, and the two debug lines a refusal is made of
ZENOH_LOG_FILTER = (
    "warn,zenoh_link_tcp::unicast=debug,zenoh_transport::unicast::establishment::accept=debug"
)
_ANSI = re.compile(r"\x1b\[[0-9;]*m")
_ACCEPTED = re.compile(r"Accepted TCP connection on \S+: (\S+)")
_REFUSED = re.compile(r"establishment::accept: (\w+) extension - Recv \w+\. ([^.]+)\.")
_FORWARDED = re.compile(r"\b(WARN|ERROR)\b")
_READABLE = {
    "Invalid password": "wrong password",
    "Invalid user": "unknown user",
    "Expected extension": "no user and password given",
}


class Refusals:
    """Turns Zenoh log lines into rate-limited 'refused a session' log records."""

    def __init__(
        self,
        logger: logging.Logger,
        interval: float = 10.0,
        clock: Callable[[], float] = time.monotonic,
        forward_all: bool = False,
        access: AccessRefusals | None = None,
    ) -> None:
        self.logger = logger
        self.access = access  # TLS and access-control refusals, when the router has them
        self.forward_all = forward_all  # RUST_LOG chose the lines: pass them all on
        self.interval = interval
        self._clock = clock
        self._peer = "an unknown address"
        self._unsaid = 0
        self._said_at = -float("inf")
        self.total = 0

    def on_line(self, line: str) -> str | None:
        """Note ``line``; returns the line to pass on to stdout (cleaned), if any."""
        line = _ANSI.sub("", line).rstrip("\n")
        if self.access is not None and self.access.on_line(line):
            return None
        if accepted := _ACCEPTED.search(line):
            self._peer = accepted.group(1)
            return None
        if refused := _REFUSED.search(line):
            self._refused(refused.group(1), refused.group(2))
            return None
        return clean(line) if self.forward_all or _FORWARDED.search(line) else None

    def _refused(self, method: str, reason: str) -> None:
        self.total += 1
        readable = _READABLE.get(reason, reason)
        now = self._clock()
        if now - self._said_at < self.interval:
            self._unsaid += 1
            return
        more = f" ({self._unsaid} more refused since the last report)" if self._unsaid else ""
        self.logger.warning(
            "refused a session from %s: %s (%s authentication)%s",
            self._peer,
            readable,
            method,
            more,
        )
        self._unsaid, self._said_at = 0, now


def watch_refusals(logger: logging.Logger, *, access_control: bool = False) -> Refusals:
    """Route Zenoh's log of this process through a :class:`Refusals` (call before
    opening the session; once per process: it takes over file descriptor 1 and
    points ``sys.stdout`` at a copy of the original). With ``access_control``,
    access-control denials are read too (:mod:`access_refusals`)."""
    access = AccessRefusals(logger)
    refusals = Refusals(logger, forward_all=bool(os.environ.get("RUST_LOG")), access=access)
    original = os.dup(1)
    out = os.fdopen(original, "w", buffering=1)
    sys.stdout = out
    # Zenoh writes its log from the threads that route messages: with access control, a
    # line per message. Into a file in memory, never a pipe that a busy machine lets fill
    # and then makes them wait on (:mod:`log_tail`)
    LogTail(1, partial(_pass_on, refusals, out))
    log_filter = ZENOH_LOG_FILTER + f",{TLS_LOG_FILTER}"
    zenoh.init_log_from_env_or(log_filter + f",{ACL_LOG_FILTER}" if access_control else log_filter)
    return refusals


def _pass_on(refusals: Refusals, out: IO[str], line: str) -> None:
    try:
        passed = refusals.on_line(line)
        if passed is not None:
            out.write(passed + "\n")
    except Exception:  # a log line must never stop the router's log
        refusals.logger.exception("cannot read Zenoh's log line %r", line)
