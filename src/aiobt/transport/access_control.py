"""Zenoh's access-control rules from their own file, into a router's config.

The rules of a deployment live in one JSON5 file (deploy/access-control.json5: the
``access_control`` section of a Zenoh config, alone), so both routers and the docs
share them; ``aiobt router --access-control FILE`` puts them in the router's config.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import zenoh

from aiobt.transport.diagnose import clean
from aiobt.transport.settings import BusConfigError

KEY = "access_control"


def load_rules(path: str | Path) -> dict[str, Any]:
    """The file's rules, as Zenoh reads them; :class:`BusConfigError` naming the file if
    it cannot be read, is not JSON5, or is not a valid ``access_control`` section."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except OSError as exc:
        raise BusConfigError(f"access-control file {path}: cannot read: {exc.strerror}") from None
    config = zenoh.Config()
    try:
        config.insert_json5(KEY, text)
    except zenoh.ZError as exc:
        raise BusConfigError(f"access-control file {path}: {clean(str(exc))}") from None
    rules: dict[str, Any] = json.loads(config.get_json(KEY))
    if not rules.get("enabled"):
        raise BusConfigError(f"access-control file {path}: enabled is not true, it would not apply")
    return rules


def insert_rules(config: zenoh.Config, path: str | Path) -> None:
    """Put the rules of ``path`` into ``config`` (replacing any it had)."""
    config.insert_json5(KEY, json.dumps(load_rules(path)))


def enabled(config: zenoh.Config) -> bool:
    """Whether ``config`` (a router's) enforces access control."""
    return json.loads(config.get_json(f"{KEY}/enabled")) is True
