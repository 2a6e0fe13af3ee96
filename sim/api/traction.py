"""Traction curve of a lubricant's film law at a twin-disc condition (public helper, issue 14 items 1, 8).

A twin-disc (or ball-on-disc) machine measures the traction coefficient mu = F_t / W of one
EHL contact against the slide-to-roll ratio S = (U1 - U2)/u, u = (U1 + U2)/2, at a fixed
Hertz pressure, entrainment speed and oil temperature. :func:`traction_curve` evaluates the
project's traction laws (:mod:`sim.physics.ehl`) at such a condition so that the law can be
set against a published curve without running a bearing:

- line contact of radius of relative curvature R (rolling direction), Hertz half-width
  b = 4 R p_h / E' and load per length q = pi b p_h / 2 (Hamrock's E' = E/(1 - nu^2) for two
  equal steels, :mod:`sim.physics.ehl`);
- film: the bearing model's film formula (``friction.film_thickness``: Pan & Hamrock central
  film or Dowson & Higginson) at the ambient viscosity of the oil at ``temperature`` and its
  Barus coefficient; isothermal (no inlet shear heating);
- viscosity in the film at each pressure: the lubricant's ``pressure_viscosity_model``
  (Barus or Roelands with the Barus coefficient as its initial slope);
- full film by default (solid load share Phi = 0, polished discs); a given Phi mixes in the
  boundary friction of ``friction.solid_friction_coefficient`` as the bearing model does;
- transit time 2 b / u (Maxwell elastic part of both laws);
- mu(S) = integral of tau(p(x), S u) dx over the Hertz width / (pi b p_h / 2), with the
  Hertz pressure p = p_h cos(t), x = b sin(t), by Gauss-Legendre in t (as the bearing model
  integrates a slice across its width).

The curve is isothermal: the bearing model lowers the film viscosity by each contact's own
shear heating (flash and mid-film temperature, :mod:`sim.physics.friction`), which a twin-disc
curve shows as the fall-off beyond its peak; that is not included here.
"""
import numpy as np

from sim.physics import ehl
from sim.physics import friction as _friction
from sim.physics.lubricant import MPA_S_PER_PA_S, Lubricant

#: Traction laws of :mod:`sim.physics.ehl` by their function name.
TRACTION_LAWS = {
    "traction_per_speed": "Maxwell film, Newtonian viscous part, tanh-limited by tau_L (thesis 5.17)",
    "traction_eyring": "Maxwell-Eyring film (Johnson & Tevaarwerk 1977), tanh-limited by tau_L",
}


def _law(name):
    if name not in TRACTION_LAWS:
        raise ValueError(f"law = {name!r}: choose one of {sorted(TRACTION_LAWS)}")
    return getattr(ehl, name)


def bearing_model_traction_law(cfg):
    """Name of the traction law the installed bearing model uses (a key of :data:`TRACTION_LAWS`).

    A config key naming it (``friction.traction_law`` or ``lubricant.traction_law``) wins;
    otherwise the law the friction kernels of :mod:`sim.physics.friction` import (one of the
    two), or ``"undetermined"`` when they import both or neither.
    """
    for group in ("friction", "lubricant"):
        node = cfg.get(group) or {}
        if "traction_law" in node and node["traction_law"] is not None:
            return str(node["traction_law"])
    used = [name for name in TRACTION_LAWS if getattr(_friction, name, None) is getattr(ehl, name)]
    return used[0] if len(used) == 1 else "undetermined"


