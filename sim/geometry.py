"""Bearing geometry of the TSRB and the TRB: derived values, feasibility, slice discretisation.

Frames (MODEL.md 1-2). Bearing axis z, pointing from the large roller ends towards the apex
of the raceway cones, so that the axial load ``Fa`` on the inner ring acts along +z. In the
meridian plane of a roller, coordinates are (r, z); the roller centre (mid-length, on its
axis) sits at (Dpw/2, 0). The roller frame has ``u`` along the roller axis towards the
large end and ``v`` normal to it, outwards:

    u = (sin(alpha), -cos(alpha)),   v = (cos(alpha), sin(alpha))      in (r, z).

``alpha`` is the angle of the roller axis (the mean contact angle of eq. (2.1)); the outer
contact normal is at alpha + gamma, the inner at alpha - gamma (MODEL.md 2). In the roller
frame, x runs along u from mid-length (positive towards the large end), y along v.

Everything here is computed once per bearing; kernels receive plain arrays (mm, rad).
"""
from dataclasses import dataclass, field, fields

import numpy as np

from sim.config_schema import BearingConfig, MaterialConfig, SolverConfig, node_problems
from sim.errors import GeometryError

TRB = 0
TSRB = 1
TYPE_CODES = {"TRB": TRB, "TSRB": TSRB}  # kernel codes of the schema's bearing types (sim.config_schema.BEARING_TYPES)
BEARING_KEYS = [f.name for f in fields(BearingConfig)]

# The logarithmic crown (thesis eq. (2.5)) is infinite at the roller end itself: where the profile is
# needed at the end (the roller end radius, the mass integral, the end-profile table of
# sim.api.bearing_model) it is taken ROLLER_END_CLIP (relative to Lwe / 2) inside it, where the drop is
# c Dwe ln(1 / (2 ROLLER_END_CLIP)) = 0.09 mm for a TRB 32208, far beyond any elastic approach here;
# numerical choice.
ROLLER_END_CLIP = 1e-9

# Raceway profile kinds understood by sim.physics.contact.
RACE_LINE = 0  # straight generatrix (cone): point and unit normal into the ring
RACE_LENS = 1  # two circular arcs, each with its own radius, whose disks intersect (TSRB, "two intersected tori")

#: per-point osculation keys of a TSRB (sim.config_schema, thesis 8.2): [race][point], race 0 outer,
#: 1 inner; point 0 the small-end contact point, 1 the large-end one. Null in the config: kappa.
OSCULATION_KEYS = (("kappa_outer_small", "kappa_outer_large"), ("kappa_inner_small", "kappa_inner_large"))


def taper_angle(alpha, Dwe, Dpw):
    """Roller cone half-angle gamma.

    Parameters
    ----------
    alpha : float
        Mean contact angle (roller-axis angle) [rad].
    Dwe, Dpw : float
        Roller diameter at mid-length and pitch diameter [mm].

    Returns
    -------
    float
        gamma [rad] = atan(Dwe sin(alpha) / Dpw), thesis eq. (2.1).
    """
    return np.arctan(Dwe * np.sin(alpha) / Dpw)


def raceway_profile_radius(PCR, kappa):
    """Profile curve radius of the raceways PCR_LB from the osculation.

    Parameters
    ----------
    PCR : float
        Profile curve radius of the roller [mm].
    kappa : float
        Osculation [1].

    Returns
    -------
    float
        PCR_LB [mm] = PCR (2 - kappa), from thesis eq. (2.7): kappa = 1 - (PCR_LB - PCR)/PCR.
    """
    return PCR * (2.0 - kappa)


def centre_offset_aA(PCR, alpha, gamma, Dwe, Dpw):
    """Distance aA from the bearing axis to the centre of the roller's PCR (thesis Fig. 2.7).

    Parameters
    ----------
    PCR : float
        Profile curve radius of the roller [mm].
    alpha, gamma : float
        Roller-axis angle and taper angle [rad].
    Dwe, Dpw : float
        Roller and pitch diameter [mm].

    Returns
    -------
    float
        aA [mm], positive on the far side of the bearing axis:
        aA = PCR cos(alpha + gamma) - Dpw/2 - (Dwe/2) cos(alpha).
        This is the relation of MODEL.md 2 (reproduces thesis Tables 7.1, 7.4, 7.5 (longer
        roller) and A.5 to about 1 mm; Tables 6.1 and 7.5 (bigger alpha) do not fit it).
    """
    return PCR * np.cos(alpha + gamma) - 0.5 * Dpw - 0.5 * Dwe * np.cos(alpha)


def log_crown_drop(x, Dwe, Lwe, coefficient):
    """Logarithmic roller profile drop of tapered rollers.

    Parameters
    ----------
    x : array_like
        Position along the roller axis from mid-length [mm], |x| < Lwe/2.
    Dwe, Lwe : float
        Roller diameter and effective length [mm].
    coefficient : float
        0.00045 for tapered rollers [1].

    Returns
    -------
    ndarray
        P(x) [mm] = c Dwe ln(1 / (1 - (2x/Lwe)^2)), thesis eq. (2.5) (DIN 26281, ISO/TS 16281).
    """
    t = (2.0 * np.asarray(x, dtype=float) / Lwe) ** 2
    return coefficient * Dwe * np.log(1.0 / (1.0 - t))


