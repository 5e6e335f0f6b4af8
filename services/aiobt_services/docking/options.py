"""``aiobt docking``'s flags, by Nav2's ``docking_server`` parameter names (dashes for
underscores; dotted names through ``--param``), and the server's parts built from them.

The flags' defaults are Nav2's. The dock plugin ``simple_charging_dock`` comes set up
for aiobt's simulated robot and dock, as Nav2's ``nav2_params.yaml`` sets its own up
(:data:`SHIPPED`); ``--param`` overrides any of it.
"""

from __future__ import annotations

import argparse
import dataclasses
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

from aiobt.geometry.smooth import RotateParams, SmoothControlParams
from aiobt.system.plugin_params import comma_list, dotted_param, params_from
from aiobt.system.service import non_negative, positive

from .controller import ControllerParams
from .database import DockInstance, database_path, docks_from_params
from .params import DockingParams
from .plugins import ChargingDock, DockWiring, PluginFactory
from .simple_charging_dock import SimpleChargingDock, SimpleChargingDockParams
from .simple_dock import SimpleDockParams
from .simple_non_charging_dock import SimpleNonChargingDock

T = TypeVar("T")
PLUGIN_TYPES: dict[str, tuple[type[Any], PluginFactory]] = {  # Nav2's type: params, class
    "opennav_docking::SimpleChargingDock": (SimpleChargingDockParams, SimpleChargingDock),
    "opennav_docking::SimpleNonChargingDock": (SimpleDockParams, SimpleNonChargingDock),
}
DEFAULT_PLUGIN = "simple_charging_dock"
# aiobt's robot and dock: the marker is on the dock's face, a robot radius ahead of the
# docked pose, and the detection is planar (no camera-frame turn); docked is pressed on
# the contacts; a longer staging run and a stiffer law settle the heading before contact
SHIPPED: dict[str, dict[str, str]] = {
    DEFAULT_PLUGIN: {
        "use_external_detection_pose": "true",
        "external_detection_translation_x": "-0.22",
        "external_detection_rotation_pitch": "0.0",
        "external_detection_rotation_roll": "0.0",
        "docking_threshold": "0.005",
        "staging_x_offset": "-1.0",
    },
    "controller": {
        "k_phi": "5.0",
        "k_delta": "3.0",
        "v_linear_min": "0.15",
        "v_linear_max": "0.15",
    },
}


# Nav2's controller parameters for reading the controller's costmap and footprint topics:
# aiobt's controller publishes neither, so the server checks its own (docs/docking.md)
NOT_READ = ("costmap_topic", "footprint_topic", "transform_tolerance")


@dataclass(slots=True, frozen=True)
class PluginSpec:
    name: str
    make: PluginFactory
    params: Any


@dataclass(slots=True, frozen=True)
class Settings:
    """The server's parameters, checked before anything starts."""

    docking: DockingParams
    controller: ControllerParams
    plugins: list[PluginSpec]
    docks: dict[str, DockInstance] | None = None  # Nav2's ``docks`` parameter, if given


def add_docking_arguments(group: argparse._ArgumentGroup) -> None:
    add, d = group.add_argument, DockingParams()
    add("--dock-database", type=_database_flag, default=None, metavar="PATH_OR_WORLD",
        help="dock database (YAML): a path, or a shipped world's name (office, small); "
        "'' for none (then --docks)")  # fmt: skip
    add("--docks", type=comma_list, default=None, metavar="NAMES",
        help="instead of --dock-database, comma-separated docks given by --param "
        "NAME.type=..., NAME.pose=[x,y,theta], NAME.frame (map), NAME.id")  # fmt: skip
    add("--dock-plugins", type=comma_list, default=DEFAULT_PLUGIN,
        help="comma-separated dock plugin names (default: %(default)s)")  # fmt: skip
    add("--param", type=dotted_param, action="append", default=[], metavar="SCOPE.NAME=VALUE",
        help="a plugin's or the controller's parameter, e.g. controller.k_phi=3.0 or "
        "simple_charging_dock.staging_x_offset=-0.7")  # fmt: skip
    for field in dataclasses.fields(DockingParams):
        kind = field.type if field.type in ("int", "str") else "float"
        convert = {"int": int, "str": str}.get(kind, non_negative)
        if field.name == "controller_frequency":
            convert = positive
        add(f"--{field.name.replace('_', '-')}", type=convert, default=getattr(d, field.name),
            help="(default: %(default)s)")  # fmt: skip


