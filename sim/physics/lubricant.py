"""Lubricant properties at the oil temperature of a load case (MODEL.md 5).

Viscosity-temperature: Ubbelohde-Walther, DIN 51563 / ASTM D341,
``log10(log10(nu + 0.7)) = A - B log10(T)`` with nu in mm^2/s and T in K, fitted through the
points of the lubricant config (two points) or through one point with a given slope B.
Density: linear in temperature. Pressure-viscosity: Barus or Roelands with the Barus coefficient
as its initial slope (:func:`sim.physics.ehl.pressure_viscosity`); that coefficient holds at
``pressure_viscosity_temperature`` and, with ``pressure_viscosity_temperature_law: roelands``, follows
Roelands' temperature-independent pressure-viscosity index elsewhere (:meth:`Lubricant.pressure_viscosity_at`).
Every parameter comes from ``conf/lubricant/*.yaml``.
"""
from dataclasses import dataclass

import numpy as np

from sim.config_schema import LubricantConfig, check_node, field_check
from sim.errors import InputError
from sim.physics.ehl import ROELANDS_ETA_INF

#: Walther's constant [mm^2/s] (DIN 51563, ASTM D341).
WALTHER_SHIFT = 0.7
#: 0 degC in K.
ZERO_CELSIUS = 273.15
#: MPa s per Pa s (the Roelands constants of :mod:`sim.physics.ehl` are in MPa s).
MPA_S_PER_PA_S = 1e-6
#: Allowed Walther slopes B [1]: the schema's range of lubricant.walther_slope, also for a fitted one.
WALTHER_SLOPE = field_check(LubricantConfig, "walther_slope")


def _walther(nu):
    return np.log10(np.log10(nu + WALTHER_SHIFT))


