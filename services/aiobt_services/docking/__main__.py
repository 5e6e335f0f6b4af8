"""``python -m aiobt_services.docking``: the same as ``aiobt docking``."""

from __future__ import annotations

import sys

from aiobt.system.service import module_main

from .main import add_arguments, run


def main(argv: list[str] | None = None) -> int:
    return module_main("python -m aiobt_services.docking", __doc__, add_arguments, run, argv)


if __name__ == "__main__":
    sys.exit(main())
