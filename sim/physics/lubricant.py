"""Lubricant properties at the oil temperature of a load case (MODEL.md 5).

Viscosity-temperature: Ubbelohde-Walther, DIN 51563 / ASTM D341,
``log10(log10(nu + 0.7)) = A - B log10(T)`` with nu in mm^2/s and T in K, fitted through the
points of the lubricant config (two points) or through one point with a given slope B.
Density: linear in temperature. Pressure-viscosity: Barus or Roelands with the Barus coefficient
as its initial slope (:func:`sim.physics.ehl.pressure_viscosity`). Every parameter comes from ``conf/lubricant/*.yaml``.
"""
from dataclasses import dataclass

import numpy as np

from sim.errors import InputError

#: Walther's constant [mm^2/s] (DIN 51563, ASTM D341).
WALTHER_SHIFT = 0.7
#: 0 degC in K.
ZERO_CELSIUS = 273.15


def _walther(nu):
    return np.log10(np.log10(nu + WALTHER_SHIFT))


@dataclass(frozen=True)
class Lubricant:
    """Oil of one ``lubricant`` config node.

    Attributes: Walther constants ``A``, ``B`` [1]; density [kg/m^3] at ``density_temperature``
    [degC] with ``density_slope`` [kg/(m^3 K)]; Barus ``pressure_viscosity`` [1/MPa] and the
    ``pressure_viscosity_model`` of the traction ('barus' or 'roelands'); limiting
    shear stress ``tau_L = limiting_shear_stress_0 + limiting_shear_coefficient p`` [MPa]; the
    elastic ``shear_modulus`` of the film [MPa] (Maxwell traction at low slip); the film's
    ``thermal_conductivity`` [W/(m K)] (shear heating, :mod:`sim.physics.friction`); the
    ``eyring_stress`` tau_E0 [MPa] of the Maxwell-Eyring traction law
    (:func:`sim.physics.ehl.traction_eyring`), None where the config has none.
    """

    name: str
    A: float
    B: float
    density_temperature: float
    density_ref: float
    density_slope: float
    pressure_viscosity: float
    pressure_viscosity_model: str
    limiting_shear_stress_0: float
    limiting_shear_coefficient: float
    shear_modulus: float
    thermal_conductivity: float
    eyring_stress: float = None

    @classmethod
    def from_config(cls, lub):
        for key in ("name", "temperature", "viscosity", "density", "density_temperature", "density_slope",
                    "pressure_viscosity", "pressure_viscosity_model", "limiting_shear_coefficient", "limiting_shear_stress_0", "shear_modulus",
                    "thermal_conductivity"):
            if key not in lub:
                raise InputError(f"lubricant.{key} is missing")
        try:
            T = [float(t) for t in lub["temperature"]]
            nu = [float(v) for v in lub["viscosity"]]
        except TypeError:
            raise InputError(f"lubricant.temperature = {lub['temperature']!r} and lubricant.viscosity = "
                             f"{lub['viscosity']!r} must be lists of one or two numbers") from None
        for temp in T:
            if not -40.0 <= temp <= 200.0:
                raise InputError(f"lubricant.temperature = {temp!r} is outside the allowed range [-40, 200] degC")
        if len(T) != len(nu) or not 1 <= len(T) <= 2:
            raise InputError(f"lubricant.temperature / lubricant.viscosity: need one or two matching points, "
                             f"got {len(T)} temperatures and {len(nu)} viscosities")
        for v in nu:
            if not v > 0.0:
                raise InputError(f"lubricant.viscosity = {v!r} is outside the allowed range (0, inf) mm^2/s")
        logT = [np.log10(t + ZERO_CELSIUS) for t in T]
        if len(T) == 2:
            if T[0] == T[1] or (nu[0] - nu[1]) * (T[1] - T[0]) <= 0.0:
                raise InputError(f"lubricant.viscosity = {nu} must fall with lubricant.temperature = {T}")
            if lub.get("walther_slope") is not None:
                raise InputError("lubricant.walther_slope must be null when two viscosity points are given "
                                 "(the slope is fitted through them)")
            B = (_walther(nu[0]) - _walther(nu[1])) / (logT[1] - logT[0])
            if not 1.0 <= B <= 6.0:
                raise InputError(f"lubricant.viscosity = {nu} at {T} degC gives a Walther slope {B:.4g} outside "
                                 f"the allowed range [1, 6] of mineral and synthetic oils")
        else:
            if lub.get("walther_slope") is None:
                raise InputError("lubricant.walther_slope is required when only one viscosity point is given")
            B = float(lub["walther_slope"])
            if not 1.0 <= B <= 6.0:
                raise InputError(f"lubricant.walther_slope = {B!r} is outside the allowed range [1, 6]")
        A = _walther(nu[0]) + B * logT[0]
        alpha_p = float(lub["pressure_viscosity"])
        if not 0.0 <= alpha_p <= 0.1:
            raise InputError(f"lubricant.pressure_viscosity = {alpha_p!r} is outside the allowed range [0, 0.1] 1/MPa")
        pv_model = str(lub["pressure_viscosity_model"])
        if pv_model not in ("barus", "roelands"):
            raise InputError(f"lubricant.pressure_viscosity_model = {pv_model!r} is not one of ['barus', 'roelands']")
        rho = float(lub["density"])
        if not 500.0 <= rho <= 1500.0:
            raise InputError(f"lubricant.density = {rho!r} is outside the allowed range [500, 1500] kg/m^3")
        c = float(lub["limiting_shear_coefficient"])
        if not 0.0 < c <= 0.5:
            raise InputError(f"lubricant.limiting_shear_coefficient = {c!r} is outside the allowed range (0, 0.5]")
        t0 = float(lub["limiting_shear_stress_0"])
        if not 0.0 <= t0 <= 100.0:
            raise InputError(f"lubricant.limiting_shear_stress_0 = {t0!r} is outside the allowed range [0, 100] MPa")
        ds = float(lub["density_slope"])
        if not -5.0 <= ds <= 0.0:
            raise InputError(f"lubricant.density_slope = {ds!r} is outside the allowed range [-5, 0] kg/(m^3 K)")
        G = float(lub["shear_modulus"])
        if not 10.0 <= G <= 1e5:
            raise InputError(f"lubricant.shear_modulus = {G!r} is outside the allowed range [10, 1e5] MPa")
        k = float(lub["thermal_conductivity"])
        if not 0.01 <= k <= 1.0:
            raise InputError(f"lubricant.thermal_conductivity = {k!r} is outside the allowed range [0.01, 1] W/(m K)")
        tau_E = lub.get("eyring_stress")
        if tau_E is not None:
            tau_E = float(tau_E)
            if not 0.0 < tau_E <= 100.0:
                raise InputError(f"lubricant.eyring_stress = {tau_E!r} is outside the allowed range (0, 100] MPa")
        return cls(str(lub["name"]), A, B, float(lub["density_temperature"]), rho, ds, alpha_p, pv_model, t0, c, G, k,
                   tau_E)

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
