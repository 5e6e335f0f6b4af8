"""Small helpers for text a person reads."""

from __future__ import annotations


def plural(count: int, word: str, words: str = "") -> str:
    """``1 recovery``, ``2 recoveries``, ``0 goals`` (``words``: the plural, default word+s)."""
    if count == 1:
        return f"1 {word}"
    if not words:
        words = (
            word[:-1] + "ies" if word.endswith("y") and word[-2:-1] not in "aeiou" else word + "s"
        )
    return f"{count} {words}"
