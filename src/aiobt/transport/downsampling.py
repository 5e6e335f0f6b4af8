"""Zenoh's downsampling rules from their own file, into a router's config.

A router per host sends the other host only what it needs, at the rate it needs it:
``deploy/downsampling.json5`` (the ``downsampling`` section of a Zenoh config, alone)
thins the robot's streams on the interface towards the base host (Wi-Fi), and leaves
the robot host's own services their full rate. ``aiobt router --downsampling FILE``
puts it in the router's config.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import zenoh

from aiobt.transport.diagnose import clean
from aiobt.transport.settings import BusConfigError

KEY = "downsampling"


def load_rules(path: str | Path) -> list[dict[str, Any]]:
    """The file's rules, as Zenoh reads them; :class:`BusConfigError` naming the file if
    it cannot be read, is not JSON5, or is not a valid ``downsampling`` section."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except OSError as exc:
        raise BusConfigError(f"downsampling file {path}: cannot read: {exc.strerror}") from None
    config = zenoh.Config()
    try:
        config.insert_json5(KEY, text)
    except zenoh.ZError as exc:
        raise BusConfigError(f"downsampling file {path}: {clean(str(exc))}") from None
    rules: list[dict[str, Any]] = json.loads(config.get_json(KEY))
    return rules


def insert_rules(config: zenoh.Config, path: str | Path) -> None:
    """Put the rules of ``path`` into ``config`` (replacing any it had)."""
    config.insert_json5(KEY, json.dumps(load_rules(path)))
