"""The filter with ``laser_model_type: likelihood_field_prob`` (its tracking:
``test_amcl``): it keeps ``pf.c``'s ``converged`` flag for beam skipping, and feeds the
recovery averages the unscaled mean likelihood."""

import math

import numpy as np
import pytest

from aiobt_services.localization.amcl import Amcl, converged
from aiobt_services.localization.laser_model import Beams, Likelihood, select_beams
from aiobt_services.localization.likelihood_field_prob import LikelihoodFieldProbModel
from aiobt_services.localization.params import AmclParams

from .maps import cast, field, room

BEARINGS = -np.pi + 2 * np.pi / 360 * np.arange(360, dtype=np.float64)
CELLS = room()
PROB = {"laser_model_type": "likelihood_field_prob", "update_min_d": 0.05, "update_min_a": 0.05}


def _filter(**params: object) -> Amcl:
    amcl = Amcl(AmclParams.from_mapping({"random_seed": 7, **PROB, **params}))
    amcl.set_map(field(CELLS))
    return amcl


def _beams(truth: np.ndarray) -> Beams:
    return select_beams(cast(CELLS, tuple(truth), BEARINGS), BEARINGS, max_beams=60,
                        range_min=0.05, range_max=12.0,
                        laser_model_type="likelihood_field_prob")  # fmt: skip


def test_the_filter_uses_the_model_laser_model_type_names() -> None:
    assert isinstance(_filter().laser, LikelihoodFieldProbModel)
    model = _filter(do_beamskip=True, beam_skip_distance=0.3).laser
    assert isinstance(model, LikelihoodFieldProbModel)
    assert model.beam_skip is not None
    assert model.beam_skip.distance == 0.3
    assert isinstance(_filter(do_beamskip=False).laser, LikelihoodFieldProbModel)
    assert _filter(do_beamskip=False).laser.beam_skip is None  # type: ignore[union-attr]


def test_converged_is_every_particle_within_half_a_metre_of_the_mean_in_x_and_y() -> None:
    tight = np.array([[1.0, 1.0, 0.0], [1.4, 1.0, 3.0], [1.0, 0.6, -3.0]])
    assert converged(tight)
    assert not converged(np.vstack([tight, [[2.2, 1.0, 0.0]]]))
    assert not converged(np.zeros((0, 3)))


def test_the_flag_is_set_at_resamples_and_cleared_at_resets(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    amcl = _filter(do_beamskip=True)
    seen: list[bool] = []
    real = LikelihoodFieldProbModel.weigh

    def spy(
        model: LikelihoodFieldProbModel, p: np.ndarray, b: Beams, *, converged: bool
    ) -> Likelihood:
        seen.append(converged)
        return real(model, p, b, converged=converged)

    monkeypatch.setattr(LikelihoodFieldProbModel, "weigh", spy)
    truth = np.array([1.0, 3.0, 0.0])
    amcl.initialize(amcl.check_pose(1.0, 3.0, 0.0, np.diag([0.01, 0.01, 0.01])))
    assert not amcl.converged
    amcl.on_scan(np.zeros(3), _beams(truth))
    assert amcl.converged  # the first resample: a set 0.1 m wide
    amcl.on_scan(np.array([0.1, 0.0, 0.0]), _beams(truth + np.array([0.1, 0.0, 0.0])))
    assert seen == [False, True]
    amcl.global_localization()
    assert not amcl.converged


def test_the_recovery_averages_get_the_unscaled_mean_likelihood() -> None:
    amcl = _filter(recovery_alpha_slow=0.001, recovery_alpha_fast=0.1)
    truth = np.array([1.0, 3.0, 0.0])
    amcl.initialize(amcl.check_pose(*truth))
    particles, beams = amcl.particles.copy(), _beams(truth)
    amcl.on_scan(np.zeros(3), beams)
    angle = particles[:, 2:3] + beams.bearings
    hx = particles[:, 0:1] + beams.ranges * np.cos(angle)
    hy = particles[:, 1:2] + beams.ranges * np.sin(angle)
    pz = amcl.field.hit_terms(hx, hy) + 0.5 / 12.0  # type: ignore[union-attr]
    expected = float(np.mean(np.exp(np.sum(np.log(pz.astype(np.float64)), axis=1))))
    assert 1e-60 < expected < 1e-10  # far from 1: the scale matters
    assert math.isclose(amcl.recovery.w_slow, expected, rel_tol=1e-3)
