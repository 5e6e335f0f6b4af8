"""``aiobt router`` whose reader of Zenoh's log is held off the CPU for the first
``AIOBT_BENCH_HOLD`` seconds: what a machine that keeps that thread from running does.

Run as a script by :mod:`bench.deploy.denial_log` ``--hold S``, with this tree's
Python or a baseline checkout's (``--baseline-python``): it holds whichever reader
that code has (``aiobt.transport.log_tail.LogTail`` here, the log pipe's
``refusals._pump`` before it).
"""

from __future__ import annotations

import os
import sys
import time
from typing import Any

from aiobt.cli.router import main
from aiobt.transport import refusals

HOLD = float(os.environ.get("AIOBT_BENCH_HOLD", "0"))


def _held(run: Any) -> Any:
    def held(*args: Any) -> Any:
        time.sleep(HOLD)
        return run(*args)

    return held


try:
    from aiobt.transport import log_tail

    log_tail.LogTail._run = _held(log_tail.LogTail._run)  # type: ignore[method-assign]
except ImportError:  # the code before: a pipe, read by refusals._pump
    refusals._pump = _held(refusals._pump)  # type: ignore[attr-defined]

if __name__ == "__main__":
    sys.exit(main())
