"""``python -m aiobt.navigator``: the same as ``aiobt navigator``."""

from __future__ import annotations

import sys

from aiobt.navigator.main import add_arguments, run
from aiobt_services._cli import module_main


def main(argv: list[str] | None = None) -> int:
    return module_main("python -m aiobt.navigator", __doc__, add_arguments, run, argv)


if __name__ == "__main__":
    sys.exit(main())
