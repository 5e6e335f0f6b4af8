"""Where a world puts the robot: the initial pose ``aiobt up`` gives localization.

On a real robot the user tells localization where the robot stands (RViz's "2D Pose
Estimate", or AMCL's ``initial_pose`` parameters). In the simulation the start is
known: the world's map YAML carries it under ``aiobt: start: [x, y, yaw]`` (Nav2's
map_server ignores the key), and the robot's ``--start`` overrides it. The shipped
worlds (``office``, ``small``) live with the robot service; the library finds their
folder by module path, as the catalog names the services, without importing it.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import yaml

SHIPPED_WORLDS = "aiobt_services.robot.worlds"  # the robot service's worlds, by module path
Start = tuple[float, float, float]


class WorldError(ValueError):
    """A world's file cannot be read or its start is malformed; the message names both."""


def world_file(world: str) -> Path:
    """A shipped world's map YAML by name, else ``world`` as a path."""
    spec = importlib.util.find_spec(SHIPPED_WORLDS)
    for folder in (spec.submodule_search_locations or []) if spec else []:
        shipped = Path(folder) / f"{world}.yaml"
        if "/" not in world and shipped.is_file():
            return shipped
    return Path(world)


def world_start(world: str) -> Start:
    """The robot's start in ``world`` (``aiobt: start:``; (0, 0, 0) when the file has
    none, as the robot service reads it)."""
    path = world_file(world)
    try:
        doc = yaml.safe_load(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise WorldError(f"world {world!r}: cannot read {path}: {exc.strerror}") from None
    except yaml.YAMLError as exc:
        raise WorldError(f"world {world!r}: {path} is not valid YAML: {exc}") from None
    extras = doc.get("aiobt") if isinstance(doc, dict) else None
    start = extras.get("start", (0.0, 0.0, 0.0)) if isinstance(extras, dict) else (0.0, 0.0, 0.0)
    try:
        x, y, yaw = (float(v) for v in start)
    except (TypeError, ValueError):
        raise WorldError(f"world {world!r}: {path}: aiobt.start must be [x, y, yaw], got "
                         f"{start!r}") from None  # fmt: skip
    return x, y, yaw


def start_from_args(args: list[str] | tuple[str, ...]) -> Start | None:
    """The robot's ``--start X Y YAW`` among its flags, if given."""
    if "--start" not in args:
        return None
    at = args.index("--start")
    try:
        x, y, yaw = (float(v) for v in args[at + 1 : at + 4])
    except ValueError:
        raise WorldError(f"robot --start {' '.join(args[at + 1 : at + 4])}: "
                         "expected three numbers X Y YAW") from None  # fmt: skip
    return x, y, yaw
