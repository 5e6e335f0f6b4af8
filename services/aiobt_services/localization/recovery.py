"""AMCL's short- and long-term averages of the measurement likelihood (Augmented
MCL, Probabilistic Robotics p. 258): when the short-term average drops below the
long-term one the robot is probably not where the particles are, and a share
``1 - w_fast / w_slow`` of the next resample is drawn at random from free space.

One deliberate difference from ``pf.c``: the average folded in is the mean
likelihood of the measurement under the particles (the weighted sum of the
sensor model's factors, the prior weights summing to 1), as Probabilistic
Robotics defines it. AMCL folds in the sum of the unnormalised weights divided
by the particle count, which carries a factor 1/N: when KLD sampling grows the
set from 500 to 2,000 particles its average drops fourfold without any change
in how well the scans fit, and after the set shrinks a kidnap must cut the fit
by more than that before recovery starts (in the office world it never did).
``bench.localization.kidnap`` measured both (recovery 0.05 / 0.5): 9 of 20
kidnaps found with this average, 6 of 20 with ``pf.c``'s.

``pf_update_resample`` also zeroes both averages after every resample that
drew random particles ("to avoid spiraling off into complete randomness"). The
first resample after the fit drops then draws only ``1 - w_fast / w_slow`` at
the moment ``w_fast`` crosses below ``w_slow`` (with ``recovery_alpha_fast``
0.1, a tenth of the drop), and the next update restarts both averages at the
lost robot's fit, so nothing more is drawn unless the fit drops further: one
small burst per kidnap, whichever alphas are set. ``recovery_reset_after_injection``
(not a Nav2 parameter; default true, ``pf.c``'s behaviour) set false keeps the
averages, as Augmented MCL itself does (Probabilistic Robotics, Table 8.3):
random particles keep coming while the short-term fit stays below the long-term
one, until ``w_slow`` has settled at the new fit. In the office world
(``bench.localization.kidnap``, 20 seeded 3 m kidnaps, 30 s): with Nav2's
suggested 0.001 / 0.1, 1 found with the reset, 12 without; 0.01 / 0.2 without
the reset, 17 (median 9.7 s). The price, either way: the averages cannot tell a
kidnap from obstacles that are not on the map, and on a long drive past such
boxes (``kidnap --corridor 400``) the random particles moved a robot that was
never lost metres away. ``recovery_min_long_beams`` (not a Nav2 parameter,
:mod:`.long_beams`) tells the two apart by the sign of the scan's misfit and lets
random particles in only on a kidnap's evidence (figures in
``config/sim_robot.yaml``, which ships recovery off all the same).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(slots=True)
class RecoveryAverages:
    """``recovery_alpha_slow`` / ``recovery_alpha_fast`` (0 and 0: recovery off)."""

    alpha_slow: float
    alpha_fast: float
    w_slow: float = 0.0
    w_fast: float = 0.0

    def update(self, w_avg: float) -> None:
        """Fold in the measurement's mean likelihood (``pf_update_sensor``'s ``w_avg``)."""
        self.w_slow = (
            w_avg if self.w_slow == 0.0 else self.w_slow + self.alpha_slow * (w_avg - self.w_slow)
        )
        self.w_fast = (
            w_avg if self.w_fast == 0.0 else self.w_fast + self.alpha_fast * (w_avg - self.w_fast)
        )

    @property
    def w_diff(self) -> float:
        """The share of random particles the next resample gets."""
        if self.w_slow <= 0.0:
            return 0.0
        return max(0.0, 1.0 - self.w_fast / self.w_slow)

    def reset(self) -> None:
        """After random particles went in: AMCL resets both, 'to avoid spiraling off
        into complete randomness'."""
        self.w_slow = self.w_fast = 0.0
