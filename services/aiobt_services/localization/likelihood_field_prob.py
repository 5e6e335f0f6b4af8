"""AMCL's probabilistic likelihood-field laser model, with its beam skipping, over
all particles and beams at once (``laser_model_type: likelihood_field_prob``,
``nav2_amcl/src/sensors/laser/likelihood_field_model_prob.cpp``).

Each beam's ``pz = z_hit * exp(-d^2 / 2 sigma_hit^2) + z_rand / range_max`` is the
one :mod:`.laser_model`'s ``likelihood_field`` uses (``d`` the distance of the
beam's end point to the nearest obstacle, capped at ``laser_likelihood_max_dist``;
off the map, the cap), but the beams combine as a probability: a particle's
weight is multiplied by ``exp(sum log pz)``, the product over its beams, where
``likelihood_field`` adds ``1 + sum pz^3``. The product tells poses apart far more
sharply (a beam 0.4 m off costs a factor of about 7, not a term of the sum).

Beam skipping (``do_beamskip``), only once the filter has converged (``pf.c``'s
flag: every particle within 0.5 m of the mean in x and y after the last
resample): a beam counts for a particle when its end point is on the map and
less than ``beam_skip_distance`` from an obstacle; beams that count for at most
``beam_skip_threshold`` of the particles are left out for every particle (an
obstacle the map does not have, a person). If ``beam_skip_error_threshold`` or
more of the ``max_beams`` would be left out (beams the scan lacks, max-range
readings among them, count as left out, as in AMCL) the filter has probably
converged on a wrong pose, and all beams are used.

The range: ``pz`` lies between ``z_rand / range_max`` and ``z_hit + z_rand /
range_max``, so 60 beams give ``exp`` of -190 to -37 with Nav2's defaults and a
12 m lidar, in range for doubles (down to ``exp(-745)``) but not far from its end:
past about 230 beams the worst-fitting particles underflow to 0, past about 1,200
every particle does (AMCL then falls back to uniform weights). Here the log sums
are shifted by their maximum before ``exp`` (the best particle's factor is 1) and
the shift is returned as :class:`.Likelihood`'s ``log_scale``: the normalised
weights are the same, and the mean likelihood the recovery averages need is
``sum * exp(log_scale)``.

Two differences from the C++: the end points fall in the cell they are in (as in
``likelihood_field`` here; AMCL's ``MAP_GXWX`` rounds, half a cell off); in the
all-beams fallback AMCL also reads the per-beam buffer for beams the scan lacks
(left at 0 or at an older scan's value: log 0 zeroes every weight), here only
the scan's beams are used.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .laser_model import Beams, Likelihood, end_points
from .likelihood_field import LikelihoodField
from .se2 import FloatArray


@dataclass(slots=True, frozen=True)
class BeamSkip:
    """``beam_skip_distance``, ``beam_skip_threshold``, ``beam_skip_error_threshold``."""

    distance: float
    threshold: float
    error_threshold: float


@dataclass(slots=True, frozen=True)
class LikelihoodFieldProbModel:
    """``z_rand`` over a likelihood field built with ``z_hit`` and ``sigma_hit``;
    ``beam_skip`` None when ``do_beamskip`` is false."""

    field: LikelihoodField
    z_rand: float
    max_beams: int
    beam_skip: BeamSkip | None = None

    def weigh(self, particles: FloatArray, beams: Beams, *, converged: bool) -> Likelihood:
        """``exp(sum log pz)`` over the beams used, for each particle (rows ``x, y,
        yaw``), scaled so that the largest is 1."""
        if beams.ranges.size == 0 or len(particles) == 0:
            return Likelihood(np.ones(len(particles)), 0.0)
        hx, hy = end_points(particles, beams)
        index = self.field.flat_index(hx, hy)
        pz = self.field.padded[index] + np.float32(self.z_rand / beams.range_max)
        log_pz = np.log(pz)
        if self.beam_skip is not None and converged:
            used = self.used_beams(self.field.padded_dist[index], self.beam_skip)
            log_pz = log_pz[:, used]
        log_p = np.sum(log_pz, axis=1, dtype=np.float64)
        top = float(log_p.max())
        return Likelihood(np.exp(log_p - top), top)

    def used_beams(self, dist: npt.NDArray[np.float32], skip: BeamSkip) -> npt.NDArray[np.bool_]:
        """Which of the scan's beams to integrate, from the end points' distances to
        the nearest obstacle (particles, beams; +inf off the map)."""
        agreeing = np.count_nonzero(dist < skip.distance, axis=0) / dist.shape[0]
        used: npt.NDArray[np.bool_] = agreeing > skip.threshold
        skipped = self.max_beams - int(np.count_nonzero(used))
        if skipped >= self.max_beams * skip.error_threshold:
            return np.ones(len(used), dtype=np.bool_)  # converged on a wrong pose? all beams
        return used
