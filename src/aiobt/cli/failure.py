"""A command's failure as one line for the person at the terminal: what, and what next."""

from __future__ import annotations

from aiobt.transport import BusUnavailable, ServerUnavailable

NO_ROUTER_NEXT = "start it with `aiobt up`, or point at one with --connect ENDPOINT"
NO_NAVIGATOR_NEXT = "is the navigator up? `aiobt status` lists what is, `aiobt up` starts it"


def failure(command: str, exc: BaseException) -> str:
    """``aiobt {command}: {exc}``, with the next step when it is known (no router, no
    navigator)."""
    text = f"aiobt {command}: {exc}"
    if isinstance(exc, BusUnavailable) and "no router at" in str(exc):
        text += f"; {NO_ROUTER_NEXT}"
    elif isinstance(exc, ServerUnavailable) or "no subscriber (navigator)" in str(exc):
        text += f"; {NO_NAVIGATOR_NEXT}"
    return text