def docking_params(args: argparse.Namespace) -> DockingParams:
    return DockingParams(
        **{f.name: getattr(args, f.name) for f in dataclasses.fields(DockingParams)}
    )


def _database_flag(text: str) -> Path | None:
    return database_path(text) if text else None


def scoped(args: argparse.Namespace, scope: str) -> dict[str, str]:
    given = {key: value for name, key, value in args.param if name == scope}
    return SHIPPED.get(scope, {}) | given


def check_scopes(args: argparse.Namespace) -> None:
    """ValueError naming a --param for neither the controller nor a plugin loaded."""
    docks = args.docks or []
    for scope, key, _ in args.param:
        if scope != "controller" and scope not in args.dock_plugins and scope not in docks:
            loaded = ", ".join(args.dock_plugins)
            raise ValueError(f"--param {scope}.{key}: '{scope}' is neither 'controller' nor "
                             f"among the dock_plugins ({loaded}) nor the docks "
                             f"({', '.join(docks) or 'none'})")  # fmt: skip


def controller_params(args: argparse.Namespace) -> ControllerParams:
    """``controller.*``: the law's, the turn in place's and the collision check's."""
    given = {_law_name(k): v for k, v in scoped(args, "controller").items()}
    law_keys = {f.name for f in dataclasses.fields(SmoothControlParams)}
    rotate_keys = {f.name for f in dataclasses.fields(RotateParams)}
    own_keys = {f.name for f in dataclasses.fields(ControllerParams)} - {"law", "rotate"}
    for key in set(given) & set(NOT_READ):
        raise ValueError(f"controller.{key}: not read: aiobt's controller publishes no "
                         "local_costmap/costmap_raw nor published_footprint; the approach is "
                         "checked on the server's own costmap from {ns}/scan with --footprint "
                         "or --robot-radius (docs/docking.md)")  # fmt: skip
    for key in set(given) - law_keys - rotate_keys - own_keys:
        known = ", ".join(sorted(k.rstrip("_") for k in law_keys | rotate_keys | own_keys))
        raise ValueError(f"controller.{key}: no such parameter (known: {known})")

    def part(cls: type[T], keys: set[str]) -> T:
        made: T = params_from(cls, "controller", {k: given[k] for k in keys & set(given)})
        return made

    own = part(ControllerParams, own_keys)
    law = part(SmoothControlParams, law_keys)
    return dataclasses.replace(own, law=law, rotate=part(RotateParams, rotate_keys))


def _law_name(key: str) -> str:
    return "lambda_" if key == "lambda" else key


def plugin_specs(args: argparse.Namespace) -> list[PluginSpec]:
    if not args.dock_plugins:
        raise ValueError("Charging dock plugins empty! Must provide 1.")
    specs: list[PluginSpec] = []
    for name in args.dock_plugins:
        given = scoped(args, name)
        kind = given.pop("plugin", "opennav_docking::SimpleChargingDock")
        if kind not in PLUGIN_TYPES:
            known = ", ".join(PLUGIN_TYPES)
            raise ValueError(f"{name}.plugin: no dock plugin '{kind}' (known: {known})")
        params, make = PLUGIN_TYPES[kind]
        specs.append(PluginSpec(name, make, params_from(params, name, given)))
    return specs


def settings_from(args: argparse.Namespace) -> Settings:
    """ValueError naming the parameter that is wrong."""
    check_scopes(args)
    docks = None
    if args.docks is not None:
        docks = docks_from_params(args.docks, {name: scoped(args, name) for name in args.docks})
    return Settings(docking_params(args), controller_params(args), plugin_specs(args), docks)


def make_plugins(specs: list[PluginSpec], wiring: DockWiring) -> dict[str, ChargingDock]:
    return {spec.name: spec.make(spec.name, spec.params, wiring) for spec in specs}
