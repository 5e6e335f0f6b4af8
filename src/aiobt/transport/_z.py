"""Typed wrappers for the few zenoh calls its stubs leave untyped."""

from __future__ import annotations

from typing import Any


def drop(query: Any) -> None:
    """End a query's reply stream (the client sees the end at once)."""
    query.drop()


def undeclare(entity: Any) -> None:
    entity.undeclare()


def close(entity: Any) -> None:
    entity.close()


def matching(status: Any) -> bool:
    """``matching_status`` is a MatchingStatus at run time (the stubs say bool)."""
    return bool(getattr(status, "matching", status))
