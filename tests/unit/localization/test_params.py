import pytest

from aiobt_services.localization.params import AmclParams, InitialPose, ParamError


def test_defaults_are_nav2s() -> None:
    p = AmclParams()
    assert (p.alpha1, p.alpha2, p.alpha3, p.alpha4) == (0.2, 0.2, 0.2, 0.2)
    assert (p.min_particles, p.max_particles, p.pf_err, p.pf_z) == (500, 2000, 0.05, 0.99)
    assert (p.z_hit, p.z_rand, p.sigma_hit, p.laser_likelihood_max_dist) == (0.5, 0.5, 0.2, 2.0)
    assert (p.max_beams, p.update_min_d, p.update_min_a, p.resample_interval) == (60, 0.25, 0.2, 1)
    assert (p.recovery_alpha_slow, p.recovery_alpha_fast, p.do_beamskip) == (0.0, 0.0, False)
    assert p.recovery_reset_after_injection  # not Nav2's name; pf.c's behaviour by default
    assert p.recovery_min_long_beams == 0.0  # not Nav2's name; no gate, as pf.c
    assert p.laser_model_type == "likelihood_field"
    assert (p.beam_skip_distance, p.beam_skip_threshold, p.beam_skip_error_threshold) == (
        0.5,
        0.3,
        0.9,
    )


def test_the_prob_model_takes_beam_skipping() -> None:
    p = AmclParams.from_mapping(
        {"laser_model_type": "likelihood_field_prob", "do_beamskip": True,
         "beam_skip_distance": 0.3, "beam_skip_threshold": 0.5, "beam_skip_error_threshold": 1.0}
    )  # fmt: skip
    assert (p.laser_model_type, p.do_beamskip, p.beam_skip_error_threshold) == (
        "likelihood_field_prob",
        True,
        1.0,
    )


def test_a_nav2_params_mapping_loads_with_dotted_and_nested_initial_pose() -> None:
    p = AmclParams.from_mapping(
        {"use_sim_time": True, "max_particles": 3000, "recovery_alpha_slow": 0.001,
         "initial_pose": {"x": 1, "y": 2.0, "yaw": 0.5}, "set_initial_pose": True}
    )  # fmt: skip
    assert p.max_particles == 3000
    assert p.recovery_alpha_slow == 0.001
    assert p.initial_pose == InitialPose(1.0, 2.0, 0.0, 0.5)
    assert p.set_initial_pose
    assert AmclParams.from_mapping({"initial_pose.x": 4}).initial_pose.x == 4.0
    kept = AmclParams.from_mapping({"recovery_reset_after_injection": False})
    assert not kept.recovery_reset_after_injection


@pytest.mark.parametrize(
    ("values", "names"),
    [
        ({"max_particls": 3}, "max_particls"),
        ({"min_particles": 3000}, "min_particles"),
        ({"pf_err": 0.0}, "pf_err"),
        ({"sigma_hit": -1.0}, "sigma_hit"),
        (
            {"do_beamskip": True},
            "do_beamskip: true does nothing with laser_model_type 'likelihood_field'",
        ),
        (
            {"laser_model_type": "beam"},
            "laser_model_type 'beam': Nav2's beam model .* is not implemented here",
        ),
        (
            {"laser_model_type": "likelihood"},
            "laser_model_type 'likelihood': must be one of "
            "'likelihood_field', 'likelihood_field_prob'",
        ),
        ({"beam_skip_distance": -0.1}, "beam_skip_distance must be finite and >= 0"),
        ({"beam_skip_threshold": 1.5}, "beam_skip_threshold must be finite and >= 0 and <= 1"),
        ({"beam_skip_error_threshold": float("nan")}, "beam_skip_error_threshold"),
        ({"robot_model_type": "nav2_amcl::OmniMotionModel"}, "robot_model_type"),
        ({"max_beams": "60"}, "max_beams"),
        ({"alpha1": float("nan")}, "alpha1"),
        ({"recovery_min_long_beams": 1.5}, "recovery_min_long_beams"),
        ({"recovery_min_long_beams": -0.1}, "recovery_min_long_beams"),
        ({"recovery_min_long_beams": 0.1, "laser_likelihood_max_dist": 0.4}, "2 sigma_hit"),
    ],
)
def test_bad_parameters_are_refused_by_name(values: dict[str, object], names: str) -> None:
    with pytest.raises(ParamError, match=names):
        AmclParams.from_mapping(values)
