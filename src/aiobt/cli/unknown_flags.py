"""argparse's "unrecognized arguments", with the closest known flag, as node IDs get."""

from __future__ import annotations

import argparse
import difflib
from collections.abc import Sequence


def unknown_flags_message(extra: Sequence[str], parser: argparse.ArgumentParser) -> str:
    """``unrecognized arguments: --max-sped (did you mean --max-speed?)``."""
    known = [flag for action in parser._actions for flag in action.option_strings]
    parts = []
    for arg in extra:
        flag = arg.split("=", 1)[0]
        close = difflib.get_close_matches(flag, known, n=1, cutoff=0.7)
        parts.append(
            f"{arg} (did you mean {close[0]}?)" if flag.startswith("--") and close else arg
        )
    return f"unrecognized arguments: {' '.join(parts)}"


def command_parser(parser: argparse.ArgumentParser, command: str) -> argparse.ArgumentParser:
    """The sub-parser of ``command`` (argparse keeps no public handle on it)."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            found: argparse.ArgumentParser = action.choices[command]
            return found
    raise LookupError(f"no sub-command {command!r}")
