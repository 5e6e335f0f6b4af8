"""Typed wrappers for the few zenoh calls its stubs leave untyped."""

from __future__ import annotations

import time
from typing import Any

BORROW_RETRIES = 200  # x 1 ms: a Zenoh thread's callback on the entity ends well within


def drop(query: Any) -> None:
    """End a query's reply stream (the client sees the end at once)."""
    query.drop()


def undeclare(entity: Any) -> None:
    """Undeclare; while a Zenoh thread's callback still holds the entity (zenoh-python
    raises "Already borrowed", seen closing a publisher whose matching listener was
    reporting), wait a millisecond and try again."""
    for _ in range(BORROW_RETRIES):
        try:
            entity.undeclare()
            return
        except RuntimeError as exc:
            if "Already borrowed" not in str(exc):
                raise
            time.sleep(0.001)
    entity.undeclare()


def close(entity: Any) -> None:
    entity.close()


def matching(status: Any) -> bool:
    """``matching_status`` is a MatchingStatus at run time (the stubs say bool)."""
    return bool(getattr(status, "matching", status))
