"""docs/robot_contract.md holds to the robot service's code: the service's own ``serve``
runs on a bus that records what it declares, and every key it declares is in the
doc's tables, each table's keys are the ones it declares, with the same kind and
model; the simulation's own keys are all under ``sim/`` and nothing else is; the fields
named exist on those models, with the frames the service puts in them; the rates and the
command timeout are its defaults."""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import importlib
import re
from collections.abc import AsyncIterator, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from pydantic import BaseModel

from aiobt.system.robot_flags import add_pose_timeout_argument
from aiobt_services.controller import main as controller_main
from aiobt_services.localization.odom_buffer import KEEP
from aiobt_services.robot import convert
from aiobt_services.robot import main as robot_main
from aiobt_services.robot.drive import DriveLimits
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.runner import Rates
from aiobt_services.robot.sensors import LidarConfig
from aiobt_services.robot.sim import Simulation
from aiobt_services.robot.worlds import SMALL

DOC = Path(__file__).parents[3] / "docs" / "robot_contract.md"
PUBLISHES, TAKES = "What a base publishes", "What a base takes"
SIM_ONLY, STAND_IN = "Simulation only", "The localization's stand-in"
OTHER_PARTS = "What the simulation publishes for other parts of a robot"


@dataclass(frozen=True, slots=True)
class Declared:
    kind: str  # "topic", "latched topic", "subscribed", "service", "liveliness token"
    models: tuple[type[Any], ...]


class RecordingBus:
    """What ``serve`` declares on a bus, by key relative to the namespace."""

    namespace = "robot"

    def __init__(self) -> None:
        self.declared: dict[str, Declared] = {}

    def _add(self, key: str, kind: str, *models: type[Any]) -> None:
        assert key not in self.declared or self.declared[key].kind == kind, key
        self.declared[key] = Declared(kind, models)

    def publisher(self, name: str, model: type[Any], **_: Any) -> Any:
        self._add(name, "topic", model)
        return argparse.Namespace(put=lambda _msg: None)

    def latched_publisher(self, name: str, model: type[Any], **_: Any) -> Any:
        self._add(name, "latched topic", model)
        return argparse.Namespace(put=lambda _msg: None)

    def subscribe(self, name: str, model: type[Any], **_: Any) -> None:
        self._add(name, "subscribed", model)

    def serve(
        self, name: str, request: type[Any], reply: type[Any], _handler: Any, *,
        namespace: str | None = None,
    ) -> None:  # fmt: skip
        within = "" if namespace is None else f"{namespace.removeprefix(self.namespace + '/')}/"
        assert namespace is None or namespace.startswith(f"{self.namespace}/"), namespace
        self._add(f"{within}srv/{name}", "service", request, reply)

    def declare_token(self, name: str) -> None:
        self._add(name, "liveliness token")


