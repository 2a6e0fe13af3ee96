"""Inlet shear-heating reduction factor of the EHL film and rolling force (Gupta et al. 1992).

phi_T = [1 - 13.2 (p_h/E') L^0.42] / [1 + 0.213 (1 + 2.23 |S|^0.83) L^0.64], L = eta0 beta u^2/k
(Gupta, Cheng, Zhu, Forster & Schrand, Tribol. Trans. 35 (1992) 269-274, as quoted by Zhou &
Hoeprich 1991 eqs. 21-22 and Wingertszahn et al. 2023 eqs. 12-14; the expression is that of
shared/reference/friction_literature.md). Kernels :func:`sim.physics.ehl.film_thermal_factor_gupta`
and :func:`sim.physics.ehl.thermal_loading`. Limits and monotonicity of the published form, one
value evaluated by hand, and the size of L for the project's oil.
"""
from pathlib import Path

import numpy as np
import pytest
from omegaconf import OmegaConf

from sim.physics import ehl
from sim.physics.lubricant import Lubricant

REPO = Path(__file__).resolve().parents[2]
EP = 228000.0       # MPa
PH = 1000.0         # MPa


def test_no_heating_no_reduction():
    """L = 0 (isothermal): phi_T = 1 exactly, at any slip; L -> 0 continuously (the L^0.42 term
    dominates: 1 - phi_T ~ 13.2 (p_h/E') L^0.42, below 1e-4 at L = 1e-8)."""
    for S in (0.0, 0.1, 1.0):
        assert ehl.film_thermal_factor_gupta(PH, EP, 0.0, S) == 1.0
        assert 1.0 - 1e-4 < ehl.film_thermal_factor_gupta(PH, EP, 1e-8, S) < 1.0


def test_decreasing_in_thermal_loading_and_slip():
    """phi_T falls strictly with L (numerator falls, denominator rises) and with |S|
    (denominator), symmetric in the sign of S; on 0 < L <= 10, 0 <= |S| <= 2 it stays in (0, 1)."""
    Ls = np.logspace(-4, 1, 60)
    for S in (0.0, 0.05, 0.3, 2.0):
        phi = np.array([ehl.film_thermal_factor_gupta(PH, EP, L, S) for L in Ls])
        assert np.all(np.diff(phi) < 0.0) and np.all((phi > 0.0) & (phi < 1.0))
    for L in (0.01, 0.3, 3.0):
        phi = [ehl.film_thermal_factor_gupta(PH, EP, L, S) for S in (0.0, 0.01, 0.1, 0.5, 1.0)]
        assert np.all(np.diff(phi) < 0.0)
        assert ehl.film_thermal_factor_gupta(PH, EP, L, -0.2) == ehl.film_thermal_factor_gupta(PH, EP, L, 0.2)


def test_value_by_hand():
    """p_h/E' = 1000/228000, L = 1, S = 0: (1 - 13.2 * 0.0043860) / (1 + 0.213) = 0.94211/1.213
    = 0.77668 (hand arithmetic, 5 digits); S = 1, L = 1: 0.94211/(1 + 0.213 * 3.23) = 0.55812."""
    assert ehl.film_thermal_factor_gupta(PH, EP, 1.0, 0.0) == pytest.approx(0.77668, abs=1e-5)
    assert ehl.film_thermal_factor_gupta(PH, EP, 1.0, 1.0) == pytest.approx(0.55812, abs=1e-5)


def test_floored_at_zero_beyond_the_fitted_range():
    """The numerator vanishes at L = (E'/(13.2 p_h))^(1/0.42) (~7e3 here, far beyond any bearing);
    the kernel returns 0 there instead of a negative factor."""
    L0 = (EP / (13.2 * PH)) ** (1 / 0.42)
    assert ehl.film_thermal_factor_gupta(PH, EP, 1.01 * L0, 0.0) == 0.0
    assert ehl.film_thermal_factor_gupta(PH, EP, 0.99 * L0, 0.0) > 0.0


def test_thermal_loading_of_fva3_is_of_order_0p1_to_1_at_bearing_speeds():
    """FVA 3 (conf/lubricant/fva3.yaml) at 50 degC: eta0 ~ 50 mPa s, beta ~ 0.04/K, k = 0.13
    W/(m K); L = eta0 beta u^2/k = 0.05 * 0.04 * 25 / 0.13 ~ 0.4 at u = 5 m/s (hand estimate).
    The kernel, in kernel units (eta0 MPa s, u mm/s), agrees with that estimate in SI to 1e-12
    relative (a unit slip of 1e6 would be caught), and phi_T at 5 m/s, 1 GPa is 0.8-0.95."""
    lub = Lubricant.from_config(OmegaConf.to_container(OmegaConf.load(REPO / "conf" / "lubricant" / "fva3.yaml")))
    eta0_SI = float(lub.dynamic_viscosity(50.0))                # Pa s
    beta = float(lub.temperature_viscosity_coefficient(50.0))   # 1/K
    k = lub.thermal_conductivity
    L = ehl.thermal_loading(eta0_SI * 1e-6, beta, 5000.0, k)
    assert L == pytest.approx(eta0_SI * beta * 5.0 ** 2 / k, rel=1e-12)
    assert 0.1 < L < 1.0, L
    assert 0.8 < ehl.film_thermal_factor_gupta(PH, EP, L, 0.0) < 0.95