def _require(condition, name, value, bound, rule, context="", limit=None):
    """Raise GeometryError naming the config key (``bearing.`` unless the name carries its group).

    ``rule`` names the feasibility rule (a key of ``Geometry.RULES``); ``context`` lists the
    other keys of the rule with their values, so that whichever of them was changed is named
    too; ``limit`` is the bound on the blamed key as a number, where it has a closed form. The
    error carries ``key``, ``rule`` and ``limit`` as attributes.
    """
    if not condition:
        key = name if "." in name else f"bearing.{name}"
        err = GeometryError(f"{key} = {value!r} is impossible: it must be {bound}"
                            + (f" ({context})" if context else ""))
        err.key, err.rule, err.limit = key, rule, limit
        raise err


def max_rollers(Dpw, Dwe, web_ratio):
    """Most rollers of diameter Dwe that fit on the pitch circle Dpw with a cage web of web_ratio Dwe.

    Neighbouring rollers' mid-length circles (diameter Dwe, centres on the pitch circle) are a
    chord Dpw sin(pi/Z) apart; the cage web between them needs web_ratio Dwe, so Z fits when
    Dpw sin(pi/Z) >= (1 + web_ratio) Dwe. Tapered rollers share the cone apex on the bearing
    axis, so the angular pitch they need is the same along the whole roller; crowned rollers lie
    inside their cone. Returns 0 when no Z >= 2 fits.
    """
    need = (1.0 + web_ratio) * Dwe
    if need >= Dpw:
        return 0
    z = int(np.pi / np.arcsin(need / Dpw))
    # round-off at the boundary: the inequality decides. The formula is within one of it, so a
    # step or two either way; unbounded loops never ended where z + 1 is z in floating point
    # (Dpw = 1e300 mm, found by the fuzz of tests/robustness/test_fuzz_api.py)
    for _ in range(2):
        if z > 0 and Dpw * np.sin(np.pi / z) < need:
            z -= 1
    for _ in range(2):
        if Dpw * np.sin(np.pi / (z + 1)) >= need:
            z += 1
    return z


