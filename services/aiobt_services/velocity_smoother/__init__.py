"""Nav2's velocity smoother: acceleration limits, deadband and a timeout between the
controller's command and the base. Pure logic here; the service in ``.service`` and
``.main`` (``python -m aiobt_services.velocity_smoother``)."""

from .limits import apply_constraints, find_eta_constraint
from .params import SmootherConfigError, SmootherParams
from .smoother import VelocitySmoother

__all__ = [
    "SmootherConfigError",
    "SmootherParams",
    "VelocitySmoother",
    "apply_constraints",
    "find_eta_constraint",
]
