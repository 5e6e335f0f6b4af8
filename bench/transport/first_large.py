"""The first large messages of a process: Zenoh's defaults against aiobt's settings.

Run: ``.venv/bin/python -m bench.transport.first_large --sessions 10``

With Zenoh's defaults, a message over 3 KB between processes of one host goes
through shared memory, set up on a process's first such messages: a 16 MB pool
mapped and locked, then a segment and watchdog threads. aiobt's settings turn
shared memory off (``aiobt.transport.settings``). A planner's reply or a
FollowPath goal (400 poses: 57 KB of JSON) is such a message, and the first ones
of each process came late (issue 17: the planner's slowest round trip).

Two routers on loopback, one per variant (Zenoh's defaults with shared memory on,
aiobt's), each with a queryable in this process that notes when a query reaches
Zenoh's thread. Round by round, for each variant, a new sender process opens a
session the variant's way and sends ``--queries`` queries of ``--size`` bytes
(``--gap`` wall s apart), noting how long each ``get`` call took. Reported per
variant: the queries' delivery (sent -> reached the queryable, wall ms, the
monotonic clock is the host's) and the ``get`` call's time, for the first two of
each session and for the others: median and max over all sessions.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import textwrap
import threading
import time
from pathlib import Path

import zenoh

from aiobt.testing.bus import exit_on_sigterm, running_router
from aiobt.transport import BusSettings

KEY = "bench/first_large"
ROOT = str(Path(__file__).resolve().parents[2])  # where ``bench`` imports from
SENDER = textwrap.dedent(
    """
    import json, sys, time, zenoh
    from bench.transport.first_large import session_config
    endpoint, variant, size, count, gap, key = sys.argv[1:7]
    payload = b"x" * int(size)
    with zenoh.open(session_config(variant, endpoint)) as session:
        querier = session.declare_querier(key)
        deadline = time.monotonic() + 20.0
        while not querier.matching_status.matching:
            if time.monotonic() > deadline:
                sys.exit("no queryable matched")
            time.sleep(0.01)
        time.sleep(0.5)  # a session that has been up a moment, as a service's is
        sent = []
        for _ in range(int(count)):
            began = time.monotonic()
            querier.get(payload=payload, handler=lambda reply: None)
            sent.append((began, time.monotonic() - began))
            time.sleep(float(gap))
        print(json.dumps(sent), flush=True)
        time.sleep(0.5)  # the last replies
    """
)


class Arrivals:
    """A queryable noting each query's arrival on Zenoh's thread."""

    def __init__(self, session: zenoh.Session) -> None:
        self.times: list[float] = []
        self._lock = threading.Lock()
        self.queryable = session.declare_queryable(KEY, self._on_query)

    def _on_query(self, query: zenoh.Query) -> None:
        arrived = time.monotonic()
        with self._lock:
            self.times.append(arrived)
        query.reply(KEY, b"ok")

    def take(self) -> list[float]:
        with self._lock:
            times, self.times = self.times, []
        return times


def session_config(variant: str, endpoint: str) -> zenoh.Config:
    """A client of ``endpoint`` with aiobt's settings or Zenoh's defaults (this process's
    and the senders')."""
    if variant == "aiobt":
        return BusSettings(connect=(endpoint,)).zenoh_config()
    config = zenoh.Config()
    config.insert_json5("mode", '"client"')
    config.insert_json5("connect/endpoints", json.dumps([endpoint]))
    return config


def one_session(endpoint: str, variant: str, args: argparse.Namespace) -> list[tuple[float, float]]:
    """(delivery, call) seconds of each query of one new sender process."""
    argv = [endpoint, variant, str(args.size), str(args.queries), str(args.gap), KEY]
    done = subprocess.run(
        [sys.executable, "-c", SENDER, *argv],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=ROOT,  # ``-c`` imports from the working directory: ``bench`` is there
    )
    if done.returncode != 0:
        raise SystemExit(f"sender ({variant}) failed:\n{done.stderr}")
    return [(began, call) for began, call in json.loads(done.stdout)]


def summary(values: list[float]) -> str:
    return f"{statistics.median(values) * 1e3:.1f} / {max(values) * 1e3:.1f}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--sessions", type=int, default=10, help="sender processes per variant")
    parser.add_argument("--queries", type=int, default=6, help="queries per sender")
    parser.add_argument("--size", type=int, default=57_000, help="bytes per query")
    parser.add_argument("--gap", type=float, default=0.1, help="wall s between queries")
    exit_on_sigterm()
    args = parser.parse_args(argv)
    results: dict[str, list[list[tuple[float, float]]]] = {"zenoh": [], "aiobt": []}
    with tempfile.TemporaryDirectory() as tmp:
        shm_on = Path(tmp) / "shm_on.json5"
        shm_on.write_text("{transport: {shared_memory: {enabled: true}}}")  # Zenoh's default
        with (
            running_router(extra_args=["--config", str(shm_on)]) as (_, zenoh_endpoint),
            running_router() as (_, aiobt_endpoint),
        ):
            endpoints = {"zenoh": zenoh_endpoint, "aiobt": aiobt_endpoint}
            sessions = {v: zenoh.open(session_config(v, e)) for v, e in endpoints.items()}
            try:
                arrivals = {v: Arrivals(s) for v, s in sessions.items()}
                for _ in range(args.sessions):
                    for variant, endpoint in endpoints.items():
                        sent = one_session(endpoint, variant, args)
                        got = arrivals[variant].take()
                        if len(got) != len(sent):
                            raise SystemExit(f"{variant}: {len(got)} of {len(sent)} arrived")
                        results[variant].append(
                            [(a - began, call) for a, (began, call) in zip(got, sent, strict=True)]
                        )
            finally:
                for session in sessions.values():
                    session.close()  # type: ignore[no-untyped-call]
    print(
        f"{args.sessions} sender processes per variant, {args.queries} queries of "
        f"{args.size} B each, {args.gap} s apart; median / max ms"
    )
    print("| variant | delivery, first two | delivery, the others | get call, first two "
          "| get call, the others |")  # fmt: skip
    print("|---|---|---|---|---|")
    for variant, runs in results.items():
        first = [trip for run in runs for trip in run[:2]]
        rest = [trip for run in runs for trip in run[2:]]
        cells = [summary([t[i] for t in part]) for i in (0, 1) for part in (first, rest)]
        print(f"| {variant} | {cells[0]} | {cells[1]} | {cells[2]} | {cells[3]} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
