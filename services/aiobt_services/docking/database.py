"""The dock database (Nav2's ``dock_database`` file): dock instances by name.

    docks:
      home_dock:
        type: simple_charging_dock   # the dock plugin; may be empty with one plugin
        frame: map                   # default map
        pose: [0.49, 9.75, 3.14159]  # x, y, theta
        id: "tag_0"                  # optional, e.g. the fiducial's id

Parsed from the YAML's nodes, so that every problem names the file, the line and the
dock (:class:`~.errors.DockDatabaseError`); a shipped world's name (``office``,
``small``) stands for its database in ``databases/``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import yaml

from aiobt.geometry import Pose2D

from .errors import DockDatabaseError

DATABASES_DIR = Path(__file__).resolve().parent / "databases"
KEYS = ("type", "frame", "pose", "id")


@dataclass(slots=True, frozen=True)
class DockInstance:
    """One dock: ``name`` (the DockRobot goal's ``dock_id``), its plugin ``type``, its
    ``pose`` (where the robot stands docked) in ``frame``, and the plugin's ``id``."""

    name: str
    type: str
    pose: Pose2D
    frame: str = "map"
    id: str = ""


def database_path(text: str) -> Path:
    """A path, or a shipped world's name (its file in ``databases/``)."""
    shipped = DATABASES_DIR / f"{text}.yaml"
    return shipped if "/" not in text and shipped.is_file() else Path(text)


def load_database(path: Path) -> dict[str, DockInstance]:
    try:
        text = path.read_text()
    except OSError as exc:
        raise DockDatabaseError(f"dock database {path}: cannot read: {exc.strerror}") from None
    return parse_database(text, str(path))


def parse_database(text: str, source: str = "<string>") -> dict[str, DockInstance]:
    try:
        root = yaml.compose(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f":{mark.line + 1}" if mark is not None else ""
        problem = getattr(exc, "problem", None) or str(exc)
        raise DockDatabaseError(f"dock database {source}{where}: not YAML: {problem}") from None
    if not isinstance(root, yaml.MappingNode):
        raise DockDatabaseError(f"dock database {source}: expected a mapping with 'docks'")
    docks = _value(root, "docks")
    if docks is None:
        raise DockDatabaseError(f"dock database {source} does not contain 'docks'")
    if not isinstance(docks, yaml.MappingNode):
        raise _error(source, docks, "", "'docks' must map dock names to their fields")
    found: dict[str, DockInstance] = {}
    for key, node in docks.value:
        name = str(key.value)
        if name in found:
            raise _error(source, key, name, "appears twice")
        found[name] = _dock(source, name, key, node)
    return found


def _dock(source: str, name: str, key: yaml.Node, node: yaml.Node) -> DockInstance:
    if not isinstance(node, yaml.MappingNode):
        raise _error(source, node, name, "expected a mapping of type, frame, pose, id")
    for field_key, _ in node.value:
        if field_key.value not in KEYS:
            raise _error(source, field_key, name, f"unknown field '{field_key.value}' "
                         f"(known: {', '.join(KEYS)})")  # fmt: skip
    kind, pose = _value(node, "type"), _value(node, "pose")
    if kind is None:
        raise _error(source, key, name, "has no 'type'")
    if pose is None:
        raise _error(source, key, name, "has no 'pose'")
    return DockInstance(
        name,
        _scalar(source, name, kind, "type"),
        _pose(source, name, pose),
        _scalar(source, name, _value(node, "frame"), "frame") or "map",
        _scalar(source, name, _value(node, "id"), "id"),
    )


def docks_from_params(
    names: list[str], given: Mapping[str, Mapping[str, str]]
) -> dict[str, DockInstance]:
    """Nav2's ``parseDockParams``: each dock of ``names`` from its scope in ``given``
    (``{"dock1": {"type": ..., "pose": "[x, y, theta]"}}``); ``frame`` defaults to map,
    ``id`` to empty. ValueError naming the dock and its parameter."""
    found: dict[str, DockInstance] = {}
    for name in names:
        if name in found:
            raise ValueError(f"docks: dock '{name}' appears twice")
        fields = dict(given.get(name, {}))
        for key in set(fields) - set(KEYS):
            raise ValueError(f"{name}.{key}: unknown dock field (known: {', '.join(KEYS)})")
        if "type" not in fields:
            raise ValueError(f"Dock {name} has no dock 'type' (give --param {name}.type=...)")
        if "pose" not in fields:
            raise ValueError(
                f"Dock {name} has no valid 'pose' (give --param {name}.pose=[x,y,theta])"
            )
        try:
            pose = _pose_of(fields["pose"].strip().strip("[]").split(","))
        except ValueError as exc:
            raise ValueError(f"Dock {name} has no valid 'pose': {name}.pose={fields['pose']!r} "
                             f"{exc}") from None  # fmt: skip
        found[name] = DockInstance(name, fields["type"], pose, fields.get("frame") or "map",
                                   fields.get("id", ""))  # fmt: skip
    return found


def _pose_of(items: Sequence[object]) -> Pose2D:
    """``[x, y, theta]`` from three items; ValueError saying what is wrong."""
    if len(items) != 3:
        raise ValueError("must be [x, y, theta]")
    try:
        x, y, theta = (float(str(item)) for item in items)
    except ValueError:
        raise ValueError("must hold three numbers") from None
    if not all(math.isfinite(v) for v in (x, y, theta)):
        raise ValueError("must be finite")
    return Pose2D(x, y, theta)


def _pose(source: str, name: str, node: yaml.Node) -> Pose2D:
    items = node.value if isinstance(node, yaml.SequenceNode) else []
    if any(not isinstance(item, yaml.ScalarNode) for item in items):
        raise _error(source, node, name, "'pose' must hold three numbers")
    try:
        return _pose_of([item.value for item in items])
    except ValueError as exc:
        raise _error(source, node, name, f"'pose' {exc}") from None


def _scalar(source: str, name: str, node: yaml.Node | None, field: str) -> str:
    if node is None:
        return ""
    if not isinstance(node, yaml.ScalarNode):
        raise _error(source, node, name, f"'{field}' must be a string")
    return str(node.value)


def _value(mapping: yaml.MappingNode, key: str) -> yaml.Node | None:
    return next((value for k, value in mapping.value if k.value == key), None)


def _error(source: str, node: yaml.Node, name: str, problem: str) -> DockDatabaseError:
    dock = f" dock '{name}'" if name else ""
    return DockDatabaseError(f"dock database {source}:{node.start_mark.line + 1}:{dock} {problem}")
