"""The localization service's command line: the bus flags, and AMCL's parameters
from a Nav2 params file (``amcl: ros__parameters: ...``) and ``--set NAME=VALUE``."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import yaml

from aiobt.system.catalog import realtime_priority
from aiobt.system.realtime import add_realtime_argument
from aiobt.transport import add_bus_arguments

from .params import AmclParams, ParamError

CONFIG_DIR = Path(__file__).parent / "config"  # shipped params files, by name (sim_robot)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    parser.add_argument(
        "--sim-time",
        action="store_true",
        help="accepted as every service takes it: the filter runs on the stamps of the "
        "odometry and scans it reads, whichever clock made them",
    )
    parser.add_argument(
        "--params-file",
        type=_params_path,
        metavar="YAML",
        help="a Nav2 params file: its amcl.ros__parameters (or a flat mapping of AMCL's "
        "parameter names); or a shipped one by name: "
        + ", ".join(sorted(p.stem for p in CONFIG_DIR.glob("*.yaml"))),
    )
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="one AMCL parameter, the value in YAML (e.g. --set recovery_alpha_fast=0.1); "
        "after the params file; repeatable",
    )
    add_realtime_argument(parser, realtime_priority("localization"))


def params_from_args(args: argparse.Namespace) -> AmclParams:
    """The parameters the flags give (:class:`ParamError` names a bad one)."""
    values: dict[str, Any] = {}
    if args.params_file is not None:
        values.update(read_params_file(args.params_file))
    for item in args.set:
        name, sep, text = item.partition("=")
        if not sep or not name:
            raise ParamError(f"--set {item!r}: expected NAME=VALUE")
        values[name.strip()] = yaml.safe_load(text)
    return AmclParams.from_mapping(values)


def _params_path(text: str) -> Path:
    shipped = CONFIG_DIR / f"{text}.yaml"
    return shipped if "/" not in text and shipped.is_file() else Path(text)


def read_params_file(path: Path) -> dict[str, Any]:
    """AMCL's parameters from a Nav2 params file (``amcl.ros__parameters``) or a flat
    mapping (:class:`ParamError` says what is wrong with it)."""
    try:
        data = yaml.safe_load(path.read_text())
    except (OSError, yaml.YAMLError) as exc:
        raise ParamError(f"--params-file {path}: {exc}") from None
    if not isinstance(data, dict):
        raise ParamError(f"--params-file {path}: expected a mapping at the top")
    amcl = data.get("amcl", data)
    if isinstance(amcl, dict) and "ros__parameters" in amcl:
        amcl = amcl["ros__parameters"]
    if not isinstance(amcl, dict):
        raise ParamError(f"--params-file {path}: amcl.ros__parameters is not a mapping")
    return amcl
