"""Nav2's composition: several services in one process, on one bus session.

    aiobt safety_chain --connect tcp/127.0.0.1:7447 --sim-time [each service's flags]

Nav2 runs its servers as composable nodes in one container when ``use_composition``
is true; here a composition (:data:`aiobt.system.catalog.COMPOSITIONS`) runs its
services' own wiring (each service's ``main.component(args)``) in one process: one
Zenoh session, so one set of receiving threads, and one asyncio loop. Each service
keeps its flags, parameters, keys, presence token (``nodes/<service>``), start order
and errors: what talks to them cannot tell. The flags are the union of the
services' (the bus, clock and ``--realtime-priority`` flags once, for all); a flag
two services both define otherwise is refused (:func:`flag_clashes`), never merged.

The library imports no service: each is loaded by its module path from the catalog
when the command runs, as ``aiobt <service>`` does.
"""

from __future__ import annotations

import argparse
import importlib
import logging
from collections.abc import Mapping, Sequence
from types import ModuleType

from aiobt.system.catalog import COMPOSITIONS, service
from aiobt.system.realtime import add_realtime_argument
from aiobt.system.service import Component, add_clock_arguments, run_service, serve_components
from aiobt.transport import add_bus_arguments

log = logging.getLogger("aiobt.system.compose")


class CompositionError(ValueError):
    """A composition that cannot be built; the message names it and why."""


def components_of(composition: str) -> tuple[str, ...]:
    """The services ``composition`` runs, in start order; CompositionError if unknown."""
    try:
        return COMPOSITIONS[composition]
    except KeyError:
        known = ", ".join(COMPOSITIONS)
        raise CompositionError(f"no composition '{composition}' (known: {known})") from None


def shared_flags() -> frozenset[str]:
    """The flags every service has and a composition takes once: bus, clock, priority."""
    parser = argparse.ArgumentParser(add_help=True)
    add_bus_arguments(parser)
    add_clock_arguments(parser)
    add_realtime_argument(parser, 0)
    parser.add_argument("-v", "--verbose", action="count")
    return frozenset(flag for action in parser._actions for flag in action.option_strings)


def flag_clashes(flags: Mapping[str, frozenset[str]], shared: frozenset[str]) -> list[str]:
    """Each flag, outside ``shared``, that two services of ``flags`` (name -> its flags)
    both define, as "``--flag``: a and b"; empty when they can share one command line."""
    owner: dict[str, str] = {}
    clashes = []
    for name, own in flags.items():
        for flag in sorted(own - shared):
            if flag in owner:
                clashes.append(f"{flag}: {owner[flag]} and {name}")
            owner.setdefault(flag, name)
    return clashes


def _module(name: str) -> ModuleType:
    module = importlib.import_module(service(name).module)
    if not hasattr(module, "component"):
        raise CompositionError(f"service '{name}' cannot be composed: no component(args)")
    return module


def _flags_of(module: ModuleType) -> frozenset[str]:
    parser = argparse.ArgumentParser()
    module.add_arguments(parser)
    return frozenset(flag for action in parser._actions for flag in action.option_strings)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Every component's flags on ``parser`` (made with ``conflict_handler="resolve"``),
    whose default ``_command`` names the composition (the ``aiobt`` command sets both);
    CompositionError on a clash."""
    names = components_of(parser.get_default("_command"))
    modules = {name: _module(name) for name in names}
    clashes = flag_clashes({n: _flags_of(m) for n, m in modules.items()}, shared_flags())
    if clashes:
        raise CompositionError(f"{', '.join(names)} cannot share flags: {'; '.join(clashes)}")
    if parser.conflict_handler != "resolve":  # the shared flags: each service adds them
        raise CompositionError("a composition's parser must take a repeated flag's last")
    for module in modules.values():
        module.add_arguments(parser)


def build(names: Sequence[str], args: argparse.Namespace) -> list[Component]:
    """Each service's component from the one command line, in order (its own
    configuration error, naming the parameter, if one is bad)."""
    return [_module(name).component(args) for name in names]


def run(args: argparse.Namespace) -> int:
    name: str = args._command
    try:
        components = build(components_of(name), args)
    except ValueError as exc:  # each service's configuration error is one
        log.error("%s", exc)
        return 2
    return run_service(serve_components(args, components, log, args.realtime_priority), log, name)
