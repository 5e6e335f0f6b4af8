"""``aiobt certs DIR``: a CA and one certificate per service and host, for mutual TLS.

    aiobt certs deploy/certs                                   # routers router-robot, router-base
    aiobt certs certs --host robot=198.18.0.1 --host base=198.18.0.2,base.lan
    aiobt certs certs --renew          # new certificates from the CA already in certs/
    aiobt certs deploy/certs --host compose=router --seen-at /certs   # docker-compose.yml

Writes ``ca.pem``/``ca-key.pem``, ``<name>.pem``/``<name>-key.pem`` (keys mode 0600)
and ``<name>.json5``, the Zenoh config that makes a session present ``<name>``'s
certificate (``--config DIR/<name>.json5``; with ``--seen-at PATH`` the files name
PATH instead of DIR, where containers mount it). The names are the ones
deploy/access-control.json5 grants rights to. Refuses to overwrite without --force.
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

from aiobt.deploy.certs import (
    DEFAULT_DAYS,
    DEFAULT_HOSTS,
    CertPlan,
    CertsError,
    parse_host,
    write_certs,
)
from aiobt.deploy.zenoh_configs import write_configs

log = logging.getLogger("aiobt.cli.certs")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("directory", metavar="DIR", type=Path, help="where to write the files")
    parser.add_argument(
        "--host",
        action="append",
        metavar="NAME[=ADDR,...]",
        help=f"a host with a router (certificate router-NAME), with the addresses others "
        f"dial it at; repeatable (default: {', '.join(DEFAULT_HOSTS)}, loopback only)",
    )
    parser.add_argument(
        "--days", type=int, default=DEFAULT_DAYS, help="validity (default: %(default)s)"
    )
    parser.add_argument("--force", action="store_true", help="overwrite existing files")
    parser.add_argument(
        "--renew",
        action="store_true",
        help="keep the CA in DIR and issue every certificate again (rotation)",
    )
    parser.add_argument(
        "--seen-at",
        type=Path,
        metavar="PATH",
        default=None,
        help="the directory as the sessions see it, in the config files (e.g. /certs, where "
        "docker-compose.yml mounts DIR; default: DIR)",
    )


def run(args: argparse.Namespace) -> int:
    try:
        hosts = dict(parse_host(h) for h in args.host or DEFAULT_HOSTS)
        if args.days < 1:
            raise CertsError(f"--days must be >= 1, got {args.days}")
        if args.seen_at is not None and not args.seen_at.is_absolute():
            raise CertsError(f"--seen-at must be an absolute path, got {args.seen_at}")
        plan = CertPlan(hosts=hosts, days=args.days)
        written = write_certs(args.directory, plan, force=args.force, renew=args.renew)
    except CertsError as exc:
        log.error("aiobt certs: %s", exc)
        return 2
    written += write_configs(args.directory, plan, args.seen_at)
    log.info("wrote %d files in %s: %s", len(written), args.directory, ", ".join(plan.names()))
    return 0
