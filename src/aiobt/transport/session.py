"""Opening the one Zenoh session of a process: retried while the router is absent."""

from __future__ import annotations

import asyncio
import json
import logging
import time

import zenoh

from aiobt.transport import diagnose
from aiobt.transport.settings import (
    OPEN_TIMEOUT_KEY,
    BusSettings,
    connect_endpoints,
    listen_endpoints,
)
from aiobt.transport.tls_check import TlsFiles

log = logging.getLogger("aiobt.transport.session")
_RETRY_DELAYS = (0.1, 0.2, 0.5, 1.0)


class BusUnavailable(ConnectionError):
    """The router could not be reached within ``connect_timeout``."""


async def open_session(settings: BusSettings) -> zenoh.Session:
    """Open the session, retrying (with back-off) until the router answers.

    Gives up with :class:`BusUnavailable` after ``settings.connect_timeout``
    seconds if one is set (the last attempt is made at that time); retries
    forever otherwise, logging every few seconds. Cancelling it (a service
    asked to stop while it waits for its router) ends the wait at once.

    Each attempt runs in the loop's thread: Zenoh refuses at once when nothing
    listens or the credentials are wrong, and a hung far end is given up after
    the link open timeout (``OPEN_TIMEOUT_MS``, 2 s, or less near the deadline).
    (Opening from a worker thread kept the loop free during a slow attempt but
    measurably slowed every later typed subscription, by about 0.02x-0.03x of a
    raw one-way trip in ``bench.transport.oneway``.)
    """
    start = time.monotonic()
    deadline = None if settings.connect_timeout is None else start + settings.connect_timeout
    attempt = 0
    last_log = start
    while True:
        config = settings.zenoh_config()  # a Config is consumed by open()
        if deadline is not None:  # a hung router's handshake must not outlast the deadline
            _bound_open_timeout(config, deadline - time.monotonic())
        tried = time.monotonic()
        try:
            session = zenoh.open(config)
        except zenoh.ZError as exc:
            now = time.monotonic()
            if deadline is not None and now >= deadline:
                raise BusUnavailable(
                    f"cannot open the Zenoh session ({_where(settings)}) after "
                    f"{now - start:.1f} s: {_why(config, exc, now - tried)}"
                ) from None
            if attempt == 0 or now - last_log > 5.0:
                log.warning(
                    "cannot open the Zenoh session yet (%s), retrying: %s",
                    _where(settings),
                    _why(config, exc, now - tried),
                )
                last_log = now
        else:
            log.info("Zenoh session open (%s); %s", _where(settings), _listening(config))
            return session
        delay = _RETRY_DELAYS[min(attempt, len(_RETRY_DELAYS) - 1)]
        if deadline is not None:  # the last attempt comes at the deadline, not after it
            delay = max(0.0, min(delay, deadline - time.monotonic()))
        attempt += 1
        await asyncio.sleep(delay)


def _bound_open_timeout(config: zenoh.Config, seconds: float) -> None:
    bound = max(100, int(seconds * 1000))
    if json.loads(config.get_json(OPEN_TIMEOUT_KEY)) > bound:
        config.insert_json5(OPEN_TIMEOUT_KEY, json.dumps(bound))


def _why(config: zenoh.Config, exc: zenoh.ZError, took: float) -> str:
    limit = json.loads(config.get_json(OPEN_TIMEOUT_KEY)) / 1000.0
    tls = TlsFiles.of(config)
    return diagnose.open_failure(connect_endpoints(config), str(exc), took, limit, tls)


def _listening(config: zenoh.Config) -> str:
    endpoints = listen_endpoints(config)
    return f"listening on {', '.join(endpoints)}" if endpoints else "listening nowhere"


def _where(settings: BusSettings) -> str:
    endpoints = ", ".join(settings.connect) or "default endpoints"
    return f"mode {settings.mode or 'client'}, connect {endpoints}"
