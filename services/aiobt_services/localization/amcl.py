"""The particle filter as ``amcl_node`` runs it, on plain arrays: no transport,
no clock. One call per scan (:meth:`Amcl.on_scan`) with the odometry pose the
scan was taken at; the caller publishes what it returns.

Flow per scan (``laserReceived``): the first scan after an initialisation only
records the odometry; later ones move the particles by the odometry since the
last update (:mod:`.motion_model`) once it exceeds ``update_min_d`` (in x or y)
or ``update_min_a``, or when a no-motion update was requested; then weigh them
(``laser_model_type``: :mod:`.laser_model` or :mod:`.likelihood_field_prob`),
update the recovery averages, and every ``resample_interval`` updates resample
(:mod:`.resample`). The estimate, the ``map`` -> ``odom`` correction and
``pf.c``'s ``converged`` flag (beam skipping waits for it) are recomputed after
each resample.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np

from . import se2
from .estimate import Estimate, estimate
from .initial_pose import DEFAULT_COVARIANCE, InitialPose, checked, sample
from .laser_model import Beams, LaserModel, LikelihoodFieldModel
from .likelihood_field import LikelihoodField
from .likelihood_field_prob import BeamSkip, LikelihoodFieldProbModel
from .long_beams import MARGIN_SIGMAS, long_beam_share
from .motion_model import DifferentialMotionModel
from .params import AmclParams
from .recovery import RecoveryAverages
from .resample import resample
from .se2 import FloatArray

log = logging.getLogger("aiobt_services.localization.amcl")

LOG_DOUBLE_MAX = 709.0  # math.exp raises above ~709.78
CONVERGED_DIST = 0.5  # pf.c's dist_threshold: converged when every particle is this near


def laser_model(params: AmclParams, field: LikelihoodField) -> LaserModel:
    """The model ``laser_model_type`` names (``amcl_node``'s ``createLaserObject``)."""
    if params.laser_model_type == "likelihood_field_prob":
        skip = BeamSkip(
            params.beam_skip_distance,
            params.beam_skip_threshold,
            params.beam_skip_error_threshold,
        )
        return LikelihoodFieldProbModel(
            field, params.z_rand, params.max_beams, skip if params.do_beamskip else None
        )
    return LikelihoodFieldModel(field, params.z_rand)


def converged(particles: FloatArray) -> bool:
    """``pf_update_converged``: every particle within ``CONVERGED_DIST`` of the
    mean position in x and in y."""
    if len(particles) == 0:
        return False
    spread = np.abs(particles[:, :2] - particles[:, :2].mean(axis=0))
    return bool(np.all(spread <= CONVERGED_DIST))


@dataclass(slots=True, frozen=True)
class ScanOutcome:
    """What one scan did: ``updated`` (motion + weighing ran), ``resampled``, and,
    when the estimate changed, the new ``estimate`` and ``map_to_odom``."""

    updated: bool
    resampled: bool
    estimate: Estimate | None = None
    map_to_odom: FloatArray | None = None


class Amcl:
    """Particles, weights and AMCL's bookkeeping for one map."""

    def __init__(self, params: AmclParams, rng: np.random.Generator | None = None) -> None:
        self.params = params
        seed = None if params.random_seed < 0 else params.random_seed
        self.rng = rng if rng is not None else np.random.default_rng(seed)
        self.motion = DifferentialMotionModel(
            params.alpha1, params.alpha2, params.alpha3, params.alpha4
        )
        self.recovery = RecoveryAverages(params.recovery_alpha_slow, params.recovery_alpha_fast)
        self.field: LikelihoodField | None = None
        self.laser: LaserModel | None = None
        self.converged = False  # pf.c's flag: set at each resample, cleared at each reset
        self.particles = np.zeros((0, 3))
        self.weights = np.zeros(0)
        self.last_estimate: Estimate | None = None
        self.map_to_odom: FloatArray | None = None
        self._odom_ref: FloatArray | None = None  # AMCL's pf_odom_pose_ (None: pf_init_ false)
        self._force_update = False
        self._resample_count = 0
        self.long_beams = 0.0  # the last gate's share of long beams (long_beams.py)

    # -- inputs other than scans ----------------------------------------
    def set_map(self, field: LikelihoodField) -> None:
        """Use ``field`` from now on (a new map keeps the particles, as AMCL does
        unless ``always_reset_initial_pose``)."""
        self.field = field
        self.laser = laser_model(self.params, field)

    @property
    def initialized(self) -> bool:
        """Has the filter been given a pose (or told to localize globally)?"""
        return len(self.particles) > 0

    def check_pose(
        self,
        x: float,
        y: float,
        yaw: float,
        covariance: FloatArray | None = None,
        where: str = "initial pose",
    ) -> InitialPose:
        """The pose checked against the map (raises :class:`InitialPoseError`)."""
        cov = DEFAULT_COVARIANCE if covariance is None else covariance
        return checked(x, y, yaw, cov, self.field, where)

    def initialize(self, pose: InitialPose) -> None:
        """``max_particles`` drawn from the pose's Gaussian (``handleInitialPose``)."""
        self._reset(sample(pose, self.params.max_particles, self.rng))
        self.last_estimate = Estimate(pose.mean.copy(), pose.covariance.copy(), 1, 1.0)

    def global_localization(self) -> None:
        """``max_particles`` uniform over the free space, any heading."""
        if self.field is None:
            raise RuntimeError("no map yet: global localization needs the map's free space")
        self._reset(self.field.random_free_poses(self.params.max_particles, self.rng))
        self.last_estimate = estimate(self.particles, self.weights)

    def request_nomotion_update(self) -> None:
        """The next scan updates the filter even if the robot has not moved."""
        self._force_update = True

    def _reset(self, particles: FloatArray) -> None:
        self.particles = particles
        self.weights = np.full(len(particles), 1.0 / len(particles))
        self._odom_ref = None
        self.converged = False
        self.recovery.reset()

    # -- scans -----------------------------------------------------------
    def on_scan(self, odom_pose: FloatArray, beams: Beams) -> ScanOutcome:
        """One scan taken at ``odom_pose`` (x, y, yaw in ``odom``)."""
        if self.laser is None or not self.initialized:
            return ScanOutcome(False, False)
        odom_pose = np.asarray(odom_pose, dtype=np.float64)
        if self._odom_ref is None:  # first scan since (re)initialisation
            self._odom_ref = odom_pose
            self._resample_count = 0
            self._weigh(beams)
            return self._publish(odom_pose, resampled=self._maybe_resample(beams))
        delta = self._delta(odom_pose, self._odom_ref)
        if not (self._moved(delta) or self._force_update):
            return ScanOutcome(False, False)
        self._force_update = False
        self.particles = self.motion.odometry_update(self.particles, odom_pose, delta, self.rng)
        self._odom_ref = odom_pose
        self._weigh(beams)
        resampled = self._maybe_resample(beams)
        if not resampled:
            return ScanOutcome(True, False)
        return self._publish(odom_pose, resampled=True)

    def takes_scan_at(self, odom_pose: FloatArray) -> bool:
        """Whether a scan taken at ``odom_pose`` would update the filter (:meth:`on_scan`
        does more than nothing): the first since (re)initialisation, after enough motion,
        or a no-motion update asked. Standing still, AMCL weighs no scan; the caller
        need not prepare its beams."""
        if self.laser is None or not self.initialized:
            return False
        if self._odom_ref is None or self._force_update:
            return True
        return self._moved(self._delta(np.asarray(odom_pose, dtype=np.float64), self._odom_ref))

    @staticmethod
    def _delta(odom_pose: FloatArray, reference: FloatArray) -> FloatArray:
        """The odometry's motion since ``reference``: dx, dy (in ``odom``), the turn."""
        turn = float(se2.angle_diff(odom_pose[2], reference[2]))
        return np.array([*(odom_pose[:2] - reference[:2]), turn])

    def _moved(self, delta: FloatArray) -> bool:
        """``update_min_d`` in x or y, or ``update_min_a``, exceeded (AMCL's test)."""
        p = self.params
        return bool(np.any(np.abs(delta[:2]) > p.update_min_d) or abs(delta[2]) > p.update_min_a)

    def _weigh(self, beams: Beams) -> None:
        assert self.laser is not None
        factors, log_scale = self.laser.weigh(self.particles, beams, converged=self.converged)
        weights = self.weights * factors
        total = float(weights.sum())
        if total > 0.0 and np.isfinite(total):
            # the prior weights sum to 1, so ``total`` times the model's scale is the
            # measurement's mean likelihood (see :mod:`.recovery` for why not AMCL's
            # ``total / N``); out of doubles' range, the averages are left as they were
            mean_likelihood = total * math.exp(min(log_scale, LOG_DOUBLE_MAX))
            if 0.0 < mean_likelihood < math.inf:
                self.recovery.update(mean_likelihood)
            self.weights = weights / total
        else:
            self.weights = np.full(len(weights), 1.0 / len(weights))

    def _maybe_resample(self, beams: Beams) -> bool:
        self._resample_count += 1
        if self._resample_count % self.params.resample_interval:
            return False
        assert self.field is not None
        w_diff = self.recovery.w_diff
        if w_diff > 0.0 and not self._may_inject(beams):
            w_diff = 0.0
        self.particles = resample(
            self.particles,
            self.weights,
            params=self.params,
            w_diff=w_diff,
            field=self.field,
            rng=self.rng,
        )
        self.weights = np.full(len(self.particles), 1.0 / len(self.particles))
        self.converged = converged(self.particles)
        if w_diff > 0.0 and self.params.recovery_reset_after_injection:
            self.recovery.reset()
        return True

    def _may_inject(self, beams: Beams) -> bool:
        """The long-beam gate (not Nav2's, :mod:`.long_beams`): random particles only
        while enough of the scan's beams reach past the map's walls from the heaviest
        particle and end away from them. Ray cast only here, when the averages ask
        for random particles."""
        if self.params.recovery_min_long_beams <= 0.0:
            return True
        assert self.field is not None
        best = self.particles[int(np.argmax(self.weights))]
        margin = MARGIN_SIGMAS * self.params.sigma_hit
        far = self.params.z_hit * math.exp(-0.5 * MARGIN_SIGMAS**2)
        self.long_beams = long_beam_share(self.field, best, beams, margin, far)
        return self.long_beams >= self.params.recovery_min_long_beams

    def _publish(self, odom_pose: FloatArray, *, resampled: bool) -> ScanOutcome:
        self.last_estimate = estimate(self.particles, self.weights)
        self.map_to_odom = se2.compose(self.last_estimate.mean, se2.inverse(odom_pose))
        return ScanOutcome(True, resampled, self.last_estimate, self.map_to_odom)
