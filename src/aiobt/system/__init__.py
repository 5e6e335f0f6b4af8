"""The whole system on one machine: settings, service commands, a process supervisor.

``aiobt up`` and ``aiobt demo`` run it; docker-compose.yml runs the same commands
in containers. See :func:`run_system`.
"""

from aiobt.system.config import ConfigError, SystemConfig, load_config
from aiobt.system.console import ConsoleSink
from aiobt.system.runner import System, run_system
from aiobt.system.supervisor import Fatal

__all__ = [
    "ConfigError",
    "ConsoleSink",
    "Fatal",
    "System",
    "SystemConfig",
    "load_config",
    "run_system",
]