def twin_disc_contact(cfg, p_h, u, R, temperature):
    """Hertz line contact and film of a twin-disc condition.

    Parameters
    ----------
    cfg : omegaconf.DictConfig
        Composed project config (``sim.load_config``): its ``lubricant``, ``material`` and
        ``friction`` nodes are used.
    p_h : float
        Maximum Hertz pressure [MPa].
    u : float
        Entrainment (mean) speed (U1 + U2)/2 [m/s], > 0.
    R : float
        Radius of relative curvature in the rolling direction [mm].
    temperature : float
        Oil (disc bulk) temperature [degC].

    Returns
    -------
    dict
        ``b`` half-width [mm], ``q`` load per length [N/mm], ``E_prime`` [MPa], ``eta0``
        ambient viscosity [MPa s], ``alpha_p`` [1/MPa], ``h`` central (or minimum) film
        thickness [mm], ``t_transit`` [s], ``lubricant`` (:class:`Lubricant`).
    """
    lub = Lubricant.from_config(cfg.lubricant)
    E_prime = float(cfg.material.E) / (1.0 - float(cfg.material.nu) ** 2)
    b = 4.0 * R * p_h / E_prime
    q = np.pi * b * p_h / 2.0
    eta0 = float(lub.dynamic_viscosity(temperature)) * MPA_S_PER_PA_S
    u_mm = u * 1e3
    alpha_p = float(lub.pressure_viscosity_at(temperature))
    h = ehl.film_line(u_mm, q, R, eta0, alpha_p, E_prime, ehl.FILM_FORMULAS[str(cfg.friction.film_thickness)])
    return {"b": b, "q": q, "E_prime": E_prime, "eta0": eta0, "alpha_p": alpha_p, "h": h,
            "t_transit": 2.0 * b / u_mm, "lubricant": lub}


def traction_curve(cfg, srr, *, p_h, u, R, temperature, law="traction_eyring", phi=0.0, points=32):
    """Traction coefficient against slide-to-roll ratio of one EHL line contact.

    Parameters
    ----------
    cfg : omegaconf.DictConfig
        Composed project config: ``lubricant`` (viscosity, pressure-viscosity, tau_L0, c, G,
        tau_E0), ``material`` (E, nu), ``friction`` (film formula, boundary friction).
    srr : array_like
        Slide-to-roll ratios S = (U1 - U2)/u [1], >= 0.
    p_h : float
        Maximum Hertz pressure [MPa].
    u : float
        Entrainment speed [m/s].
    R : float
        Radius of relative curvature [mm].
    temperature : float
        Oil temperature [degC].
    law : str
        ``"traction_eyring"`` or ``"traction_per_speed"`` (:data:`TRACTION_LAWS`).
    phi : float
        Solid load share [1] (0: full film).
    points : int
        Gauss-Legendre points over a half of the Hertz width.

    Returns
    -------
    numpy.ndarray
        mu [1], the shape of ``srr``.
    """
    fn = _law(law)
    c = twin_disc_contact(cfg, p_h, u, R, temperature)
    lub = c["lubricant"]
    pv = ehl.PRESSURE_VISCOSITY_MODELS[lub.pressure_viscosity_model]
    z = ehl.roelands_index(c["eta0"], c["alpha_p"])
    solid = ehl.SolidFriction(mu_s=float(cfg.friction.solid_friction_coefficient),
                              v_s=float(cfg.friction.solid_slip_velocity) * 1e3)    # m/s -> mm/s
    rheology = ehl.FilmRheology(tau_E0=float(lub.eyring_stress_at(temperature)), tau_L0=float(lub.limiting_shear_stress_0),
                                c_tau=float(lub.limiting_shear_coefficient), G=float(lub.shear_modulus))
    x, w = np.polynomial.legendre.leggauss(int(points))
    t = 0.25 * np.pi * (x + 1.0)                                       # (0, pi/2)
    w = 0.25 * np.pi * w
    srr = np.asarray(srr, dtype=float)
    out = np.empty(srr.shape)
    for k, S in np.ndenumerate(srr):
        v = abs(S) * u * 1e3                                           # sliding speed [mm/s]
        F = 0.0
        for tk, wk in zip(t, w):
            p = p_h * np.cos(tk)
            eta_p = ehl.pressure_viscosity(p, c["eta0"], c["alpha_p"], z, pv)
            g = fn(p, v, c["h"], phi, eta_p, rheology, solid, c["t_transit"])   # both laws: same arguments
            F += wk * np.cos(tk) * g * v                               # tau cos(t) dt, over (0, pi/2)
        out[k] = 4.0 / np.pi * F / p_h                                 # (2/pi) over (-pi/2, pi/2)
    return out