@dataclass(frozen=True)
class Geometry:
    """A TSRB or TRB, with every derived value computed once (kernel units: mm, rad, N, t).

    Built by :meth:`from_config`; refuses impossible input before any numerics run.
    """

    type: str
    alpha: float
    #: alpha as configured [deg]: the design coordinate (sim.io.design_values), equal to the value given,
    #: which degrees(radians(x)) is not (15 -> 14.999999999999998), so that a sweep's .sel(alpha=15) finds it
    alpha_deg: float
    gamma: float
    Dpw: float
    Dwe: float
    Lwe: float
    B: float
    r: float
    R: float
    Z: int
    b_m: float
    #: least cage web between neighbouring rollers at the pitch circle, in roller diameters [1]
    cage_web_ratio: float
    #: contact angle of the ISO 281 factors and ratings [deg]. TRB: derived, the cup (outer
    #: raceway) angle alpha + gamma, as ISO 281 / ISO 355 define the nominal contact angle of
    #: tapered roller bearings; TSRB: configured (ISO 281 has no TSRB; thesis Table 6.2 rates
    #: the prototype at its alpha).
    ratings_alpha: float
    E: float
    nu: float
    density: float  # t/mm^3
    n_slices: int
    # TSRB only (nan for the TRB)
    PCR: float = np.nan
    kappa: float = np.nan
    #: osculation of each raceway arc at its own contact point [1] (OSCULATION_KEYS; kappa where not configured)
    kappa_outer_small: float = np.nan
    kappa_outer_large: float = np.nan
    kappa_inner_small: float = np.nan
    kappa_inner_large: float = np.nan
    aP: float = np.nan
    aPk: float = np.nan
    # TRB only (nan for the TSRB)
    crown_coefficient: float = np.nan
    roller_end_radius_ratio: float = np.nan
    rib_contact_height_ratio: float = np.nan
    #: roller end / rib contact model, "sphere" or "torus" (config bearing.roller_end; "" for a TSRB)
    roller_end: str = ""
    roller_end_edge_radius: float = np.nan   # mm, r_k of the torus
    rib_opening_angle: float = np.nan        # deg, as configured
    arrays: dict = field(default_factory=dict, compare=False, repr=False)

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_config(cls, bearing, material, n_slices):
        """Build from the ``bearing`` and ``material`` config nodes (degrees at this edge).

        Each key is checked against its schema (:mod:`sim.config_schema`) first: a missing key
        or a value outside its range raises :class:`GeometryError` naming them all, with value
        and allowed range; then :meth:`_check` refuses combinations that cannot exist.
        """
        kind = bearing.get("type")
        problems = node_problems(BearingConfig, bearing, "bearing", bearing_type=kind,
                                 keys=[f for f in BEARING_KEYS if f != "surface"])  # surface: friction's
        problems += node_problems(MaterialConfig, material, "material", keys=("E", "nu", "density"))
        problems += node_problems(SolverConfig, {"n_slices": n_slices}, "solver", keys=("n_slices",))
        if problems:
            raise GeometryError("\n".join(problems))
        b = dict(bearing)
        own = [f.name for f in fields(BearingConfig) if f.metadata.get("only") == kind]  # this type's keys
        E, nu, rho = float(material["E"]), float(material["nu"]), float(material["density"])
        alpha = np.radians(float(b["alpha"]))
        Dwe, Dpw = float(b["Dwe"]), float(b["Dpw"])
        with np.errstate(divide="ignore", over="ignore"):
            apex = 0.5 * Dpw / np.sin(alpha)
        if not np.isfinite(apex):   # an alpha in (0, 60) deg that underflows to 0 rad (or nearly)
            err = GeometryError(f"bearing.alpha = {float(b['alpha'])!r} is impossible: it underflows to 0 rad, so the "
                                "raceway cones' apex, Dpw / (2 sin(alpha)) from the roller, lies infinitely far")
            err.key, err.rule, err.limit = "bearing.alpha", None, None
            raise err
        extra = {k: (str(b[k]) if k == "roller_end" else float(b[k])) for k in own if b.get(k) is not None}
        if kind == "TSRB":  # per-point osculations default to kappa (thesis 8.2; sim.config_schema)
            extra.update({k: extra["kappa"] for pair in OSCULATION_KEYS for k in pair if k not in extra})
        gamma = taper_angle(alpha, Dwe, Dpw)
        if kind == "TRB":
            extra["ratings_alpha"] = float(np.degrees(alpha + gamma))  # ISO 281: the cup angle
        g = cls(type=kind, alpha=alpha, alpha_deg=float(b["alpha"]), gamma=gamma, Dpw=Dpw, Dwe=Dwe,
                Lwe=float(b["Lwe"]), B=float(b["B"]), r=float(b["r"]), R=float(b["R"]), Z=int(b["Z"]),
                b_m=float(b["b_m"]), cage_web_ratio=float(b["cage_web_ratio"]), E=E, nu=nu, density=rho * 1e-12,
                n_slices=int(n_slices), **extra)
        g._check()
        object.__setattr__(g, "arrays", g._build_arrays())
        return g

    #: every feasibility rule of :meth:`_check`: name -> (blamed key, the keys it combines). The
    #: TSRB rules use the crowned profile, the TRB rules its rib and roller-end sphere.
    RULES = {
        "Dwe_fit": ("Dwe", ("Dwe", "Dpw", "cage_web_ratio")),
        "Z_fit": ("Z", ("Z", "Dwe", "Dpw", "cage_web_ratio")),
        "PCR_span": ("PCR", ("PCR", "Lwe", "alpha", "Dwe", "Dpw")),
        "aPk_in_roller": ("aPk", ("aPk", "aP", "Lwe")),
        "end_radii": ("PCR", ("PCR", "Lwe", "alpha", "Dwe", "Dpw")),
        "rib_on_end_face": ("rib_contact_height_ratio",
                            ("rib_contact_height_ratio", "Dwe", "Lwe", "alpha", "Dpw", "crown_coefficient")),
        "end_sphere_reaches_rib": ("roller_end_radius_ratio",
                                   ("roller_end_radius_ratio", "rib_contact_height_ratio", "Dwe", "Lwe", "alpha",
                                    "Dpw", "crown_coefficient")),
        "torus_face": ("roller_end_edge_radius", ("roller_end_edge_radius", "Dwe", "Lwe", "alpha", "Dpw")),
        "torus_rib_convex": ("rib_opening_angle",
                             ("rib_opening_angle", "roller_end_edge_radius", "Dwe", "Lwe", "alpha", "Dpw")),
        "outer_ring_section": ("R", ("R", "Dpw", "Dwe", "Lwe", "alpha", "PCR")),
        "inner_ring_section": ("r", ("r", "Dpw", "Dwe", "Lwe", "alpha", "PCR")),
        "ring_width": ("B", ("B", "Lwe", "Dwe", "alpha")),
    }

    def _with(self, *names):
        """'Dpw = 60.0, Dwe = 10.0': the given keys with their values (angles in deg, as configured)."""
        shown = {"alpha": self.alpha_deg}
        return ", ".join(f"{n} = {shown.get(n, getattr(self, n))!r}" for n in names)

    def _check(self):
        """Refuse geometry that cannot exist (MODEL.md 2), naming parameter, value and bound.

        Only bounds that combine keys (:attr:`RULES`): each key's own range is the schema's,
        checked in :meth:`from_config`. Checked in order, so that a rule only sees what the
        earlier ones made well defined (the end radii only once the crown spans the roller):

        - rollers fit on the pitch circle with the cage's least web (:func:`max_rollers`): Z at
          most the number that fits, and at least three must fit (else Dwe is blamed);
        - TSRB: the crown circle spans the roller, the contact points lie on it, both end
          radii exceed 0.1 Dwe;
        - TRB: the rib contact lies on the large end face and the roller-end sphere reaches it;
        - both rings have a positive section: the outer raceway stays inside the outside
          radius R, the inner raceway outside the bore radius r (raceways taken as the roller
          envelope at its ends; the TRB's uncrowned cone); the roller's axial extent fits in B.
        """
        half = 0.5 * self.Lwe
        web = self.cage_web_ratio
        fits = max_rollers(self.Dpw, self.Dwe, web)
        fit_context = (f"rollers of Dwe = {self.Dwe!r} mm with the cage's least web cage_web_ratio Dwe = "
                       f"{web * self.Dwe:.3f} mm on the pitch circle Dpw = {self.Dpw!r} mm: "
                       f"Dpw sin(pi/Z) >= (1 + cage_web_ratio) Dwe, cage_web_ratio = {web!r}")
        _require(fits >= 3, "Dwe", self.Dwe,
                 f"<= Dpw sin(pi/3) / (1 + cage_web_ratio) = {self.Dpw * np.sin(np.pi / 3) / (1 + web):.3f} mm "
                 "for the fewest rollers allowed, 3, to fit", "Dwe_fit", fit_context,
                 self.Dpw * np.sin(np.pi / 3) / (1 + web))
        _require(self.Z <= fits, "Z", self.Z, f"<= {fits}, the most that fit", "Z_fit", fit_context, fits)
        if self.type == "TSRB":
            bound = half / (1.0 - np.sin(self.gamma))
            _require(self.PCR > bound, "PCR", self.PCR,
                     f"> Lwe/(2 (1 - sin(gamma))) = {bound:.3f} (the crown circle must span the roller)", "PCR_span",
                     self._with("Lwe", "alpha", "Dwe", "Dpw") + f", gamma = {np.degrees(self.gamma):.3f} deg", bound)
            _require(self.aPk + self.aP < self.Lwe, "aPk", self.aPk,
                     f"< Lwe - aP = {self.Lwe - self.aP} (second contact point inside the roller)", "aPk_in_roller",
                     self._with("Lwe", "aP"), self.Lwe - self.aP)
            rho_ends = self.roller_radius(np.array([-half, half]))
            _require(rho_ends.min() > 0.1 * self.Dwe, "PCR", self.PCR,
                     f"large enough that both roller end radii exceed 0.1 Dwe = {0.1 * self.Dwe:.3f} mm "
                     f"(now {rho_ends.min():.3f} mm)", "end_radii", self._with("Lwe", "Dwe", "alpha", "Dpw"))
        elif self.roller_end == "torus":
            _require(self.roller_end_edge_radius < self._torus_edge_limit(), "roller_end_edge_radius",
                     self.roller_end_edge_radius,
                     f"< {self._torus_edge_limit():.4f} mm, where the edge radius would leave no flat end face",
                     "torus_face", self._with("Dwe", "Lwe", "alpha", "Dpw"), self._torus_edge_limit())
            limit = self._torus_opening_limit()
            _require(self.rib_opening_angle > np.degrees(limit), "rib_opening_angle", self.rib_opening_angle,
                     f"> {np.degrees(limit):.4f} deg: at smaller angles the roller end's circumference is flatter "
                     "than the cone rib's, so it would touch the rib at two points off the meridian plane, not at "
                     "one point of its edge", "torus_rib_convex",
                     self._with("roller_end_edge_radius", "Dwe", "Lwe", "alpha", "Dpw"), float(np.degrees(limit)))
        else:
            rho_large = float(self.roller_radius(half * (1 - ROLLER_END_CLIP)))
            _require(self.rib_contact_height_ratio * self.Dwe < rho_large, "rib_contact_height_ratio",
                     self.rib_contact_height_ratio,
                     f"< {rho_large / self.Dwe:.4f}, the large-end radius over Dwe (the rib contact must lie on the "
                     "roller end face)", "rib_on_end_face",
                     self._with("Dwe", "Lwe", "crown_coefficient", "alpha", "Dpw"), rho_large / self.Dwe)
            reach = (rho_large - self.rib_contact_height_ratio * self.Dwe) / (self.apex_distance + half)
            _require(self.roller_end_radius_ratio > reach, "roller_end_radius_ratio", self.roller_end_radius_ratio,
                     f"> {reach:.4f} (the roller-end sphere, radius ratio x (apex distance + Lwe/2), must reach the "
                     "rib contact)", "end_sphere_reaches_rib",
                     self._with("rib_contact_height_ratio", "Dwe", "Lwe", "alpha", "Dpw", "crown_coefficient"), reach)
        # the roller must fit between the rings and inside the width
        x_end = np.array([-half, half])
        # uncrowned cone for the TRB (its logarithmic drop is unbounded at the very ends)
        rho_end = self.roller_radius(x_end) if self.type == "TSRB" else 0.5 * self.Dwe + x_end * np.tan(self.gamma)
        r_out = 0.5 * self.Dpw + x_end * np.sin(self.alpha) + rho_end * np.cos(self.alpha)
        r_in = 0.5 * self.Dpw + x_end * np.sin(self.alpha) - rho_end * np.cos(self.alpha)
        roller = self._with("Dpw", "Dwe", "Lwe", "alpha") + (f", PCR = {self.PCR!r}" if self.type == "TSRB" else "")
        _require(r_out.max() < self.R, "R", self.R,
                 f"> {r_out.max():.3f} mm (outer raceway radius at the large end: the outer ring needs a section)",
                 "outer_ring_section", roller, r_out.max())
        _require(r_in.min() > self.r, "r", self.r,
                 f"< {r_in.min():.3f} mm (inner raceway radius at the small end: the inner ring needs a section)",
                 "inner_ring_section", roller, r_in.min())
        axial = self.Lwe * np.cos(self.alpha) + self.Dwe * np.sin(self.alpha)
        _require(axial < self.B, "B", self.B, f"> {axial:.3f} mm (axial extent of the roller)", "ring_width",
                 self._with("Lwe", "Dwe", "alpha"), axial)

    # ------------------------------------------------------------------ derived values
    @property
    def type_code(self):
        return TYPE_CODES[self.type]

    @property
    def cup_angle(self):
        """Outer raceway (cup) contact angle alpha + gamma [rad] of the nominal geometry (MODEL.md 2)."""
        return self.alpha + self.gamma

    @property
    def single_row_thrust_angle(self):
        """Angle to the radial plane [rad] of the force with which each roller presses the inner ring
        at its nominal pose, less body loads and friction: a single row carries Fa / Fr > tan of it
        only (:meth:`sim.api.bearing_model.BearingModel.check_limits`; Sjovall's load zone epsilon
        -> 0 at the bound, Harris & Kotzalas 2007, Rolling Bearing Analysis, 7.4).

        TRB: the cup angle alpha + gamma. The roller's outer contact force is normal to the straight
        cup; the inner raceway and the rib, both on the inner ring, balance it.
        TSRB: the roller-axis angle alpha. Every normal of the roller's crown circle passes through
        that circle's centre, and the circles of the outer and the inner side of the roller's
        meridian section are mirror images about its axis (MODEL.md 2). So the outer raceway forces
        act through one centre, the inner ones through the other, and the roller balances them only
        along the line through both centres, normal to its axis: a roller tilted by theta in its
        meridian plane presses the inner ring at alpha + theta (tests/balance/test_thrust_angle.py,
        within 0.002 deg). The flattest normal of the outer raceway, at the roller's large end
        (alpha - 2.6 deg for tsrb_reference, the bound before session 32), is reached only with
        the rollers tilted by degrees in their osculating raceways: below tan(alpha) the load zone
        closes to a few such rollers and the inner ring moves by millimetres (tsrb_reference at Fr
        8 kN, Fa / Fr = 0.84 tan(alpha): 7.2 mm axially, rollers tilted 2.2-7.3 deg, contacts 8.6 mm
        beyond the roller's unloaded span on the raceway), outside the rings' width B."""
        if self.type == "TSRB":
            return self.alpha
        return self.cup_angle

    @property
    def cone_angle(self):
        """Inner raceway (cone) contact angle alpha - gamma [rad] of the nominal geometry (MODEL.md 2)."""
        return self.alpha - self.gamma

    @property
    def PCR_LB(self):
        """Raceway profile curve radius [mm], eq. (2.7), of the symmetric osculation kappa."""
        return raceway_profile_radius(self.PCR, self.kappa)

    @property
    def osculations(self):
        """Osculation of every raceway arc [1], shape (2, 2): [race][point] as OSCULATION_KEYS."""
        return np.array([[getattr(self, k) for k in pair] for pair in OSCULATION_KEYS])

    @property
    def arc_radii(self):
        """Radius of every raceway arc [mm], shape (2, 2) as :attr:`osculations`:
        PCR (2 - kappa_<race>_<point>), eq. (2.7) applied to each arc at its own contact point."""
        return raceway_profile_radius(self.PCR, self.osculations)

    @property
    def s(self):
        """PCR_LB - PCR [mm] (Table 4.2 'osculation')."""
        return self.PCR_LB - self.PCR

    @property
    def aA(self):
        """Distance bearing axis - centre of PCR [mm] (MODEL.md 2)."""
        return centre_offset_aA(self.PCR, self.alpha, self.gamma, self.Dwe, self.Dpw)

    @property
    def contact_points_x(self):
        """TSRB contact points along the roller axis from mid-length, small-end one first [mm].

        aPk is measured from the small end face (MODEL.md 2 and 4).
        """
        return np.array([-0.5 * self.Lwe + self.aPk, -0.5 * self.Lwe + self.aPk + self.aP])

    @property
    def crown_centre(self):
        """Centre of the roller generatrix circle in the roller frame (x, y) [mm] (TSRB)."""
        return np.array([self.PCR * np.sin(self.gamma), 0.5 * self.Dwe - self.PCR * np.cos(self.gamma)])

    @property
    def load_centroid_x(self):
        """x* = PCR sin(gamma) [mm]: rib-free axial balance point of the TSRB (MODEL.md 4)."""
        return self.PCR * np.sin(self.gamma)

    @property
    def slice_width(self):
        return self.Lwe / self.n_slices

    @property
    def x_slice_from_large_end(self):
        """Slice centres along the roller axis from the large end [mm] (DATA.md ``x_slice``)."""
        return (np.arange(self.n_slices) + 0.5) * self.slice_width

    @property
    def x_slice(self):
        """Slice centres from mid-length, positive towards the large end [mm]; slice 0 at the large end."""
        return 0.5 * self.Lwe - self.x_slice_from_large_end

    @property
    def apex_distance(self):
        """Distance from the roller centre to the cone apex along the roller axis [mm]."""
        return 0.5 * self.Dpw / np.sin(self.alpha)

    def roller_radius(self, x):
        """Roller radius rho(x) normal to its axis, crown included [mm].

        TSRB: circle of radius PCR through (0, Dwe/2) with slope tan(gamma) there (MODEL.md 2).
        TRB: cone Dwe/2 + x tan(gamma) minus the logarithmic drop of eq. (2.5), taken normal
        to the generatrix (hence the 1/cos(gamma)).
        """
        x = np.asarray(x, dtype=float)
        if self.type == "TSRB":
            xc, yc = self.crown_centre
            return yc + np.sqrt(self.PCR**2 - (x - xc) ** 2)
        return 0.5 * self.Dwe + x * np.tan(self.gamma) - log_crown_drop(x, self.Dwe, self.Lwe,
                                                                       self.crown_coefficient) / np.cos(self.gamma)

    def roller_profile_slope(self, x):
        """d rho / dx of the nominal (uncrowned for the TRB) generatrix [1]."""
        x = np.asarray(x, dtype=float)
        if self.type == "TSRB":
            xc, _ = self.crown_centre
            return -(x - xc) / np.sqrt(self.PCR**2 - (x - xc) ** 2)
        return np.full_like(x, np.tan(self.gamma))

    # ------------------------------------------------------------------ kernel arrays
    def to_meridian(self, x, y):
        """Roller-frame point(s) at the nominal pose -> meridian (r, z) [mm]."""
        a = self.alpha
        r = 0.5 * self.Dpw + x * np.sin(a) + y * np.cos(a)
        z = -x * np.cos(a) + y * np.sin(a)
        return r, z

    def _race_arrays(self, side):
        """Raceway profile in ring coordinates (r, z) at the nominal (unloaded) position.

        side = +1 outer, -1 inner. Returns (kind, params[6]):
        RACE_LINE: (r0, z0, nr, nz, 0, 0), point on the line and unit normal into the ring;
        RACE_LENS: (r1, z1, r2, z2, R1, R2), the centres and radii of the small-end and the
        large-end arc, R_k = PCR (2 - kappa_k) (eq. (2.7) per arc, :attr:`arc_radii`).

        TSRB raceway (MODEL.md 2, thesis 8.2): arc k is the circle of radius R_k >= PCR internally
        tangent to the roller's crown circle at contact point k, centre c_k = p_k - R_k n_k (p_k the
        contact point, n_k the crown's outward unit normal there). Each disk |q - c_k| <= R_k holds
        the whole crown circle (internal tangency, R_k >= PCR), so the cavity the ring leaves for
        the roller is the intersection of the two disks: the penetration of a point is the larger
        of its two arc penetrations (sim.physics.contact.race_penetration). The unloaded gap
        is zero at p_1 and p_2 only and grows as s^2 (1/PCR - 1/R_k) / 2 with the arc length s from
        p_k. The two arcs meet where their gaps are equal, between the points (near the roller,
        c_1 (x - x_1)^2 = c_2 (x - x_2)^2 with c_k = 1/PCR - 1/R_k has its one root between x_1 and
        x_2), in a corner of the profile (a groove in the ring: the relief between the osculation
        regions of thesis Fig. 4.10 / [Jac92]). A grinding wheel dressed to the two arcs makes
        exactly this: its profile is the cavity, two convex arcs meeting in a ridge. A profile
        tangent-continuous where the arcs meet would need a third, blending arc: two circles each
        fixed by its radius and its tangency at p_k are tangent to each other only when R_1 = R_2.
        """
        a, g = self.alpha, self.gamma
        if self.type == "TRB":
            r0, z0 = self.to_meridian(0.0, side * 0.5 * self.Dwe)
            # normal of the generatrix in the roller frame, pointing away from the roller axis
            nx, ny = -np.sin(g), side * np.cos(g)
            nr = nx * np.sin(a) + ny * np.cos(a)
            nz = -nx * np.cos(a) + ny * np.sin(a)
            return RACE_LINE, np.array([r0, z0, nr, nz, 0.0, 0.0])
        # TSRB: each raceway arc internally tangent to the roller generatrix at a contact point
        xc, yc = self.crown_centre
        radii = self.arc_radii[0 if side > 0 else 1]
        centres = []
        for xk, Rk in zip(self.contact_points_x, radii):
            yk = float(self.roller_radius(xk))
            nx, ny = (xk - xc) / self.PCR, (yk - yc) / self.PCR  # outward normal of the roller circle
            cx, cy = xk - Rk * nx, yk - Rk * ny
            centres.append(self.to_meridian(cx, side * cy))
        (r1, z1), (r2, z2) = centres
        return RACE_LENS, np.array([r1, z1, r2, z2, radii[0], radii[1]])

    def _equivalent_radii(self, side):
        """Radius of relative curvature in the rolling direction per slice [mm] (Hertz line contact).

        Roller: principal curvature of a surface of revolution, cos(phi)/rho with phi the local
        generatrix slope; raceway: n_r / r_c at the contact (convex inner, concave outer).
        """
        x = self.x_slice
        rho = self.roller_radius(x)
        slope = np.arctan(self.roller_profile_slope(x))
        k_roller = np.cos(slope) / rho
        # normal at the contact in (r, z): roller frame normal (-sin(slope), side*cos(slope))
        nr = -np.sin(slope) * np.sin(self.alpha) + side * np.cos(slope) * np.cos(self.alpha)
        rc, _ = self.to_meridian(x, side * rho)
        k_race = nr / rc  # > 0 outer (concave seen from the roller), < 0 inner (convex)
        return 1.0 / (k_roller - k_race)

    def _build_arrays(self):
        n = self.n_slices
        x = self.x_slice
        rho = self.roller_radius(x)
        kind_o, par_o = self._race_arrays(+1)
        kind_i, par_i = self._race_arrays(-1)
        out = {
            "x": x, "rho": rho, "w": self.slice_width,
            "race_kind": np.array([kind_o, kind_i], dtype=np.int64),
            "race_par": np.vstack([par_o, par_i]),
            "R_eq": np.vstack([self._equivalent_radii(+1), self._equivalent_radii(-1)]),
        }
        # roller mass and axial moment of inertia from the profile (solid of revolution)
        xs = np.linspace(-0.5 * self.Lwe, 0.5 * self.Lwe, 401)
        inside = 0.5 * self.Lwe * (1 - ROLLER_END_CLIP)
        rs = self.roller_radius(np.clip(xs, -inside, inside))
        out["mass"] = self.density * np.trapezoid(np.pi * rs**2, xs)                 # t
        out["inertia_axial"] = self.density * np.trapezoid(0.5 * np.pi * rs**4, xs)  # t mm^2
        # about a transverse axis through the mid-length point (the roller centre of the kernels):
        # discs of radius r at x, (r^2 / 4 + x^2) pi r^2 dx each [t mm^2]
        out["inertia_transverse"] = self.density * np.trapezoid(np.pi * rs**2 * (0.25 * rs**2 + xs**2), xs)
        if self.type == "TRB":
            out["rib"], out["rib_end"] = self._rib_arrays()
        else:
            out["rib"], out["rib_end"] = np.zeros(6), np.zeros(4)
        assert out["R_eq"].shape == (2, n)
        return out

    def _rib_arrays(self):
        """Roller-end / rib contact of the TRB (thesis 5.5.1; docs/roller_end_torus.md).

        ``roller_end = "sphere"`` (dimensions ASSUMED, see conf/bearing): roller end a sphere of
        radius R_end = roller_end_radius_ratio * (apex distance to the large end face), centred on
        the roller axis; the rib an inner-ring cone touching it at the nominal pose at a height
        e = rib_contact_height_ratio * Dwe above the inner raceway (:meth:`_sphere_rib`): straight
        in the meridian plane, concave along e_t, so the Hertz contact is an ellipse elongated
        along e_t.

        ``roller_end = "torus"`` (the thesis's TRB model, 5.5.1): a flat end face whose edge is
        rounded with r_k (a torus: tube radius r_k, tube centre circle of radius a, the rim, at
        x = Lwe/2 - r_k, :meth:`_torus_rib`) against a cone rib whose generatrix opens by
        rib_opening_angle from the end face, so that the edge touches next to the raceway. In the
        meridian plane the touching tube section is a circle of radius r_k centred off the axis at
        (Lwe/2 - r_k, -a); the rib normal is (cos, -sin)(opening angle). Hertz: elliptical, r_k
        across the rolling direction, along it the end's circumferential radius against the cone
        rib's concave one.

        Returns
        -------
        rib : ndarray (6,)
            (c_x, c_y, r, n_x, n_y, R_t) [mm, 1] in the roller frame: centre of the touching circle
            (sphere centre, or tube section centre), its radius, unit rib normal into the rib,
            and the relative radius of curvature along e_t, R_t.
        rib_end : ndarray (4,)
            (R_n, x_n, R_t, R_m) [mm]: distance from the contact point along the normal to the
            roller axis (the end's principal radius about that axis), where the normal meets
            the axis (x from the roller centre), and the relative radii of curvature along e_t
            and across it, in the meridian plane.
        """
        half = 0.5 * self.Lwe
        if self.roller_end == "torus":
            t = self._torus_rib(np.radians(self.rib_opening_angle))
            rib = np.array([t["c_x"], -t["a"], self.roller_end_edge_radius, t["n_x"], t["n_y"], t["Rx"]])
            return rib, np.array([t["R_n"], t["x_n"], t["Rx"], self.roller_end_edge_radius])
        s = self._sphere_rib()
        return (np.array([s["c_x"], 0.0, s["R_end"], s["n_x"], s["n_y"], s["Rx"]]),
                np.array([s["R_end"], s["c_x"], s["Rx"], s["R_end"]]))

    def _rib_circumferential_radius(self, x_p, y_p, n_x, n_y, R_n):
        """Relative radius of curvature along e_t [mm] of a roller end touching the inner ring's rib
        at the point (x_p, y_p) [mm] of the roller frame, with unit normal (n_x, n_y) into the rib
        and the end's principal radius about the roller axis R_n [mm] (the distance along the
        normal from the point to the roller axis: a surface of revolution about it); -inf where the
        relative curvature is not positive.

        The rib is a surface of revolution about the bearing axis: along its parallel circle, e_t,
        its normal curvature is n_r / X_r (Meusnier's theorem), concave seen from the roller when
        its normal into the rib points outwards (n_r > 0). The end's curvature along e_t is 1/R_n,
        so the relative one is 1/R_n - n_r / X_r (Johnson 1985, 4.1: sum of both bodies'
        curvatures, concave negative); not positive means the end would conform to the rib or
        touch it off the meridian plane."""
        X_r = 0.5 * self.Dpw + x_p * np.sin(self.alpha) + y_p * np.cos(self.alpha)
        n_r = n_x * np.sin(self.alpha) + n_y * np.cos(self.alpha)
        k_t = 1.0 / R_n - n_r / X_r
        return 1.0 / k_t if k_t > 0.0 else -np.inf

    def _sphere_rib(self):
        """Sphere / cone-rib contact at the nominal pose (``roller_end = "sphere"``).

        The end sphere, radius R_end = roller_end_radius_ratio x (apex distance + Lwe/2), centred
        on the roller axis at c_x = Lwe/2 - R_end, touches the rib at the height
        rib_contact_height_ratio x Dwe above the inner raceway; the rib's generatrix there is
        tangent to the sphere (straight: relative radius R_end across e_t, in the meridian plane),
        and the rib is a cone about the bearing axis, so along e_t its concave circumferential
        curvature is subtracted from the sphere's (:meth:`_rib_circumferential_radius`). The
        normal through the sphere centre meets the bearing axis near the apex, so the rib's
        circumferential radius is close to the apex distance and the end conforms to the rib
        along e_t by about roller_end_radius_ratio: R_t ~ R_end / (1 - ratio), a contact ellipse
        elongated along e_t. At ratio 1 the sphere is centred on the apex, on the bearing axis, where
        the rib's normal meets it too: it conforms to the rib along e_t (Rx = inf, the schema's open
        bound).
        """
        half = 0.5 * self.Lwe
        R_end = self.roller_end_radius_ratio * (self.apex_distance + half)
        rho_large = float(self.roller_radius(half * (1 - ROLLER_END_CLIP)))
        y_c = -(rho_large - self.rib_contact_height_ratio * self.Dwe)
        c_x = half - R_end
        x_c = c_x + np.sqrt(R_end**2 - y_c**2)
        n_x, n_y = (x_c - c_x) / R_end, y_c / R_end
        return {"c_x": c_x, "R_end": R_end, "n_x": n_x, "n_y": n_y,
                "Rx": self._rib_circumferential_radius(x_c, y_c, n_x, n_y, R_end)}

    def _torus_rim(self, r_k):
        """Rim radius a [mm] of a flat end face with edge radius r_k [mm]: the distance from the
        roller axis of the centre of the edge's tube section, tangent to the end face x = Lwe/2
        and to the roller's uncrowned cone Dwe/2 + x tan(gamma) (the crown drop there is
        below 0.02 mm in the shipped TRBs): a = Dwe/2 + (Lwe/2 - r_k) tan(gamma) - r_k / cos(gamma)."""
        return 0.5 * self.Dwe + (0.5 * self.Lwe - r_k) * np.tan(self.gamma) - r_k / np.cos(self.gamma)

    def _torus_edge_limit(self):
        """Largest edge radius [mm]: the one whose rim radius is zero (:meth:`_torus_rim`)."""
        return (0.5 * self.Dwe + 0.5 * self.Lwe * np.tan(self.gamma)) / (np.tan(self.gamma) + 1.0 / np.cos(self.gamma))

    def _torus_rib(self, opening):
        """Torus / cone-rib contact at the nominal pose for a rib opening angle [rad] (docs/roller_end_torus.md).

        The rib normal into the rib in the roller frame is n = (cos b, -sin b), b the opening
        angle; the torus point with that outward normal is the edge point P = (c_x, -a) + r_k n,
        c_x = Lwe/2 - r_k. The torus is a surface of revolution about the roller axis, so its
        normal at P meets that axis, at R_n = r_k + a / sin(b) from P (Meusnier: the principal
        radius along the parallel circle), x_n = c_x - a cot(b). The cone rib is a surface of
        revolution about the bearing axis, concave seen from the roller along e_t with radius
        X_r / n_r (X_r the radius of P, n_r = sin(alpha - b) the radial component of n). Relative
        curvature along e_t: 1/R_n - n_r / X_r (Rx its inverse; -inf where it is not positive:
        the end would conform to the rib or touch it at two points); across: 1/r_k (the rib's
        generatrix is straight).
        """
        r_k = self.roller_end_edge_radius
        a = self._torus_rim(r_k)
        c_x = 0.5 * self.Lwe - r_k
        n_x, n_y = np.cos(opening), -np.sin(opening)
        x_p, y_p = c_x + r_k * n_x, -a + r_k * n_y
        R_n = r_k + a / np.sin(opening)
        return {"c_x": c_x, "a": a, "n_x": n_x, "n_y": n_y, "R_n": R_n, "x_n": c_x - a * n_x / np.sin(opening),
                "Rx": self._rib_circumferential_radius(x_p, y_p, n_x, n_y, R_n)}

    def _torus_opening_limit(self):
        """Smallest rib opening angle [rad] at which the torus touches the cone rib at one edge
        point (relative curvature along e_t positive, :meth:`_torus_rib`), by bisection in
        (0, 30 deg] (the schema's range); 30 deg if none there."""
        lo, hi = 0.0, np.radians(30.0)
        if not self._torus_rib(hi)["Rx"] > 0.0:
            return hi
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if self._torus_rib(mid)["Rx"] > 0.0:
                hi = mid
            else:
                lo = mid
        return hi

    def summary(self):
        """Derived values for reports and Dataset attributes."""
        d = {"gamma_deg": float(np.degrees(self.gamma))}
        if self.type == "TSRB":
            d.update(PCR_LB=self.PCR_LB, s=self.s, aA=float(self.aA), x_star=float(self.load_centroid_x),
                     x_large=float(self.contact_points_x[1]))
        return d