@dataclass(frozen=True)
class Lubricant:
    """Oil of one ``lubricant`` config node.

    Attributes: Walther constants ``A``, ``B`` [1]; density [kg/m^3] at ``density_temperature``
    [degC] with ``density_slope`` [kg/(m^3 K)]; Barus ``pressure_viscosity`` [1/MPa] at
    ``pressure_viscosity_temperature`` [degC], its ``pressure_viscosity_temperature_law``
    ('constant' or 'roelands', :meth:`pressure_viscosity_at`) and the
    ``pressure_viscosity_model`` of the traction ('barus' or 'roelands'); limiting
    shear stress ``tau_L = limiting_shear_stress_0 + limiting_shear_coefficient p`` [MPa]; the
    elastic ``shear_modulus`` of the film [MPa] (Maxwell traction at low slip); the film's
    ``thermal_conductivity`` [W/(m K)] (shear heating, :mod:`sim.physics.friction`); the
    ``eyring_stress`` tau_E0 [MPa] of the Maxwell-Eyring traction law
    (:func:`sim.physics.ehl.traction_eyring`) at ``pressure_viscosity_temperature``, and its
    ``eyring_stress_temperature_law`` ('constant' or 'bair_winer', :meth:`eyring_stress_at`).
    """

    name: str
    A: float
    B: float
    density_temperature: float
    density_ref: float
    density_slope: float
    pressure_viscosity: float
    pressure_viscosity_temperature: float
    pressure_viscosity_temperature_law: str
    pressure_viscosity_model: str
    limiting_shear_stress_0: float
    limiting_shear_coefficient: float
    shear_modulus: float
    thermal_conductivity: float
    eyring_stress: float
    eyring_stress_temperature_law: str

    @classmethod
    def from_config(cls, lub):
        """Build from the ``lubricant`` config node.

        Each key is checked against its schema (:mod:`sim.config_schema`) first: a missing key
        or a value outside its range raises :class:`InputError` naming them all, with value and
        allowed range. Then the viscosity points: one or two, falling with temperature, and
        either a fitted or a given Walther slope in ``walther_slope``'s range.
        """
        check_node(LubricantConfig, lub, "lubricant", error=InputError)
        T = [float(t) for t in lub["temperature"]]
        nu = [float(v) for v in lub["viscosity"]]
        if len(T) != len(nu) or not 1 <= len(T) <= 2:
            raise InputError(f"lubricant.temperature / lubricant.viscosity: need one or two matching points, "
                             f"got {len(T)} temperatures and {len(nu)} viscosities")
        logT = [np.log10(t + ZERO_CELSIUS) for t in T]
        if len(T) == 2:
            if T[0] == T[1] or (nu[0] - nu[1]) * (T[1] - T[0]) <= 0.0:
                raise InputError(f"lubricant.viscosity = {nu} must fall with lubricant.temperature = {T}")
            if lub.get("walther_slope") is not None:
                raise InputError("lubricant.walther_slope must be null when two viscosity points are given "
                                 "(the slope is fitted through them)")
            B = (_walther(nu[0]) - _walther(nu[1])) / (logT[1] - logT[0])
            if not WALTHER_SLOPE.accepts(B):
                raise InputError(f"lubricant.viscosity = {nu} at {T} degC gives a Walther slope {B:.4g}: it must be "
                                 f"{WALTHER_SLOPE} (lubricant.walther_slope's range, mineral and synthetic oils)")
        else:
            if lub.get("walther_slope") is None:
                raise InputError("lubricant.walther_slope is required when only one viscosity point is given")
            B = float(lub["walther_slope"])
        A = _walther(nu[0]) + B * logT[0]
        return cls(str(lub["name"]), A, B, float(lub["density_temperature"]), float(lub["density"]),
                   float(lub["density_slope"]), float(lub["pressure_viscosity"]),
                   float(lub["pressure_viscosity_temperature"]), str(lub["pressure_viscosity_temperature_law"]),
                   str(lub["pressure_viscosity_model"]),
                   float(lub["limiting_shear_stress_0"]), float(lub["limiting_shear_coefficient"]),
                   float(lub["shear_modulus"]), float(lub["thermal_conductivity"]), float(lub["eyring_stress"]),
                   str(lub["eyring_stress_temperature_law"]))

    def kinematic_viscosity(self, temperature):
        """nu [mm^2/s] at ``temperature`` [degC] (Ubbelohde-Walther, DIN 51563)."""
        w = self.A - self.B * np.log10(np.asarray(temperature, dtype=float) + ZERO_CELSIUS)
        return 10.0 ** (10.0 ** w) - WALTHER_SHIFT

    def density(self, temperature):
        """rho [kg/m^3] at ``temperature`` [degC], linear in temperature."""
        return self.density_ref + self.density_slope * (np.asarray(temperature, dtype=float) - self.density_temperature)

    def dynamic_viscosity(self, temperature):
        """eta0 [Pa s] = nu rho at ambient pressure and ``temperature`` [degC]."""
        return self.kinematic_viscosity(temperature) * 1e-6 * self.density(temperature)

    def temperature_viscosity_coefficient(self, temperature):
        """beta = -d ln(eta0)/dT [1/K] at ``temperature`` [degC]: the local exponential
        (Reynolds) slope of the Ubbelohde-Walther line and the density law.

        With w = A - B log10(T_K) and nu + 0.7 = 10^(10^w):
        d nu/dT = -(nu + 0.7) ln(10) 10^w B / T_K, and d ln(eta0)/dT = (d nu/dT)/nu + (d rho/dT)/rho.
        """
        T_K = np.asarray(temperature, dtype=float) + ZERO_CELSIUS
        nu = self.kinematic_viscosity(temperature)
        w = self.A - self.B * np.log10(T_K)
        dnu = -(nu + WALTHER_SHIFT) * np.log(10.0) * 10.0 ** w * self.B / T_K
        return -(dnu / nu + self.density_slope / self.density(temperature))

    def pressure_viscosity_at(self, temperature):
        """Barus pressure-viscosity coefficient alpha [1/MPa] at ``temperature`` [degC]:
        ``pressure_viscosity`` at every temperature ('constant') or, at
        ``pressure_viscosity_temperature``, then with Roelands' temperature-independent index
        (:func:`pressure_viscosity_roelands`, 'roelands'). So a hotter, thinner oil stiffens less
        with pressure, as the traction's film temperature already assumes
        (:func:`sim.physics.ehl.pressure_viscosity` at the film's viscosity with the bulk oil's Z).
        """
        alpha = np.full(np.shape(temperature), self.pressure_viscosity)
        if self.pressure_viscosity_temperature_law == "roelands":
            # Walther's nu + 0.7 = 10^(10^w) > 1 mm^2/s keeps eta above eta_inf at any density above 211 kg/m^3
            eta = self.dynamic_viscosity(temperature) * MPA_S_PER_PA_S
            eta_ref = self.dynamic_viscosity(self.pressure_viscosity_temperature) * MPA_S_PER_PA_S
            alpha = pressure_viscosity_roelands(alpha, eta, eta_ref)
        return alpha[()] if alpha.ndim == 0 else alpha

    def eyring_stress_at(self, temperature):
        """Eyring stress tau_E0 [MPa] at ``temperature`` [degC]: ``eyring_stress`` at every
        temperature ('constant') or, with 'bair_winer', tau_E0 = 2 Lambda / alpha (Bair & Winer 1979;
        Arana, Larranaga & Ulacia 2019, eqs. 12-13, from Eyring's theory: tau_E = k Theta / v_tau
        and alpha = v_p / (k Theta), so tau_E = (v_p / v_tau) / alpha): ``eyring_stress`` at
        ``pressure_viscosity_temperature``, elsewhere in proportion to 1 / :meth:`pressure_viscosity_at`.
        """
        tau = np.full(np.shape(temperature), self.eyring_stress)
        if self.eyring_stress_temperature_law == "bair_winer":
            tau = tau * self.pressure_viscosity / self.pressure_viscosity_at(temperature)
        return tau[()] if tau.ndim == 0 else tau


def pressure_viscosity_roelands(alpha_ref, eta, eta_ref):
    """Pressure-viscosity coefficient [unit of ``alpha_ref``] of an oil at the temperature where its
    ambient viscosity is ``eta``, given ``alpha_ref`` where it is ``eta_ref`` (both [MPa s]).

    Roelands' (1966) viscosity-temperature-pressure relation holds an oil's pressure-viscosity
    index Z independent of temperature, and its slope at p = 0 is alpha = Z ln(eta0/eta_inf) / p_R
    (Hamrock, Schmid & Jacobson 2004, ch. 4; :func:`sim.physics.ehl.roelands_index`), so

        alpha = alpha_ref ln(eta/eta_inf) / ln(eta_ref/eta_inf),   eta_inf = 6.31e-5 Pa s.

    Against 13 mineral oils at 30 and 100 degC from their 60 degC value (Stachowiak & Batchelor,
    Table 2.3): median error 3 %, where a constant alpha errs by 24 %
    (tests/friction/test_pressure_viscosity_temperature.py).
    """
    return alpha_ref * np.log(eta / ROELANDS_ETA_INF) / np.log(eta_ref / ROELANDS_ETA_INF)
