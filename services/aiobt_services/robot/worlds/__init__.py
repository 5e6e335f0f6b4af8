"""Shipped worlds (Nav2 map YAML + PGM) and the script that generates them."""

from __future__ import annotations

from pathlib import Path

WORLDS_DIR = Path(__file__).resolve().parent
OFFICE = WORLDS_DIR / "office.yaml"
SMALL = WORLDS_DIR / "small.yaml"


def world_path(name_or_path: str) -> Path:
    """A shipped world by name ("office", "small") or any map YAML path."""
    shipped = WORLDS_DIR / f"{name_or_path}.yaml"
    return shipped if shipped.is_file() else Path(name_or_path)
