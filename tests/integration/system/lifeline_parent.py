"""A parent for test_lifeline.py: the real spawner (``aiobt.testing.bus``) starts a
router and a service, this prints their pids and waits for its stdin to close.

    python -m tests.integration.system.lifeline_parent [--from-thread] [--exit-on-sigterm]

Prints ``pids ROUTER SERVICE`` once both serve; when its stdin closes (or, with
``--exit-on-sigterm``, on SIGTERM) it stops them and prints ``stopped CODE CODE``.
``--from-thread`` starts them on a thread that has ended before they are asked
whether they still run.
"""

from __future__ import annotations

import argparse
import sys
import threading

from aiobt.testing.bus import ServiceProcess, exit_on_sigterm, spawn_service, start_router

SERVER = "tests.integration.transport.action_server_proc"


def start(procs: list[ServiceProcess]) -> None:
    router, endpoint = start_router()
    procs.append(router)
    procs.append(spawn_service(["-m", SERVER, "--connect", endpoint, "--namespace", "lifeline"]))


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--from-thread", action="store_true")
    parser.add_argument("--exit-on-sigterm", action="store_true")
    args = parser.parse_args()
    if args.exit_on_sigterm:
        exit_on_sigterm()
    procs: list[ServiceProcess] = []
    try:
        if args.from_thread:
            starter = threading.Thread(target=start, args=(procs,))
            starter.start()
            starter.join()
        else:
            start(procs)
        ready = procs[1].wait_for_output("ready", 60.0)
        if not (ready and all(p.running for p in procs)):
            raise SystemExit("\n".join(p.output() for p in procs))
        print("pids", *(p.pid for p in procs), flush=True)
        sys.stdin.read()  # until the test closes it
    finally:
        print("stopped", *(p.stop() for p in procs), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