def robot_args(*flags: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    robot_main.add_arguments(parser)
    return parser.parse_args(list(flags))


def declared_by_the_service(monkeypatch: pytest.MonkeyPatch, *flags: str) -> dict[str, Declared]:
    """Everything the robot service's ``serve`` declares with ``flags`` (``--stepped``
    added: then it returns once its stop event is set, which it is from the start)."""
    bus = RecordingBus()

    @contextlib.asynccontextmanager
    async def recording(*_: Any) -> AsyncIterator[RecordingBus]:
        yield bus

    def stopped() -> asyncio.Event:
        event = asyncio.Event()
        event.set()
        return event

    monkeypatch.setattr(robot_main, "open_bus_unless_stopped", recording)
    monkeypatch.setattr(robot_main, "stop_on_signals", stopped)
    monkeypatch.setattr(robot_main, "settle", lambda: None)  # no gc.freeze in pytest's process
    with Simulation(load_map(SMALL)) as sim:
        asyncio.run(robot_main.serve(robot_args("--stepped", *flags), sim))
    return bus.declared


@dataclass(frozen=True, slots=True)
class Row:
    key: str
    cells: tuple[str, ...]  # kind, model, then the table's other columns


KINDS = ("topic", "latched topic", "subscribed", "service", "liveliness token")


def doc_tables() -> dict[str, list[Row]]:
    """The key tables under each heading (``##``/``###``), by the heading's text."""
    tables: dict[str, list[Row]] = {}
    heading = ""
    for line in DOC.read_text().splitlines():
        if line.startswith("#"):
            heading = line.lstrip("#").strip()
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if line.startswith("| `") and len(cells) > 2 and cells[1].startswith(KINDS):
            tables.setdefault(heading, []).append(Row(cells[0].strip("`"), tuple(cells[1:])))
    headings = (PUBLISHES, TAKES, SIM_ONLY, OTHER_PARTS, STAND_IN)
    return {h: rows for h, rows in tables.items() if h.startswith(headings)}


@pytest.fixture(scope="module")
def declared() -> Iterator[tuple[dict[str, Declared], dict[str, Declared]]]:
    """What the service declares as a real base would (``--pose-source none``) and as the
    localization's stand-in (``--pose-source truth``)."""
    with pytest.MonkeyPatch.context() as patch:
        yield (
            declared_by_the_service(patch, "--pose-source", "none"),
            declared_by_the_service(patch, "--pose-source", "truth"),
        )


def keys_of(tables: dict[str, list[Row]], *headings: str) -> set[str]:
    return {row.key for h, rows in tables.items() if h.startswith(headings) for row in rows}


def test_every_key_the_service_declares_is_in_the_doc_and_every_key_there_is_declared(
    declared: tuple[dict[str, Declared], dict[str, Declared]],
) -> None:
    hardware, stand_in = declared
    tables = doc_tables()
    assert keys_of(tables, PUBLISHES, TAKES, SIM_ONLY, OTHER_PARTS) == hardware.keys()
    assert keys_of(tables, STAND_IN) == stand_in.keys() - hardware.keys()
    assert hardware.keys() <= stand_in.keys()
    assert keys_of(tables, TAKES) == {k for k, d in hardware.items() if d.kind == "subscribed"}
    # the simulation's own keys (its truth, its services) are its namespace's, all of it
    assert keys_of(tables, SIM_ONLY) == {k for k in hardware if k.startswith("sim/")}
    assert not {k for k in stand_in.keys() - hardware.keys() if k.startswith("sim/")}


def _model(name: str) -> type[Any]:
    module, _, attr = name.rpartition(".")
    found: type[Any] = getattr(importlib.import_module(module), attr)
    return found


def test_each_row_has_the_kind_and_the_models_the_service_declares(
    declared: tuple[dict[str, Declared], dict[str, Declared]],
) -> None:
    everything = {**declared[1], **declared[0]}
    for heading, rows in doc_tables().items():
        for row in rows:
            code = everything[row.key]
            kind, models = row.cells[0], re.findall(r"`(aiobt\.[\w.]+)`", row.cells[1])
            assert kind.startswith(code.kind), (heading, row.key, kind, code.kind)
            assert tuple(_model(m) for m in models) == code.models, (heading, row.key, models)


def _sample_messages() -> dict[str, BaseModel]:
    with Simulation(load_map(SMALL)) as sim:
        sim.step()
        return {
            "odom": convert.odometry(sim),
            "scan": convert.laser_scan(sim.scan()),
            "battery": convert.battery_state(sim.battery, sim.time),
            "map": convert.occupancy_grid(sim.world),
        }


def _field(message: BaseModel, path: str) -> Any:
    """The value at ``path`` (``a.b.c``) of ``message``; fails unless each part is a field."""
    value: Any = message
    for part in path.split("."):
        assert isinstance(value, BaseModel), (path, part)
        assert part in type(value).model_fields, (type(value).__name__, path)
        value = getattr(value, part)
    return value


def _field_type(model: type[BaseModel], path: str) -> Any:
    """The annotation at ``path`` of ``model`` (no message needed); fails unless each part
    is a field."""
    annotation: Any = model
    for part in path.split("."):
        assert isinstance(annotation, type), (path, part)
        assert issubclass(annotation, BaseModel), (path, part)
        assert part in annotation.model_fields, (annotation.__name__, path)
        annotation = annotation.model_fields[part].annotation
    return annotation


def test_the_fields_named_exist_and_carry_the_frames_the_doc_gives() -> None:
    sample = _sample_messages()
    checked = 0
    for row in doc_tables()[PUBLISHES] + doc_tables()[TAKES]:
        fields = row.cells[2]
        for path, value in re.findall(r"`([a-z_.]+)`(?: \(`([\w]+)`\))?", fields):
            message = sample.get(row.key)
            if message is None:  # no sample: the path must still be a field of the model
                assert not value, (row.key, path)
                _field_type(_model(re.findall(r"`(aiobt\.[\w.]+)`", row.cells[1])[0]), path)
            else:
                got = _field(message, path)
                assert not value or got == value, (row.key, path, got, value)
            checked += 1
    assert checked >= 25


def _flat(text: str) -> str:
    return " ".join(text.split())


def test_the_rates_the_timeout_and_the_limits_are_the_services_defaults() -> None:
    args = robot_args()
    rates = Rates()
    text = _flat(DOC.read_text())
    rows = {row.key: " ".join(row.cells) for rs in doc_tables().values() for row in rs}
    expected = {
        "odom": args.odom_hz, "scan": args.scan_hz, "battery": rates.battery,
        "clock": rates.clock, "sim/pose": args.odom_hz, "pose": args.odom_hz,
    }  # fmt: skip
    for key, hz in expected.items():
        assert f"{hz:g} Hz" in rows[key], (key, rows[key])
    limits = DriveLimits()
    assert (args.cmd_timeout, args.max_linear, args.max_angular) == (
        limits.cmd_timeout, limits.max_linear, limits.max_angular,
    )  # fmt: skip
    assert f"`--cmd-timeout`, {args.cmd_timeout:g} s by default" in text
    assert f"`--max-linear` {args.max_linear:.1f} m/s" in text
    assert f"`--max-angular` {args.max_angular:.1f} rad/s" in text
    assert f"({limits.max_linear_accel:g} m/s², {limits.max_angular_accel:g} rad/s²)" in text
    parser = argparse.ArgumentParser()
    add_pose_timeout_argument(parser.add_argument_group())
    assert f"`--pose-timeout` ({parser.parse_args([]).pose_timeout:g} s" in text
    assert f"{KEEP} messages" in text
    controller = argparse.ArgumentParser()
    controller_main.add_arguments(controller)
    assert f"the controller's `--rate` ({controller.parse_args([]).rate:g} Hz)" in rows["cmd_vel"]
    assert f"({LidarConfig().height:g} m up)" in text
