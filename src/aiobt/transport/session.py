"""Opening the one Zenoh session of a process: retried while the router is absent."""

from __future__ import annotations

import asyncio
import logging
import time

import zenoh

from aiobt.transport.settings import BusSettings

log = logging.getLogger("aiobt.transport.session")
_RETRY_DELAYS = (0.1, 0.2, 0.5, 1.0)


class BusUnavailable(ConnectionError):
    """The router could not be reached within ``connect_timeout``."""


async def open_session(settings: BusSettings) -> zenoh.Session:
    """Open the session, retrying (with back-off) until the router answers.

    Gives up with :class:`BusUnavailable` after ``settings.connect_timeout``
    seconds if one is set; retries forever otherwise, logging every few seconds.
    """
    config = settings.zenoh_config()
    start = time.monotonic()
    attempt = 0
    last_log = start
    while True:
        try:
            return zenoh.open(config)
        except zenoh.ZError as exc:
            waited = time.monotonic() - start
            if settings.connect_timeout is not None and waited >= settings.connect_timeout:
                raise BusUnavailable(
                    f"cannot open the Zenoh session ({_where(settings)}) after "
                    f"{waited:.1f} s: {exc}"
                ) from None
            if attempt == 0 or time.monotonic() - last_log > 5.0:
                log.warning("Zenoh not reachable (%s), retrying: %s", _where(settings), exc)
                last_log = time.monotonic()
        delay = _RETRY_DELAYS[min(attempt, len(_RETRY_DELAYS) - 1)]
        attempt += 1
        await asyncio.sleep(delay)
        config = settings.zenoh_config()  # a Config is consumed by open()


def _where(settings: BusSettings) -> str:
    endpoints = ", ".join(settings.connect) or "default endpoints"
    return f"mode {settings.mode or 'client'}, connect {endpoints}"
