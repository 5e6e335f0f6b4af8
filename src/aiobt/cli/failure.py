"""A command's failure as one line for the person at the terminal: what, and what next."""

from __future__ import annotations

from aiobt.transport import BusUnavailable

NO_ROUTER_NEXT = "start it with `aiobt up`, or point at one with --connect ENDPOINT"


def failure(command: str, exc: BaseException) -> str:
    """``aiobt {command}: {exc}``, with the next step when it is known (no router)."""
    text = f"aiobt {command}: {exc}"
    if isinstance(exc, BusUnavailable) and "no router at" in str(exc):
        text += f"; {NO_ROUTER_NEXT}"
    return text
