"""Observing trees: status-change observers, transition loggers, replay files.

- :class:`StatusObserver` / :class:`TransitionRecorder` — the observer API;
- :class:`ConsoleLogger` — one line per transition (BT.CPP's StdCoutLogger);
- :class:`JsonlLogger` — a JSON Lines file of transitions;
- :class:`BtlogLogger` — Groot2-replayable ``.btlog`` (BT.CPP's FileLogger2);
- :class:`SqliteLogger` — BT.CPP's SqliteLogger schema;
- :class:`TreeStatistics` — ticks and results per node (BT.CPP's TreeObserver);
- :func:`tree_to_xml` — the instantiated tree as XML with ``_uid`` attributes;
- :class:`Groot2Publisher` — Groot2 attaches live (BT.CPP's Groot2Publisher).

All are attached on construction and detached by ``close()`` (or ``with``).
"""

from aiobt.loggers.btlog import BtlogLogger
from aiobt.loggers.console import ConsoleLogger
from aiobt.loggers.groot2 import Groot2Publisher
from aiobt.loggers.jsonl import JsonlLogger
from aiobt.loggers.observer import StatusObserver, Transition, TransitionRecorder
from aiobt.loggers.sqlite import SqliteLogger
from aiobt.loggers.stats import NodeStatistics, TreeStatistics
from aiobt.loggers.tree_xml import tree_to_xml

__all__ = [
    "BtlogLogger",
    "ConsoleLogger",
    "Groot2Publisher",
    "JsonlLogger",
    "NodeStatistics",
    "SqliteLogger",
    "StatusObserver",
    "Transition",
    "TransitionRecorder",
    "TreeStatistics",
    "tree_to_xml",
]
