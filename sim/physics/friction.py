"""Roller kinematics from the traction balance, and the frictional torque (MODEL.md 5, thesis 5.4).

Frame: the cage frame, rotating with the cage at omega_c about the bearing axis z; the outer
ring turns at -omega_c, the inner ring at omega_i about its own axis less omega_c about z ("Inner
ring" below), roller j about its own axis u' at omega_R,j. Local basis at a roller's azimuth: (e_r, e_t, e_z), right-handed, meridian
coordinates (r, z) as in :mod:`sim.geometry`.

Per slice and raceway (kernel :func:`roller_friction`), at the contact point X with normal
n (into the ring) and rolling tangent a = n x e_t:

- sliding speed of the roller against the ring along e_t, s = omega_R (u' x (X - c)).e_t - Omega X_r
  (Omega = -omega_c on the outer ring; on the inner ring omega_i r' - omega_c X_r, "Inner ring"),
  and across the contact width y (along e_t) the spin omega_s = (omega_R u' - Omega e_z).n adds
  y omega_s along a; the traction -tau v/|v| of (5.17) is integrated over the Hertz width
  (y = b sin(t), Gauss-Legendre in t) giving the force F_t along e_t and the spin moment M_n
  about n. Their power is split per raceway contact of a roller: ``sliding`` is the power of
  the contact's rigid slip, ``drilling`` the rest, -sum(F_t (s - s_m)) - sum(M_n omega_s): the
  relative rotation about the contact normal, which along a line contact shows as s varying
  along the roller (a crowned roller rolls without slip at two points only, thesis 2.3.1, Figs.
  2.16, 2.17). The rigid slip s_m is the mean of s weighted by each slice's traction
  conductance G_k = -F_t,k / s_k = sum over the width of g dA (g = tau / |v|, the secant of the
  law (5.17); G_k > 0): s_m = -sum(F_t) / sum(G_k), so that the contact's net force is what
  the rigid slip s_m would give, and sliding = -sum(F_t) s_m = sum(F_t)^2 / sum(G_k). Both parts
  are then >= 0 (the e_t slip power sum(G_k s_k^2) is the G-weighted square of s, its mean
  part plus its variance, sum(G_k (s_k - s_m)^2): the orthogonal split in the G-weighted inner
  product, a Cauchy-Schwarz identity). Until session 18 s_m was the load-weighted mean, which
  has no such property: where s changes sign along a TSRB contact, the load-weighted mean can
  oppose the net traction, and the sliding came out negative (random cases: 64 of 298
  converged, down to -0.35 % of the torque; the TRBs' drilling down to -2.5e-5).
- rolling resistance (lubricant, Zhou & Hoeprich 1991; hysteresis, Johnson 1985) as a couple
  M = (F_h + F_y) R_eq about a, opposing the relative rolling omega_rel.a, on roller and ring;
  its power is (F_h + F_y) times the rolling speed. Its direction is regularised like the boundary
  friction, tanh(omega_rel.a rho / v_s) (rho the contact's distance from the roller axis, v_s
  ``friction.solid_slip_velocity``): 1 to round-off in rolling, and continuous where a lightly
  loaded roller stops rolling on a ring (skids at the end of a load zone: a TRB 31313 roller with
  3.8 N at Fa 3.0 kN, Fr 3.3 kN, 542 rpm); until session 18 it was a sign, the roller's moment
  jumped there by 2 M and its speed balance had no root. (5.18) in this form: the solid rolling
  share Phi M_T,S,r is the micro-slip of the asperity contacts, which the width integration of
  the Phi-weighted solid traction resolves explicitly; it has no separate coefficient. The
  lubricant's F_h of a slice strip covers its loaded length (contact ends between slice centres,
  :func:`sim.physics.elasticity.loaded_lengths`) at the mean line load of the contact, so the loss
  is continuous where a slice enters or leaves contact (:func:`lubrication_state`).
- film viscosity in the traction: per contact, the ambient viscosity lowered by the contact's
  own shear heating (:func:`_viscosity_factor`: flash + mid-film temperature, solved
  self-consistently at the speeds of the previous kinematic pass, like the film thickness),
  then raised to the local pressure (Barus or Roelands) at every width point; both are fixed
  while the roller and cage speeds are solved.
- TRB roller end / rib: point contact, sliding along e_t, traction (5.17) at the Hertz mean
  pressure with the rib's own roughness and B_ZH, C_ZH; its rolling resistance and spin are
  neglected (sliding dominated, thesis 5.5.1).
- cage pocket: the cage supplies the tangential force F_cage that balances the roller along
  e_t; its pocket friction mu_c |F_cage| acts on the spinning roller surface: a moment about
  u' and a force mu_c F_cage sign(omega_R) along v', in the roller's meridian plane. That force
  is the friction load that enters the quasi-static balance (``roller_loads``); without skew the
  raceway tractions act along e_t (out of the meridian plane, balanced by the cage) and their
  spin integrals are even across the width, so they add no meridian-plane force (with skew: the
  lateral tractions, "Roller skew" below).
- drag (optional): fluid drag on the rollers, F_D = 1/2 rho X C_D Dwe Lwe (omega_c Dpw/2)^2
  (Harris & Kotzalas 2007, drag on rolling elements), reacted by the housing (outer ring).

Roller skew (``par.skew``, config friction.skew; issue 18). The skew psi_j turns roller j
about its radial axis v' through its centre, u'' = cos(psi) u' + sin(psi) e_t (skew of a roller
about the axis normal to its raceway contacts: Harris & Kotzalas 2007, Advanced Concepts,
roller skewing; Kellstroem 1979; Nelias, Bercea & Paleu 2008 for the TRB). Assumptions, first
order in psi:

- the load distribution stays planar: the slices are displaced along e_t by x psi, along the
  rings' surfaces of revolution, so their penetrations change only by (x psi)^2 / (2 r), second order;
  loads, frames and film are those of the meridian-plane solution;
- kinematics (:func:`lateral_slip_rate`): the slice's contact point turns about the roller axis
  by beta = b psi and lies at the azimuth phi = f psi = (x psi - y beta) / X_r, where roller and
  ring normals agree (psi u'.n - beta v'.n = phi n_r, i.e. no normal relative velocity); the
  slip along the rolling direction is unchanged, and along the generatrix a the slice slips by
  s_l = -v1 (psi u'.a - beta v'.a - phi a_r) (a skewed cylinder: its surface speed times psi,
  Harris & Kotzalas). tests/friction/test_skew.py checks it against the 3-D skewed slice;
- traction: the same law (5.17) on the 2-D slip (s, s_l + y omega_s) per width point, traction
  -g(|v|) v along the slip (one formula, :func:`_traction`); |v| is then not even in y, so both
  halves of the width are integrated (twice the traction evaluations of an unskewed roller).
  This gives F_t, the lateral force F_l along a and the spin moment M_n. The lateral force is a
  meridian-plane load on the roller (EV_FU, EV_FV, EV_MW: fed back into the load distribution
  with the cage pocket friction, ``roller_loads``); its power -F_l s_l is ``sliding`` and is
  reported on its own (EV_PSKEW, output ``skew_sliding``); its moment about u'' (first order in
  psi) enters the roller's spin balance; it has no z-moment, and turned with the contact point to
  its meridian plane an e_t component f psi a_r F_l, which joins F_t in the force the cage
  supplies. Lateral slip at the rib: the same kinematics for both roller ends, sphere and torus
  (its power is ``rib``); the heating of the lateral slip in the film temperature is neglected;
- moment about the skew axis v' (EV_MS): x F_t of every slice (x = (X - c).u'), M_n (v'.n),
  the rolling couple's v' component, the rib traction at x_rib, and the normal loads turned with
  the contact points: -Q psi f (X_r (n_z v_r - n_r v_z) + n_r (d_r v_z - d_z v_r)), each normal
  lying in the meridian plane of its contact point (for the rib the plane of the roller-end
  sphere centre, azimuth psi x_end / r_centre: the TRB's end sphere has its centre near the
  bearing axis, so its rib load turns strongly with the skew and holds the roller: a restoring
  moment ~ Q_rib x_end^2 n_r / r_centre per radian). Their e_t components join F_t in the force
  the cage supplies. Gyroscopic skew moments (I_x omega_R omega_c psi, < 1 N mm here) are neglected;
- a skew rate psi' (the dynamic solver; 0 in the quasi-static solution) is a rotation about v':
  it moves the slice's roller surface by psi' x along e_t and adds psi' v'.n to the spin about n
  (rigid-body kinematics, as the spin wR u'), and so damps the skew through the tractions
  ("Rates" below);
- the cage pocket closes the balance. Nothing else holds a skewed roller elastically: without
  the pocket a TSRB roller's friction moment keeps its sign across every skew (tested), so
  there is no free equilibrium. The pocket is a clearance plus a stiff penalty couple
  (:func:`pocket_skew_couple`): zero for |psi| <= psi_c = atan(c_p / Lwe) (c_p the pocket's
  circumferential play, config friction.skew.pocket_clearance), -k (|psi| - psi_c) sign(psi)
  beyond it, k = k_p Lwe^2 / 2 (two end contacts of stiffness k_p at +-Lwe/2). If the friction
  moment vanishes inside the clearance the roller sits there (a free skew equilibrium: the TRBs,
  held by the rib); otherwise it rests on the pocket at psi_c + M / k.

Rates (the dynamic solver, :data:`RollerRates`; all zero in the quasi-static solution, where the
kernels then do exactly the arithmetic they did without them). The roller moves as a rigid body,
v(P) = v_c + Omega x (P - c), with Omega relative to its meridian frame (which orbits with it)
= omega_R u'' + psi' v' + omega_w w'' (w'' = u'' x v' = -e_t + O(psi)); the inner ring's surface
moves with its spin and its translation V. At the slice's contact point X, with x = (X - c).u',
(dr, dz) = X - c [mm], rates in rad/s and mm/s, the relative velocity roller - ring gains, first
order in psi as the skew model:

- along e_t: psi' x (the tilt and the centre move in the meridian plane, v_c.e_t = 0);
- in the meridian plane: v_c + omega_w (dr e_z - dz e_r) (= v_c - omega_w e_t x (X - c));
  its component along a adds to the lateral slip s_l of the 2-D slip (the skew's own, psi times
  lateral_slip_rate, keeps the spin's surface speed: psi' x in it is second order, psi psi'); its
  component along n (squeeze) is not a slip: the contact damping of the normal chart takes it.
  A roller (unskewed) translating along a at speed v thus slips laterally by exactly v at every
  slice, a tilt rate by omega_w (dr a_z - dz a_r), affine in the contact point;
- spin about n: psi' v'.n; rolling about a: psi' v'.a (omega_w w'' has no component along n or a).

The tractions' forces and moments are the same as for the skew (F_t along e_t, F_l along a, at X):
on the roller F_l a through EV_FU, EV_FV at the centre and its moment about w'' (EV_MW), F_t x
about v' (EV_MS); so their power on the rates, F_t psi' x + F_l (s_l - psi lateral_slip_rate), is
exactly the rates' share of the slip power F_t s + F_l s_l whose negative the loss channels count
(virtual power; tests/dynamic/test_slip_rates.py, and the dynamic solver's energy balance closes to
its integration tolerance, tests/dynamic/test_ladder.py). The inner-ring contacts' tractions react
on the inner ring (EV_RING_R, EV_RING_T, EV_RING_Z), whose translation V is in the slip; their power
on V, -F_t V_t - F_l V.a, closes the same balance. Both solvers apply that reaction: the
quasi-static ring balance (:func:`friction_loads`, with the friction loads on the rollers; the axial
sum is 1.0 kN of 35 kN for the skewed TRB 31313 at the pinion case; the e_t parts of the load zone add
up to a lateral force, which the ring's lateral displacement balances), the dynamic solver on the
ring's translation, whose velocity it passes as V.
The rib takes the same rates on its 2-D slip (s, s_b), s_b along b = n_rib x e_t in the meridian plane.
The entrainment speed of the transit time 2 b / u is the mean speed of the surfaces relative to the
contact point (Reynolds' equation in the frame of a moving contact, as for a cam and follower): the
contact lies at the azimuth f psi (lateral_slip_rate; psi x_n / r_centre at the rib) and moves
along e_t at X_r f psi', so u = 1/2 |v1 + v2 + psi' (x - 2 X_r f)|. The film itself (thickness,
load share, thermal viscosity, lubrication_state) stays that of the spins, refreshed per window; the
lateral slip of the rates does not enter the shear heating.

Inner ring (ContactLoads.ring, layout RP_*). The inner ring spins at omega_i about its own axis,
which the load displaces from the bearing axis: at a roller's azimuth by delta_r along e_r,
delta_a along e_z and e_perp along e_t, and turns by phi in the meridian plane (the imposed tilt's
component there, tilt cos(psi); sim.physics.contact.to_ring gives a point's ring coordinates). Its
surface at a contact point X moves with the rigid-body velocity omega_i n_i x (X - C) (n_i its
axis, C its centre), which in the roller's meridian frame, first order in the displacement, is
omega_i r' along e_t (r' the point's distance from the ring's own axis in the plane, from to_ring)
plus omega_i e_perp along e_r; its angular velocity omega_i n_i has the components omega_i n'_z,
omega_i a'_z about the normal n and the tangent a (n', a' in the ring's coordinates). Before
session 35 the kernels took the ring's surface about the bearing axis, omega_i X_r, an error of
omega_i delta_r: the quasi-static torque moved by 4e-6 to 3e-3 on ordinary combined and tilted
cases (TRB 32208, 31313, reference, prototype and pinion TSRBs; README), by +19 % for
tsrb_pinion_long at 5 / 4 kN, 6340 rpm, whose ring the load displaces by 0.73 mm radially. The e_perp part moves the surface along the generatrix a: a lateral slip -omega_i
e_perp a_r (the raceway's circumferential direction turned by e_perp / r against the roller's
rolling direction; the rib likewise along b). The moment of a roller's inner contacts about the
ring's own axis (EV_TRING: F_t r', the couples' components along n_i, e_perp times the lateral
force's radial component) times omega_i is the power the ring's spin puts into them: with the
slips above, -omega_R EV_MU + omega_i EV_TRING - omega_c EV_TZ is the roller's dissipated power
exactly (tests/friction/test_inner_ring_axis.py), so the drive's torque is EV_TRING summed, which
both solvers report. What the quasi-static solution leaves out (its ContactLoads.ring has e_perp
0): the e_perp lateral slip, odd in the azimuth where the ring moves along the load (it would break
the mirror symmetry of its roller classes, sim.solvers.symmetry, and it comes with the rollers'
orbit rates, which that solution has not either), and the imposed tilt's component across the
meridian plane (tilt sin(psi), the same kind of lateral slip); the dynamic solver, whose ring
translates and carries the imposed tilt's turn tilt cos(phi_j) in each meridian plane, has the
e_perp slip and, like the quasi-static solution, not the tilt's component across the plane.

Unknowns: omega_R,j (roller moment about u' = 0, per roller), with skew psi_j (moment about
v' = 0, per roller), and omega_c (cage moment about z = 0: sum over rollers of the z-moments the
contacts exert). At that equilibrium the torque the
rollers and the oil exert on the outer ring equals power loss / omega_i exactly (energy
balance); the kernels compute both independently so the identity checks the solution.
"""
import math
from collections import namedtuple

import numpy as np

from sim._math.jit import internal_kernel, kernel
from sim._math.roots import root_search, root_search_step
from sim.physics.contact import hertz_line_half_width, hertz_line_pressure, to_ring_turned
from sim.physics.ehl import (film_line, film_point, film_temperature_rise, film_traction_eyring, film_traction_maxwell,
                             flash_temperature_rise, pressure_term, rolling_force_hysteresis,
                             rolling_moment_hydrodynamic, solid_load_share, thermal_loading, film_thermal_factor_gupta,
                             traction_eyring, traction_per_speed, traction_solid, viscosity_at_pressure,
                             viscosity_log_ratio)
from sim.physics.elasticity import loaded_lengths

# Loss and torque channels of the kernels (order of the DATA.md `component` coordinate).
COMPONENTS = ["rolling", "hysteresis", "sliding", "drilling", "rib", "cage", "drag"]
NC = len(COMPONENTS)
# Roller evaluation vector (the kernels accumulate into it, the solvers sum it over rollers):
# M_u, T_z on roller, T_z on outer ring, F_t along e_t (contacts + rib), then the powers of COMPONENTS.
EV_MU, EV_TZ, EV_TOUT, EV_FT = 0, 1, 2, 3
EV_P0 = 4
(EV_ROLLING, EV_HYSTERESIS, EV_SLIDING, EV_DRILLING, EV_RIB, EV_CAGE, EV_DRAG) = range(EV_P0, EV_P0 + NC)
# then, for roller skew (module docstring, "Roller skew"): the friction moment about the skew axis v'
# [N mm]; the lateral tractions as meridian-plane loads on the roller (along u', along v' [N], moment
# about u' x v' [N mm], the layout of the quasi-static roller_loads); the power of the lateral
# traction on the lateral slip of the skewed roller (and of the dynamic solver's rates, "Rates") [N mm/s],
# a part of EV_SLIDING.
EV_MS = EV_P0 + NC
EV_FU, EV_FV, EV_MW = EV_MS + 1, EV_MS + 2, EV_MS + 3
EV_PSKEW = EV_MS + 4
# then the friction force of the inner-ring raceway and rib contacts on the inner ring along e_r, e_t,
# e_z of the roller's meridian frame [N] (the reaction of their tractions on the roller, module
# docstring "Rates")
EV_RING_R, EV_RING_T, EV_RING_Z = EV_PSKEW + 1, EV_PSKEW + 2, EV_PSKEW + 3
# then the moment of the inner-ring raceway and rib contacts on the roller about the inner ring's own
# axis [N mm] (module docstring, "Inner ring"): times omega_i, the power the inner ring's spin puts into
# the roller's contacts (the drive's share of this roller)
EV_TRING = EV_RING_Z + 1
NEV = EV_TRING + 1
# FRICTION_LOADS, friction loads of a roller's contacts in the quasi-static balance (:func:`friction_loads`): on the
# roller along u', v' [N] and about u' x v' [N mm] (BearingModel.solve's roller_loads), then on the
# inner ring along e_r, e_t, e_z of the roller's frame [N] (its ring_loads)
FL_U, FL_V, FL_W, FL_RING_R, FL_RING_T, FL_RING_Z = range(6)
NFL = 6

# Rates of a roller and of the inner ring that move the contact surfaces besides the spins (the
# dynamic solver's state; all zero in the quasi-static solution, :data:`NO_RATES`), read by
# :func:`roller_traction` (numba-supported named tuple; module docstring, "Rates"):
RollerRates = namedtuple("RollerRates", [
    "psi_dot",      # rad/s, skew rate: roller angular velocity relative to the meridian frame about v'
    "omega_w",      # rad/s, tilt rate: that angular velocity about w'' = u'' x v' (theta' cos(psi); -e_t at psi = 0)
    "vc_r",         # mm/s, roller centre velocity in its meridian frame (orbiting with it) along e_r
    "vc_z",         # mm/s, ... along e_z (no e_t component: the frame orbits with the roller)
    "vi_r",         # mm/s, inner-ring translation velocity at the roller's azimuth along e_r
    "vi_t",         # mm/s, ... along e_t
    "vi_z",         # mm/s, ... along e_z
])
NO_RATES = RollerRates(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)

# Friction parameters of one case (numba-supported named tuple; built by
# sim.api.friction_model.FrictionModel from the config, the per-case fields with ``_replace``).
FrictionParams = namedtuple("FrictionParams", [
    "eta0",         # MPa s, ambient-pressure viscosity at the oil temperature (per case): the outer ring's contacts
    "eta0_inner",   # MPa s, the same at the inner ring's temperature (its raceway and rib; per case)
    "alpha",        # 1/MPa, Barus pressure-viscosity coefficient
    "Z",            # 1, Roelands pressure-viscosity index at the oil temperature (per case)
    "pv_model",     # int, pressure-viscosity law: sim.physics.ehl.PV_BARUS or PV_ROELANDS
    "beta",         # 1/K, temperature-viscosity coefficient at the oil temperature (per case)
    "traction_law", # int, film traction law: TRACTION_EYRING or TRACTION_NEWTON_LIMITED (module constants)
    "rheology",     # sim.physics.ehl.FilmRheology: Eyring stress, limiting shear stress law, film shear modulus
    "solid",        # sim.physics.ehl.SolidFriction: asperity friction coefficient and its regularising slip
    "hysteresis",   # 1, elastic hysteresis loss factor of the steel
    "mu_cage",      # 1, roller / cage pocket friction coefficient
    "sigma",        # mm, composite roughness of the raceway contacts
    "B_ZH",         # 1, Zhou-Hoeprich load-share coefficient of the raceway contacts, thesis (5.16)
    "C_ZH",         # 1, Zhou-Hoeprich load-share exponent of the raceway contacts
    "sigma_rib",    # mm, composite roughness of the roller-end / rib contact (TRB; 0 for a TSRB)
    "B_ZH_rib",     # 1, B_ZH of the roller-end / rib contact
    "C_ZH_rib",     # 1, C_ZH of the roller-end / rib contact
    "film",         # int, film-thickness formula: sim.physics.ehl.FILM_PAN_HAMROCK or FILM_DOWSON_HIGGINSON
    "drag_k",       # N s^2 (= t mm), drag force on a roller over omega_c^2 (per case: oil density; 0 no drag)
    "thermal",      # bool, shear heating lowers the film viscosity in the traction
    "k_oil",        # W/(m K), thermal conductivity of the oil
    "k_steel",      # W/(m K), thermal conductivity of the steel (flash temperature)
    "kappa_steel",  # mm^2/s, thermal diffusivity of the steel
    "dT_tol",       # K, tolerance of the film temperature solve
    "inlet_heating",  # bool, inlet shear heating thins the film and the rolling loss (Gupta et al. 1992)
    "boundary_only",  # bool, no film: every contact in boundary friction, no rolling loss (the breakaway
                      # torque at load.speed = 0, sim.api.friction_model)
    "skew",           # bool, roller skew is an unknown of the kinematics (module docstring, "Roller skew")
    "skew_clearance", # rad, skew at which a centred roller touches its cage pocket, atan(c_p / Lwe)
    "skew_stiffness", # N mm/rad, couple per skew angle of the pocket beyond the clearance
])

# Film traction laws (config friction.traction_law): the Maxwell-Eyring film limited by tau_L
# (sim.physics.ehl.traction_eyring, the default) or the earlier Newtonian/Maxwell film limited
# by tau_L (sim.physics.ehl.traction_per_speed).
TRACTION_EYRING = 0
TRACTION_NEWTON_LIMITED = 1
TRACTION_LAWS = {"eyring": TRACTION_EYRING, "newton_limited": TRACTION_NEWTON_LIMITED}


@kernel
def _traction(par, p, v, h, phi, eta_p, t_transit):
    """Traction stress over sliding speed tau/|v| [MPa s/mm] of the configured film law, thesis (5.17)."""
    if par.traction_law == TRACTION_EYRING:
        return traction_eyring(p, v, h, phi, eta_p, par.rheology, par.solid, t_transit)
    return traction_per_speed(p, v, h, phi, eta_p, par.rheology, par.solid, t_transit)


@internal_kernel
def _film_traction(par, p, v, h, phi, eta_p, t_transit):
    """The film part of :func:`_traction` (h > 0, phi < 1): :func:`_traction` is the solid part
    (sim.physics.ehl.traction_solid) plus this."""
    if par.traction_law == TRACTION_EYRING:
        return film_traction_eyring(p, v, h, phi, eta_p, par.rheology, t_transit)
    return film_traction_maxwell(p, v, h, phi, eta_p, par.rheology, t_transit)


# The solved bearing as the friction kernels read it (numba-supported named tuple).
ContactLoads = namedtuple("ContactLoads", [
    "q",            # (Z, 2, N) line loads [N/mm], race 0 outer, 1 inner
    "Qrib",         # (Z,) roller-end / rib loads [N]
    "R_eq",         # (2, N) radii of relative curvature [mm]
    "w",            # slice width [mm]
    "E_star",       # contact modulus [MPa]
    "rib_end",      # (6,) roller end at the rib contact (TRB; zeros for a TSRB): geometry arrays ``rib_end``
                    # [mm]: R_n, distance from the contact point along the rib normal to the roller axis (the
                    # end sphere's radius; the torus's r_k + rim / sin(opening)); x_n, where that normal meets
                    # the roller axis, along u' from the roller centre (the sphere's centre); R_t, R_m, relative
                    # radii of curvature along e_t and across it (sim.geometry: the rib is a cone); then
                    # sim.physics.contact.hertz_point_radii(R_t, R_m)[1:]: R_area [mm], the radius of the
                    # circle of the Hertz contact's area, and kappa [1], its semi-axis along e_t over the other
    "nrib",         # (Z, 2) unit rib normal (r, z) into the rib at the solution (TRB; zeros for a TSRB)
    "rho_m",        # radius of the roller surface in the cage pocket, Dwe/2 [mm]
    "free",         # (Z, 2, N) free penetrations of the slices [mm] (sim.physics.elasticity.coupled_slice_loads)
    "end_drop",     # (2, 2, M) the end-profile table of the contact ends (sim.physics.roller_contact.BearingArrays)
    "ring",         # (Z, NRP) the inner ring's pose in each roller's meridian plane (layout RP_*, module
                    # docstring "Inner ring"): the ring's axis about which it spins
])
# Pose of the inner ring in a roller's meridian plane (ContactLoads.ring): its radial and axial
# displacement [mm] (sim.physics.contact.to_ring's translation), the cosine and sine of its turn in the
# plane (to_ring's ring_phi), and the offset of its axis across the plane, along e_t [mm]
RP_DR, RP_DA, RP_COS, RP_SIN, RP_PERP = range(5)
NRP = 5

# Film, load share, rolling resistance, Hertz data and film viscosity of every contact, written by
# :func:`lubrication_state` and fixed while the kinematics are solved (0 where unloaded; Fh also on
# the unloaded part of a strip at a contact end, sim.physics.elasticity.loaded_lengths).
FilmState = namedtuple("FilmState", [
    "h",            # (Z, 2, N) film thickness [mm]
    "Phi",          # (Z, 2, N) solid load share [1]
    "Fh",           # (Z, 2, N) hydrodynamic rolling force of both surfaces together [N] (couple Fh R_eq)
    "Fy",           # (Z, 2, N) hysteresis rolling force [N]
    "p0",           # (Z, 2, N) Hertz pressure [MPa]
    "b",            # (Z, 2, N) Hertz half-width [mm]
    "Eta",          # (Z, 2, N, len(quad.wq)) film viscosity at the pressure of each width point [MPa s]
    "hrib",         # (Z,) rib film [mm]
    "Phirib",       # (Z,) rib solid load share [1]
    "prib",         # (Z,) rib Hertz mean pressure [MPa]
    "Etarib",       # (Z,) rib film viscosity at that pressure [MPa s]
])
# Scratch arrays of :func:`roller_lubrication`: width-point data (NWP, len(quad.wq)), loaded
# lengths (n,) [mm] and loaded flags (n,) of one strip row.
FilmScratch = namedtuple("FilmScratch", ["pts", "lengths", "loaded"])

# Gauss-Legendre rule across a contact's width (:func:`width_quadrature`): weights wq of the nodes
# t in (0, pi/2) of y = b sin(t), with cos(t) and sin(t) at the nodes (the kernels read only
# these: they are evaluated once per rule, not at every width point of every call).
WidthQuadrature = namedtuple("WidthQuadrature", ["cos_t", "sin_t", "wq"])


def width_quadrature(n):
    """:data:`WidthQuadrature` of ``n`` Gauss-Legendre points on t in (0, pi/2)."""
    t, wt = np.polynomial.legendre.leggauss(int(n))
    tq = 0.25 * np.pi * (t + 1.0)
    # math.cos/sin per node: the libm values the kernels computed per point before (numpy's
    # vectorised cos/sin may differ in the last ulp)
    return WidthQuadrature(np.array([math.cos(x) for x in tq]), np.array([math.sin(x) for x in tq]), 0.25 * np.pi * wt)

# Everything the friction of a roller depends on besides the speeds: ContactFrames
# (sim.physics.roller_contact), ContactLoads, FilmState, FrictionParams, WidthQuadrature.
FrictionCase = namedtuple("FrictionCase", ["frames", "bearing", "film", "par", "quad"])

# Floor of the entrainment speed u [mm/s] in the transit time 2 b / u: zero entrainment gives an
# effectively infinite transit time (a purely viscous film) instead of a division by zero.
MIN_ENTRAINMENT_SPEED = 1e-300
# Transit time [s] taken as infinite: no Maxwell relaxation term (the heat estimate of
# :func:`_heat_flux` leaves it out; it only matters at micro-slip, where the heat is negligible).
# Infinite, not a large finite number: 1e300 made the Deborah number eta/(G t) of the traction laws
# subnormal (~1e-310 at the film viscosities of the width points' edges), and subnormal arithmetic
# made each Eyring solve 25x slower (measured 412 vs 16 ns; the thermal film solve was 90 % of
# lubrication_state); the results are the same (the 1e-300-relative Maxwell term rounded away).
NO_RELAXATION = math.inf
# Illinois steps of the film temperature solve: Illinois converges superlinearly (order 1.44,
# Dowell & Jarratt 1971), so this only stops a pathological case (then the last iterate is used).
# An np.int64 types like the kinematic solves' max_iter (a Python int constant would compile a
# second, Literal[int] copy of root_search).
FILM_TEMPERATURE_MAX_STEPS = np.int64(100)


@internal_kernel
def _roller_surface_speed(wR, Xr, Xz, cr, cz, ur, uz):
    """Speed along e_t of the roller surface at (Xr, Xz) [mm/s]: wR its speed about its axis
    (ur, uz) through the centre (cr, cz) [rad/s]; lengths [mm]."""
    return wR * (uz * (Xr - cr) - ur * (Xz - cz))


@kernel
def ring_surface_speed(wi_s, wc, ring, Xr, Xz):
    """Speed along e_t of a ring's surface at the meridian point (Xr, Xz) in the cage frame [mm/s]:
    the ring spins at wi_s [rad/s] about its own axis (0 for the outer ring, omega_i for the inner),
    at the distance r' of the point from that axis, and the cage frame turns at wc [rad/s] about the
    bearing axis; ``ring`` (NRP,): the inner ring's pose (module docstring, "Inner ring"). The first
    value of :func:`_ring_motion` (any normal)."""
    return _ring_motion(1, wi_s, wc, ring, Xr, Xz, 0.0, 1.0)[0]


@internal_kernel
def _ring_motion(s, wi, wc, ring, Xr, Xz, nr, nz):
    """Motion of ring s (0 outer, fixed; 1 inner, spinning at wi [rad/s] about its own axis, pose
    ``ring``) at a contact point X with normal n (into the ring), in the cage frame (turning at wc
    about the bearing axis; module docstring, "Inner ring"): its surface speed along e_t [mm/s], its
    angular velocity about n and about a = n x e_t = (-n_z, n_r) [rad/s], and, for the moment about
    the ring's axis, the point's distance r' from that axis [mm] and the axial components of n and a
    in the ring's coordinates [1] (the outer ring's: X_r, n_z, n_r)."""
    if s == 0:
        return -wc * Xr, -wc * nz, -wc * nr, Xr, nz, nr
    c = ring[RP_COS]
    sn = ring[RP_SIN]
    r_own = to_ring_turned(Xr, Xz, ring[RP_DR], ring[RP_DA], c, sn)[0]
    nz_own = to_ring_turned(nr, nz, 0.0, 0.0, c, sn)[1]
    az_own = to_ring_turned(-nz, nr, 0.0, 0.0, c, sn)[1]
    return wi * r_own - wc * Xr, wi * nz_own - wc * nz, wi * az_own - wc * nr, r_own, nz_own, az_own


@internal_kernel
def outer_rolling_speed(j, wc, case):
    """Speed of roller j about its axis [rad/s] at which it rolls on the outer raceway without
    rigid slip at cage speed wc [rad/s] (the outer ring turning at -wc in the cage frame): the
    sliding speed (:func:`_roller_surface_speed` less the ring's -wc X_r), linear in omega_R, vanishes in the mean of its outer
    slices weighted by their line loads (the held spin of a roller resting on the outer raceway,
    sim.solvers.kinematics). 0 for a roller without outer load."""
    X, Cen, Ax = case.frames.X, case.frames.Cen, case.frames.Ax
    q = case.bearing.q
    roll = 0.0
    ring = 0.0
    for k in range(q.shape[2]):
        if q[j, 0, k] > 0.0:
            roll += q[j, 0, k] * _roller_surface_speed(1.0, X[j, 0, k, 0], X[j, 0, k, 1], Cen[j, 0], Cen[j, 1],
                                                       Ax[j, 0], Ax[j, 1])
            ring -= q[j, 0, k] * wc * X[j, 0, k, 0]
    return ring / roll if roll != 0.0 else 0.0


# Rows of a contact's table of width points (:func:`_width_points`, :func:`_heat_flux`): what the
# film temperature solve needs at every trial temperature but does not depend on the viscosity.
WP_P, WP_TERM, WP_V, WP_W, WP_SOLID = range(5)   # pressure [MPa], sim.physics.ehl.pressure_term [1],
NWP = 5                                          # sliding speed [mm/s], weight [1], solid traction / speed


@internal_kernel
def _width_points(p0k, bk, par, quad, pts):
    """Pressures of a contact's width points and their :func:`sim.physics.ehl.pressure_term` into
    ``pts[WP_P]``, ``pts[WP_TERM]``; returns the number of points. Line slice (bk > 0): p0 cos(t)
    at the nodes of ``quad``; point contact (bk = 0, the rib): one point at the mean pressure p0k."""
    npts = quad.wq.shape[0] if bk > 0.0 else 1
    for i in range(npts):
        p = p0k * quad.cos_t[i] if bk > 0.0 else p0k
        pts[WP_P, i] = p
        pts[WP_TERM, i] = pressure_term(p, par.alpha, par.Z, par.pv_model)
    return npts


@internal_kernel
def _heat_flux(theta, eta0, hk, phik, npts, q_sol, par, pts):
    """Mean frictional heat flux of a contact [N/(mm s)]: (lubricant film, total).

    Line slice: traction (5.17) at the Hertz pressure p0 cos(t) and the sliding speed
    sqrt(st^2 + (y ws)^2), y = b sin(t), averaged over the width as in :func:`roller_friction`;
    point contact (the rib): at the mean pressure and the speed |st|; the ``npts`` points of
    ``pts`` (:func:`_viscosity_factor_at` fills them). ``theta`` scales the ambient viscosity
    (thermal reduction) ``eta0`` [MPa s]; ``q_sol``: the solid part of the heat, which does not
    depend on it.
    """
    eta = eta0 * theta
    log_ratio = viscosity_log_ratio(eta, par.pv_model)
    q_tot = 0.0
    for i in range(npts):
        p = pts[WP_P, i]
        v = pts[WP_V, i]
        g = pts[WP_SOLID, i]
        if phik < 1.0:
            eta_p = viscosity_at_pressure(eta, log_ratio, pts[WP_TERM, i], par.pv_model)
            g += _film_traction(par, p, v, hk, phik, eta_p, NO_RELAXATION)
        q_tot += pts[WP_W, i] * g * v * v
    return q_tot - q_sol, q_tot


# A contact whose film temperature :func:`_viscosity_factor` solves (numba-supported named tuple):
# p0, Hertz pressure (line slice) or mean pressure (point contact) [MPa]; b, Hertz half-width of a
# line slice [mm] (0 for the point contact of the rib); h, film [mm]; phi, solid load share [1]; ws,
# spin about the contact normal [rad/s]; half_length, half length of the contact along the rolling
# direction [mm]; U1, U2, surface speeds of roller and ring [mm/s] (sliding speed U1 - U2); eta0,
# ambient-pressure viscosity of the oil at the contact's ring [MPa s] (FrictionParams.eta0,
# eta0_inner).
HeatedContact = namedtuple("HeatedContact", ["p0", "b", "h", "phi", "ws", "half_length", "U1", "U2", "eta0"])


@kernel
def _viscosity_factor(contact, par, quad):
    """Thermal reduction of the film viscosity in the traction, theta = exp(-beta dT) [1].

    dT is the film temperature of the contact's own shear heating: the flash temperature of the
    surfaces under the total frictional heat plus the mid-film rise under the film's heat
    (sim.physics.ehl.flash_temperature_rise, film_temperature_rise), with the viscosity at the raised
    temperature, eta0 exp(alpha p - beta dT) (Reynolds' exponential law, beta the local
    slope of the lubricant's Ubbelohde-Walther line). Heating falls as dT rises, so
    f(dT) = rise(q(theta(dT))) - dT falls and has one root in [0, rise(q(1))], found by
    :func:`sim._math.roots.root_search_step` to par.dT_tol K. The maximum traction (limiting
    shear) is not reduced; the Maxwell transit-time term is left out of the heat estimate (it
    only matters at microslip, where the heat is negligible).

    contact: :data:`HeatedContact`; par: :data:`FrictionParams`; quad: :data:`WidthQuadrature`.
    """
    pts = np.empty((NWP, quad.wq.shape[0]))
    npts = _width_points(contact.p0, contact.b, par, quad, pts)
    return _viscosity_factor_at(contact, par, quad, npts, pts)


@internal_kernel
def _viscosity_factor_at(contact, par, quad, npts, pts):
    """:func:`_viscosity_factor` on the contact's ``npts`` width points ``pts`` (NWP, len(quad.wq)),
    pressures filled by :func:`_width_points` (:func:`lubrication_state` reuses their pressure
    terms for the film viscosity); their speeds, weights and solid traction are written here,
    once for all trial temperatures."""
    bk, hk, phik, ws, half_length, U1, U2 = (contact.b, contact.h, contact.phi, contact.ws, contact.half_length,
                                             contact.U1, contact.U2)
    if not par.thermal or hk <= 0.0:
        return 1.0
    beta = par.beta
    tol = par.dT_tol
    st = U1 - U2
    q_sol = 0.0
    for i in range(npts):
        p = pts[WP_P, i]
        if bk > 0.0:
            vy = bk * quad.sin_t[i] * ws
            v = np.sqrt(st * st + vy * vy)
            weight = quad.cos_t[i] * quad.wq[i]        # sum of cos(t) w over (0, pi/2) = 1
        else:
            v = abs(st)
            weight = 1.0
        pts[WP_V, i] = v
        pts[WP_W, i] = weight
        pts[WP_SOLID, i] = traction_solid(p, v, phik, par.solid)
        q_sol += weight * phik * par.solid.mu_s * p * v * np.tanh(v / par.solid.v_s)

    def rise(dT):
        q_film, q_tot = _heat_flux(np.exp(-beta * dT), contact.eta0, hk, phik, npts, q_sol, par, pts)
        return (film_temperature_rise(q_film, hk, par.k_oil)
                + flash_temperature_rise(q_tot, half_length, U1, U2, par.k_steel, par.kappa_steel))

    hi = rise(0.0)
    if hi <= tol:
        return np.exp(-beta * hi)
    search = root_search(0.0, hi, hi, tol, tol, FILM_TEMPERATURE_MAX_STEPS)      # f(0) = rise(0) - 0
    while not search.done:
        search = root_search_step(search, rise(search.x) - search.x)
    return np.exp(-beta * search.x)


@kernel
def lubrication_state(wR, orbit, wi, active, case):
    """Film, solid load share, rolling resistance forces, Hertz data and thermal viscosity factor
    of every loaded contact, at the speeds wR, orbit: writes ``case.film``.

    Parameters
    ----------
    wR : ndarray (Z,)
        Roller speeds about u' [rad/s].
    orbit : ndarray (Z,)
        Each roller's orbit speed [rad/s]: the cage's, or a free roller's own
        (sim.solvers.kinematics, "Pocket play"), as the time domain takes it.
    wi : float
        Inner-ring speed [rad/s].
    active : ndarray (Z,) of bool
        Rollers to evaluate; the others' film is left as it is (the caller never reads it).
    case : FrictionCase
        Frames, bearing arrays and parameters are read; ``case.film`` (:data:`FilmState`) is
        written: film viscosity ``Eta`` at the pressure p0 cos(t) of each width point after the
        thermal reduction, fixed while the kinematics are solved.
    """
    n = case.bearing.q.shape[2]
    scratch = film_scratch(n, case.quad.wq.shape[0])
    for j in range(case.bearing.q.shape[0]):
        if active[j]:
            roller_lubrication(j, wR[j], orbit[j], wi, case, scratch)


@kernel
def film_scratch(n, nq):
    """:data:`FilmScratch` for n slices and nq width points."""
    return FilmScratch(np.empty((NWP, nq)), np.empty(n), np.empty(n, dtype=np.bool_))


@kernel
def roller_lubrication(j, wR, wc, wi, case, scratch):
    """Film of roller j (the part of :func:`lubrication_state` of one roller) at its speed wR
    and orbit speed wc [rad/s], from its line loads, rib load and frames in ``case``: writes
    ``case.film`` for roller j. The time-domain solver calls it at every right-hand side, so
    that the film follows each roller's load around the bearing."""
    X, Nrm, Cen, Ax, Xrib = case.frames
    brg, film, par, quad = case.bearing, case.film, case.par, case.quad
    q, Qrib, R_eq, w, E_star = brg.q, brg.Qrib, brg.R_eq, brg.w, brg.E_star
    h, Phi, Fh, Fy, p0, b, Eta = film.h, film.Phi, film.Fh, film.Fy, film.p0, film.b, film.Eta
    n = q.shape[2]
    Ep = 2.0 * E_star                  # E' of the EHL film formulas [MPa]
    pts, lengths, loaded = scratch
    cr = Cen[j, 0]
    cz = Cen[j, 1]
    ur = Ax[j, 0]
    uz = Ax[j, 1]
    ring = brg.ring[j]
    for s in range(2):
        eta0 = par.eta0 if s == 0 else par.eta0_inner    # the oil at this ring's temperature
        # EHL rolling force of the strips: per unit length at the contact's mean line load
        # (it hardly depends on the load: W^0.0126, rolling_force_hydrodynamic) over the
        # loaded length of each strip (contact ends between slice centres,
        # sim.physics.elasticity.loaded_lengths), so the loss is continuous where a slice
        # enters or leaves contact, as the contact length is
        Qs = 0.0
        for k in range(n):
            loaded[k] = q[j, s, k] > 0.0
            Qs += w * q[j, s, k]
        loaded_lengths(brg.free[j, s], loaded, w, brg.end_drop[s], lengths)
        Ls = lengths.sum()
        q_mean = Qs / Ls if Ls > 0.0 else 0.0
        for k in range(n):
            qk = q[j, s, k]
            h[j, s, k] = 0.0
            Phi[j, s, k] = 0.0
            Fh[j, s, k] = 0.0
            Fy[j, s, k] = 0.0
            p0[j, s, k] = 0.0
            b[j, s, k] = 0.0
            if qk <= 0.0 and (lengths[k] <= 0.0 or par.boundary_only):
                continue
            nr = Nrm[j, s, k, 0]
            nz = Nrm[j, s, k, 1]
            v2, om_n = _ring_motion(s, wi, wc, ring, X[j, s, k, 0], X[j, s, k, 1], nr, nz)[:2]
            v1 = _roller_surface_speed(wR, X[j, s, k, 0], X[j, s, k, 1], cr, cz, ur, uz)
            u = 0.5 * abs(v1 + v2)
            R = R_eq[s, k]
            if lengths[k] > 0.0 and not par.boundary_only:
                # inlet shear heating lowers the Poiseuille rolling force (Zhou & Hoeprich 1991
                # eq. 22, factor of Gupta et al. 1992), here at the mean line load's pressure
                phi_R = 1.0
                if par.inlet_heating and u > 0.0:
                    phi_R = film_thermal_factor_gupta(hertz_line_pressure(q_mean, R, E_star), Ep,
                                                      thermal_loading(eta0, par.beta, u, par.k_oil),
                                                      (v1 - v2) / u)
                # the film retards both surfaces by F each (Reynolds: dissipation 2 u F, couple
                # 2 F R, sim.physics.ehl.rolling_moment_hydrodynamic): Fh is the sum of both
                Fh[j, s, k] = phi_R * rolling_moment_hydrodynamic(u, q_mean, R, lengths[k], eta0, par.alpha,
                                                                   Ep) / R
            if qk <= 0.0:
                continue
            bk = hertz_line_half_width(qk, R, E_star)
            b[j, s, k] = bk
            p0[j, s, k] = hertz_line_pressure(qk, R, E_star)
            if par.boundary_only:
                # no entrainment, no film: the solid carries the contact (Phi = 1, boundary
                # friction), no EHL rolling force and, without rolling, no hysteresis loss;
                # Eta is left as it is: the traction laws never read it without a film
                Phi[j, s, k] = 1.0
                continue
            # inlet shear heating thins the film (Zhou & Hoeprich 1991 eq. 22, factor of Gupta
            # et al. 1992)
            phi_T = 1.0
            if par.inlet_heating and u > 0.0:
                phi_T = film_thermal_factor_gupta(p0[j, s, k], Ep, thermal_loading(eta0, par.beta, u, par.k_oil),
                                                  (v1 - v2) / u)
            hk = phi_T * film_line(u, qk, R, eta0, par.alpha, Ep, par.film)
            h[j, s, k] = hk
            Phi[j, s, k] = solid_load_share(hk, par.sigma, par.B_ZH, par.C_ZH)
            Fy[j, s, k] = rolling_force_hysteresis(qk, bk, R, w, par.hysteresis)
            ws = wR * (ur * nr + uz * nz) - om_n
            npts = _width_points(p0[j, s, k], bk, par, quad, pts)
            theta = _viscosity_factor_at(HeatedContact(p0[j, s, k], bk, hk, Phi[j, s, k], ws, bk, v1, v2, eta0), par,
                                         quad, npts, pts)
            eta = eta0 * theta
            log_ratio = viscosity_log_ratio(eta, par.pv_model)
            for i in range(npts):
                Eta[j, s, k, i] = viscosity_at_pressure(eta, log_ratio, pts[WP_TERM, i], par.pv_model)
    film.hrib[j] = 0.0
    film.Phirib[j] = 0.0
    film.prib[j] = 0.0
    film.Etarib[j] = 0.0
    if Qrib[j] > 0.0:
        v1 = _roller_surface_speed(wR, Xrib[j, 0], Xrib[j, 1], cr, cz, ur, uz)
        v2 = ring_surface_speed(wi, wc, ring, Xrib[j, 0], Xrib[j, 1])
        u = 0.5 * abs(v1 + v2)
        R_t = brg.rib_end[2]
        R_m = brg.rib_end[3]
        # Hertz point contact of the end (sphere or torus) on the cone rib: elliptical, a the radius of
        # the circle of the same area, a = (3 Q R_area / (4 E*))^(1/3) (Johnson 4.22 with
        # R_area of sim.physics.contact.hertz_point_radii)
        a = (3.0 * Qrib[j] * brg.rib_end[4] / (4.0 * E_star)) ** (1.0 / 3.0)
        prib = Qrib[j] / (np.pi * a * a)
        if par.boundary_only:       # no film at the rib either (above)
            film.prib[j] = prib
            film.Phirib[j] = 1.0
            return
        hrib = film_point(u, Qrib[j], R_t, R_m, par.eta0_inner, par.alpha, Ep)   # entrainment along e_t
        Phirib = solid_load_share(hrib, par.sigma_rib, par.B_ZH_rib, par.C_ZH_rib)
        npts = _width_points(prib, 0.0, par, quad, pts)
        # the surfaces slide along e_t through the ellipse's semi-axis along e_t, a_t = a sqrt(kappa)
        # (area pi a_t a_m = pi a^2, a_t / a_m = kappa): the heat source's half-length
        a_t = a * np.sqrt(brg.rib_end[5])
        theta = _viscosity_factor_at(HeatedContact(prib, 0.0, hrib, Phirib, 0.0, a_t, v1, v2, par.eta0_inner), par,
                                     quad, npts, pts)
        film.prib[j] = prib
        film.hrib[j] = hrib
        film.Phirib[j] = Phirib
        eta = par.eta0_inner * theta
        film.Etarib[j] = viscosity_at_pressure(eta, viscosity_log_ratio(eta, par.pv_model), pts[WP_TERM, 0],
                                               par.pv_model)


@kernel
def lateral_slip_rate(v1, Xr, dr, dz, nr, nz, ur, uz, vr, vz):
    """Lateral slip per skew angle of a slice contact, d(v.a)/dpsi [mm/s per rad] (module
    docstring, "Roller skew"), and the azimuth of the contact point per skew angle f = dphi/dpsi [1].

    v1: roller surface speed along e_t at the contact [mm/s]; Xr: radius of the contact point;
    (dr, dz): contact point from the roller centre; (nr, nz): normal into the ring; (ur, uz),
    (vr, vz): roller axes u', v' [mm, 1]. The skewed roller touches the ring where the two normals
    agree; to first order in psi the contact point turns by beta = b psi about the roller axis and
    lies at the azimuth phi = f psi = (x psi - y beta) / Xr, where both normals have the same e_t
    component: psi u'.n - beta v'.n = phi n_r (equivalently, the relative velocity has no normal
    component). The roller velocity there, -v1 (-e_t + psi u' - beta v'), seen in the ring frame
    at that azimuth (the ring's own velocity is along e_t there), has the component along the
    generatrix a = (-n_z, n_r): -v1 (psi u'.a - beta v'.a - phi a_r).
    """
    x = ur * dr + uz * dz
    y = vr * dr + vz * dz
    ar = -nz
    az = nr
    b = (nr * x / Xr - (ur * nr + uz * nz)) / (nr * y / Xr - (vr * nr + vz * nz))
    f = (x - y * b) / Xr
    return -v1 * ((ur * ar + uz * az) - b * (vr * ar + vz * az) - f * ar), f


@kernel
def pocket_skew_couple(psi, par):
    """Couple of the cage pocket about the skew axis on a roller skewed by psi [rad]: (couple
    [N mm], d couple / d psi [N mm/rad]). Zero inside the clearance |psi| <= par.skew_clearance,
    beyond it a stiff linear penalty -par.skew_stiffness (psi -+ clearance) (module docstring)."""
    c = par.skew_clearance
    k = par.skew_stiffness
    if psi > c:
        return -k * (psi - c), -k
    if psi < -c:
        return -k * (psi + c), -k
    return 0.0, 0.0


@kernel
def rate_slip(rates, inner, dr, dz, ar, az, ur, uz):
    """Slip of the roller against a ring at a contact point from the roller's and the inner ring's
    rates (module docstring, "Rates"): (along e_t, along a) [mm/s], to add to the spins' slip.

    rates: :data:`RollerRates` [rad/s, mm/s]; inner: the ring is the inner ring (its translation
    moves its surface; the outer ring is fixed); (dr, dz): contact point X - c from the roller
    centre [mm]; (ar, az): in-plane tangent a = n x e_t of the surface there; (ur, uz): roller
    axis u'. Rigid body v = v_c + Omega x (X - c), Omega = psi' v' + omega_w w'' besides the spin,
    w'' = -e_t (first order in psi): along e_t psi' v' x (X - c) = psi' x e_t, x = (X - c).u'; in
    the meridian plane v_c - omega_w e_t x (X - c) = v_c + omega_w (dr e_z - dz e_r); less the inner
    ring's translation V. The part along the normal n (squeeze) is not returned.
    """
    ring_r = rates.vi_r if inner else 0.0
    ring_t = rates.vi_t if inner else 0.0
    ring_z = rates.vi_z if inner else 0.0
    s_t = rates.psi_dot * (ur * dr + uz * dz) - ring_t
    s_a = (rates.vc_r - rates.omega_w * dz - ring_r) * ar + (rates.vc_z + rates.omega_w * dr - ring_z) * az
    return s_t, s_a


@kernel
def pocket_wall_force(g, half_play, k_pocket, transition):
    """Spring force of a cage pocket's walls on a roller at g [mm] from the pocket's centre along
    the orbit (at the pocket radius): 0 inside the play, |g| <= half_play [mm]; beyond it, at the
    depth pen = |g| - half_play, -k_pocket pen sign(g) [N] (k_pocket [N/mm]: both roller ends), its
    onset smoothed over ``transition`` [mm] to first order (k pen^2 / (2 transition) below it, k (pen -
    transition / 2) beyond; as MSC Adams' IMPACT function; 0: none). Returns (the force [N], the
    cubic step 3 s^2 - 2 s^3 of s = pen / transition that ramps a damper in (1 beyond, 0 inside)).
    The time domain (sim.solvers.dynamic) adds its damper; the free rollers' quasi-static solution
    (sim.solvers.kinematics, "Pocket play") takes the spring alone."""
    pen = abs(g) - half_play
    if pen <= 0.0:
        return 0.0, 0.0
    sg = 1.0 if g > 0.0 else -1.0
    if pen < transition:
        s = pen / transition
        return -sg * k_pocket * pen * pen / (2.0 * transition), s * s * (3.0 - 2.0 * s)
    return -sg * k_pocket * (pen - 0.5 * transition), 1.0



@internal_kernel
def pocket_wall_stiffness(g, half_play, k_pocket, transition):
    """Local stiffness of :func:`pocket_wall_force`'s spring, the magnitude of dF/dg [N/mm] at g [mm]
    (same arguments): 0 inside the play, k_pocket pen / transition over the onset, k_pocket beyond."""
    pen = abs(g) - half_play
    if pen <= 0.0:
        return 0.0
    return k_pocket * pen / transition if pen < transition else k_pocket

@kernel
def roller_friction(j, wR, psi, wc, wi, case, ev):
    """Friction of roller j at roller speed wR [rad/s], skew psi [rad] and cage speed wc [rad/s],
    inner-ring speed wi [rad/s], film and frames of ``case`` (:data:`FrictionCase`): fills ``ev`` (NEV,)
    and returns the pocket friction force along v' [N] (:func:`friction_loads` takes both).

    The raceway and rib tractions (:func:`roller_traction`), the drag (:func:`roller_drag`) and
    the pocket friction (:func:`pocket_friction`) under the quasi-static pocket force, the
    tangential force F_cage = F_D - F_t that holds the roller on its orbit at the cage speed.
    """
    roller_traction(j, wR, psi, NO_RATES, wc, wi, case, ev)
    FD = roller_drag(wc, case.frames.Cen[j, 0], case.par, ev)
    return pocket_friction(FD - ev[EV_FT], wR, case.par, case.bearing.rho_m, ev)


@internal_kernel
def friction_loads(ev, F_pocket, out):
    """Friction loads of a roller's contacts in its meridian plane (layout :data:`FRICTION_LOADS`),
    from its :func:`roller_friction` evaluation ``ev`` and the pocket friction force F_pocket [N]
    it returned, written to ``out`` (NFL,): on the roller, the quasi-static roller loads (along u',
    along v' [N], about u' x v' [N mm]): the pocket force along v' (module docstring) and, with
    skew, the lateral raceway and rib tractions; on the inner ring, the reaction of its raceway
    and rib tractions along e_r, e_t and e_z [N] (module docstring, "Rates"; over the load zone
    the e_t parts add up to a lateral force on the ring, sim.solvers.quasi_static.solve_bearing)."""
    out[FL_U] = ev[EV_FU]
    out[FL_V] = F_pocket + ev[EV_FV]
    out[FL_W] = ev[EV_MW]
    out[FL_RING_R] = ev[EV_RING_R]
    out[FL_RING_T] = ev[EV_RING_T]
    out[FL_RING_Z] = ev[EV_RING_Z]


@internal_kernel
def roller_drag(wc, rc, par, ev):
    """Oil drag on a roller orbiting at wc [rad/s] with its centre at radius rc [mm] (module
    docstring; reacted by the housing = outer ring): adds its z-moments and power to ``ev`` and
    returns the drag force F_D [N], acting on the roller along -e_t."""
    FD = par.drag_k * wc * wc
    ev[EV_TZ] -= FD * rc
    ev[EV_TOUT] += FD * rc
    ev[EV_DRAG] += FD * wc * rc
    return FD


@internal_kernel
def pocket_friction(F_cage, wR, par, rho_m, ev):
    """Cage pocket friction on a roller spinning at wR [rad/s] that the pocket pushes with the
    tangential force F_cage [N] (module docstring): the moment mu_c |F_cage| rho_m [N mm] against
    the spin (rho_m the roller radius in the pocket [mm]) into ``ev`` with its power; returns the
    pocket friction force along v', mu_c F_cage sign(omega_R) [N] (a meridian-plane load)."""
    Pc = par.mu_cage * abs(F_cage) * rho_m
    ev[EV_MU] -= Pc if wR > 0.0 else -Pc
    ev[EV_CAGE] += Pc * abs(wR)
    return par.mu_cage * F_cage * np.sign(wR)


@kernel
def roller_traction(j, wR, psi, rates, wc, wi, case, ev):
    """Raceway and rib tractions and rolling resistance of roller j, orbiting at wc [rad/s], at
    roller speed wR [rad/s], skew psi [rad] and the rates ``rates`` (:data:`RollerRates`: skew and
    tilt rate, centre velocity; all 0 in the quasi-static solution), inner-ring
    speed wi [rad/s] (film and frames of ``case``): fills ``ev`` (NEV,) without drag and cage
    pocket (:func:`roller_friction` adds them; the dynamic solver its own pocket force).

    ev: moment about the roller axis [N mm], z-moment of the contacts on the roller [N mm],
    z-moment on the outer ring [N mm], tangential contact force [N], then the powers [N mm/s]
    of COMPONENTS, then the friction moment about the skew axis (without the pocket couple,
    :func:`pocket_skew_couple`) [N mm], the lateral-traction loads (u', v' [N], u' x v' [N mm])
    and the lateral-slip power [N mm/s] (EV_MS ... EV_PSKEW), then the force of the inner-ring
    contacts' tractions on the inner ring (EV_RING_R ... EV_RING_Z) [N]. Per slice (module
    docstring) the width integral gives the tangential force F_t, the lateral force F_l (skew or
    in-plane rates, "Rates") and the spin moment M_n; -F_t s is split into sliding and drilling per
    contact, -F_l s_l is sliding.

    The slice loop is written out here rather than called per slice: a kernel taking the
    FrictionCase per slice is not inlined by LLVM, and passing the bundle by value for every
    slice made the kinematic solves 40 % slower (measured, numba 0.68.1).
    """
    X, Nrm, Cen, Ax, Xrib = case.frames
    film, par = case.film, case.par
    p0, b, h, Phi, Fh, Fy, Eta = film.p0, film.b, film.h, film.Phi, film.Fh, film.Fy, film.Eta
    q, Qrib, R_eq, w = case.bearing.q, case.bearing.Qrib, case.bearing.R_eq, case.bearing.w
    cos_t, sin_t, wq = case.quad
    for i in range(NEV):
        ev[i] = 0.0
    cr = Cen[j, 0]
    cz = Cen[j, 1]
    ur = Ax[j, 0]
    uz = Ax[j, 1]
    vr = Ax[j, 2]
    vz = Ax[j, 3]
    n = p0.shape[2]
    psi_dot = rates.psi_dot
    ring = case.bearing.ring[j]
    e_perp = ring[RP_PERP]
    for s in range(2):
        ring_t = rates.vi_t if s == 1 else 0.0      # inner ring's translation along e_t [mm/s]
        F_sum = 0.0     # sum of F_t over the contact [N]
        P_slip = 0.0    # -sum F_t s [N mm/s]
        G_sum = 0.0     # sum of the slices' traction conductances G_k = -F_t,k / s_k [N s/mm] (module docstring)
        for k in range(n):
            frr = Fh[j, s, k] + Fy[j, s, k]
            if p0[j, s, k] <= 0.0 and frr <= 0.0:
                continue    # neither load nor rolling loss: an unloaded strip outside the contact ends
            Xr = X[j, s, k, 0]
            Xz = X[j, s, k, 1]
            nr = Nrm[j, s, k, 0]
            nz = Nrm[j, s, k, 1]
            p0k = p0[j, s, k]
            bk = b[j, s, k]
            hk = h[j, s, k]
            phik = Phi[j, s, k]
            eta = Eta[j, s, k]                                   # (len(quad.wq),) [MPa s]
            v1 = _roller_surface_speed(wR, Xr, Xz, cr, cz, ur, uz)
            v2, om_n, om_a, r_own, nz_own, az_own = _ring_motion(s, wi, wc, ring, Xr, Xz, nr, nz)
            dr = Xr - cr
            dz = Xz - cz
            x = ur * dr + uz * dz                                # (X - c).u' [mm]
            ar = -nz                                             # a = n x e_t in (r, z)
            az = nr
            # rates (module docstring, "Rates"; rigid body v = v_c + Omega x (X - c)): the slip
            # along e_t gains psi' x, along a the in-plane relative velocity sl_rate [mm/s]
            # (rate_slip); the skew rate adds psi' v'.n to the spin about n and psi' v'.a to the
            # rolling about a, the tilt rate (about w'' = -e_t) neither. All 0 at a steady state
            # and in the quasi-static solution.
            st_rate, sl_rate = rate_slip(rates, s == 1, dr, dz, ar, az, ur, uz)
            if s == 1 and e_perp != 0.0:
                # the inner ring's axis offset by e_perp across the meridian plane: its spin moves its
                # surface along e_r at omega_i e_perp (module docstring, "Inner ring")
                sl_rate -= wi * e_perp * ar
            st = v1 - v2 + st_rate
            ws = wR * (ur * nr + uz * nz) + psi_dot * (vr * nr + vz * nz) - om_n     # spin about n
            wroll = wR * (ur * ar + uz * az) + psi_dot * (vr * ar + vz * az) - om_a  # relative rolling about a
            # entrainment speed: the mean speed of the two surfaces along e_t relative to the contact
            # point (Reynolds' equation in the frame of a moving contact, whose Couette term carries
            # the surface speeds relative to it, as for a cam and follower), which lies at the azimuth
            # f psi (lateral_slip_rate) and so moves along e_t at X_r f psi':
            # 1/2 ((v1 + psi' x - X_r f psi') + (v2 + ring_t - X_r f psi')) [mm/s]
            rate = 0.0
            f = 0.0
            if psi != 0.0 or psi_dot != 0.0 or ring_t != 0.0:
                rate, f = lateral_slip_rate(v1, Xr, dr, dz, nr, nz, ur, uz, vr, vz)
            ue = v1 + v2
            if psi_dot != 0.0 or ring_t != 0.0:
                ue += psi_dot * (x - 2.0 * Xr * f) + ring_t
            t_transit = 2.0 * bk / max(0.5 * abs(ue), MIN_ENTRAINMENT_SPEED)   # [s]
            Ft = 0.0
            Mn = 0.0
            Fl = 0.0
            if p0k <= 0.0:
                pass        # an unloaded strip: rolling loss only (below)
            elif psi == 0.0 and sl_rate == 0.0:
                # width integral, y = b sin(t), t in (0, pi/2), both halves (|v| is even in y)
                for i in range(wq.shape[0]):
                    ct = cos_t[i]
                    y = bk * sin_t[i]
                    p = p0k * ct
                    vy = y * ws
                    v = np.sqrt(st * st + vy * vy)
                    g = _traction(par, p, v, hk, phik, eta[i], t_transit)
                    dA = 2.0 * w * bk * ct * wq[i]
                    Ft -= g * st * dA
                    Mn -= g * y * vy * dA
                    G_sum += g * dA
            else:
                # skewed roller or in-plane rates: slip (s, s_l + y omega_s) along (e_t, a), |v| no
                # longer even in y: each half of the width on its own; traction -g(|v|) v along the
                # slip direction. s_l: the skew's (lateral_slip_rate, with the surface speed v1 of the
                # spin: psi' x in it would be second order, psi psi') plus the rates' in-plane slip
                sl = psi * rate
                if sl_rate != 0.0:
                    sl += sl_rate
                for i in range(wq.shape[0]):
                    ct = cos_t[i]
                    p = p0k * ct
                    dA = w * bk * ct * wq[i]
                    for half in range(2):
                        y = bk * sin_t[i] if half == 0 else -bk * sin_t[i]
                        vy = sl + y * ws
                        v = np.sqrt(st * st + vy * vy)
                        g = _traction(par, p, v, hk, phik, eta[i], t_transit)
                        Ft -= g * st * dA
                        Fl -= g * vy * dA
                        Mn -= g * y * vy * dA
                        G_sum += g * dA
                # lateral force F_l a: meridian-plane load on the roller; its moment about the
                # skewed axis u' + psi e_t at the turned contact point (first order in psi);
                # no z-moment (a lies in the meridian plane of the contact point). Its power on the
                # rates' slip: F_l a.v_c through EV_FU, EV_FV at the centre, F_l omega_w (dr a_z -
                # dz a_r) through EV_MW about w'' (the moment (X - c) x F_l a along -e_t)
                ua = ur * ar + uz * az
                va = vr * ar + vz * az
                ev[EV_FU] += Fl * ua
                ev[EV_FV] += Fl * va
                ev[EV_MW] += Fl * (dr * az - dz * ar)
                if s == 1:              # reaction on the inner ring
                    ev[EV_RING_R] -= Fl * ar
                    ev[EV_RING_Z] -= Fl * az
                ev[EV_MU] += Fl * psi * ((dz * ar - dr * az) + f * Xr * (az * ur - ar * uz) + f * ar * (dr * uz - dz * ur))
                ev[EV_PSKEW] -= Fl * sl
                ev[EV_SLIDING] -= Fl * sl
                # the normal load -Q n acts at the azimuth phi = f psi along the turned normal:
                # its moment about the skew axis v' (geometric, first order in psi)
                Qk = w * q[j, s, k]
                ev[EV_MS] -= Qk * psi * f * (Xr * (nz * vr - nr * vz) + nr * (dr * vz - dz * vr))
                ev[EV_FT] -= Qk * psi * f * nr
                # the lateral force turned with the contact point likewise has the e_t component
                # f psi a_r F_l (as the rib's F_b)
                ev[EV_FT] += Fl * psi * f * ar
                if s == 1:              # both react on the inner ring
                    ev[EV_RING_T] += Qk * psi * f * nr - Fl * psi * f * ar
            Mrr = frr * R_eq[s, k]
            # direction of the rolling couple: against the relative rolling, regularised like the
            # boundary friction (tanh of the rolling surface speed wroll rho over v_s, rho the
            # contact's distance from the roller axis; module docstring); 1 to round-off wherever
            # the roller rolls faster than ~20 v_s
            sg = np.tanh(wroll * abs(ur * dz - uz * dr) / par.solid.v_s)
            ev[EV_MU] += Ft * (uz * dr - ur * dz) + Mn * (ur * nr + uz * nz) - sg * Mrr * (ur * ar + uz * az)
            # moment about the skew axis v': F_t at x = (X - c).u', spin and rolling couples along v'
            ev[EV_MS] += Ft * (ur * dr + uz * dz) + Mn * (vr * nr + vz * nz) - sg * Mrr * (vr * ar + vz * az)
            tz = Ft * Xr + Mn * nz - sg * Mrr * az               # z-moment on the roller
            ev[EV_TZ] += tz
            if s == 0:
                ev[EV_TOUT] -= tz                                # reaction on the outer ring
            else:
                ev[EV_RING_T] -= Ft                              # reaction on the inner ring
                # the moment about the inner ring's own axis: F_t at r', the couples' components along
                # that axis, and the lateral force's radial component at the axis's offset e_perp
                ev[EV_TRING] += Ft * r_own + Mn * nz_own - sg * Mrr * az_own + e_perp * Fl * ar
            ev[EV_FT] += Ft
            ev[EV_DRILLING] -= Mn * ws                           # spin power
            prr = Mrr * sg * wroll                               # rolling-resistance power [N mm/s], >= 0
            F_sum += Ft
            P_slip -= Ft * st
            if frr > 0.0:
                ev[EV_ROLLING] += prr * Fh[j, s, k] / frr
                ev[EV_HYSTERESIS] += prr * Fy[j, s, k] / frr
        if G_sum > 0.0:
            P_rigid = F_sum * F_sum / G_sum
            ev[EV_SLIDING] += P_rigid
            ev[EV_DRILLING] += P_slip - P_rigid
    if Qrib[j] > 0.0 and film.prib[j] > 0.0:
        # a rib without load when the film was taken (film.prib 0: the time-domain solver holds the
        # film over a window, and a roller can touch its rib within it) carries no traction until the
        # next film, as an unloaded strip of the slices above (it divided by zero before: TRB 31313,
        # 32 / 48 kN, 3821 rpm)
        prib = film.prib[j]
        nr = case.bearing.nrib[j, 0]
        nz = case.bearing.nrib[j, 1]
        R_n, x_n = case.bearing.rib_end[0], case.bearing.rib_end[1]
        r_centre = Xrib[j, 0] - R_n * nr    # radius of the point where the normal meets the roller axis [mm]
        v1 = _roller_surface_speed(wR, Xrib[j, 0], Xrib[j, 1], cr, cz, ur, uz)
        v2, _, _, r_own = _ring_motion(1, wi, wc, ring, Xrib[j, 0], Xrib[j, 1], nr, nz)[:4]
        dr = Xrib[j, 0] - cr
        dz = Xrib[j, 1] - cz
        x = ur * dr + uz * dz
        # rates as the slices (rate_slip; the rib is on the inner ring): along e_t, and in the
        # meridian plane along b = n_rib x e_t [mm/s] (the part along n_rib, squeeze, left out)
        br = -nz
        bz = nr
        st_rate, sb = rate_slip(rates, True, dr, dz, br, bz, ur, uz)
        if e_perp != 0.0:
            sb -= wi * e_perp * br          # the ring's surface along e_r at omega_i e_perp, as the slices
        st = v1 - v2 + st_rate
        skew_slip = psi != 0.0
        if skew_slip:
            # the lateral slip of the skew along b (docs/roller_end_torus.md): the slices'
            # lateral_slip_rate, a surface of revolution about the roller axis (sphere or torus)
            # touching one about the bearing axis (its azimuth factor is x_n / r_centre)
            sb += psi * lateral_slip_rate(v1, Xrib[j, 0], dr, dz, nr, nz, ur, uz, vr, vz)[0]
        # Hertz semi-axis along e_t [mm]: area Q / p = pi a_t a_m, a_t / a_m = kappa (1 for a circle)
        a_rib = np.sqrt(Qrib[j] * case.bearing.rib_end[5] / (np.pi * prib))
        # entrainment relative to the contact point, whose azimuth psi x_n / r_centre (below)
        # moves it along e_t at X_r x_n psi' / r_centre (as the slices)
        ue = v1 + v2
        if psi_dot != 0.0 or rates.vi_t != 0.0:
            ue += psi_dot * (x - 2.0 * Xrib[j, 0] * x_n / r_centre) + rates.vi_t
        t_transit = 2.0 * a_rib / max(0.5 * abs(ue), MIN_ENTRAINMENT_SPEED)
        # traction -g(|v|) v on the 2-D slip (st, sb) over the contact area Q / p [mm^2]
        v = abs(st) if sb == 0.0 else np.sqrt(st * st + sb * sb)
        g = _traction(par, prib, v, film.hrib[j], film.Phirib[j], film.Etarib[j], t_transit)
        F = -g * st * Qrib[j] / prib
        ev[EV_MU] += F * (uz * dr - ur * dz)
        ev[EV_MS] += F * (ur * dr + uz * dz)
        ev[EV_TZ] += F * Xrib[j, 0]
        ev[EV_TRING] += F * r_own
        ev[EV_FT] += F
        ev[EV_RIB] -= F * st
        ev[EV_RING_T] -= F
        if sb != 0.0:
            # in-plane force F_b b: on the roller along u', v' and about w'' (as the slices' F_l),
            # its reaction on the inner ring, its power -F_b s_b
            Fb = -g * sb * Qrib[j] / prib
            ev[EV_FU] += Fb * (ur * br + uz * bz)
            ev[EV_FV] += Fb * (vr * br + vz * bz)
            ev[EV_MW] += Fb * (dr * bz - dz * br)
            ev[EV_RING_R] -= Fb * br
            ev[EV_RING_Z] -= Fb * bz
            ev[EV_TRING] += e_perp * Fb * br
            ev[EV_RIB] -= Fb * sb
            if skew_slip:
                # its moment about the skewed axis u' + psi e_t at the turned contact point (first
                # order in psi, as the slices' F_l), and the e_t component f psi b_r of b turned to
                # the contact point's meridian plane (no z-moment: b lies in that plane), which the
                # roller's orbit takes with the normal load's (the lever f = x_n / r_centre: ~-7 at
                # the torus rib, ~-20 at the sphere's, ~0.2 at a slice)
                f = x_n / r_centre
                ev[EV_MU] += Fb * psi * ((dz * br - dr * bz) + f * Xrib[j, 0] * (bz * ur - br * uz)
                                         + f * br * (dr * uz - dz * ur))
                ev[EV_FT] += Fb * psi * f * br
                ev[EV_RING_T] -= Fb * psi * f * br
        if psi != 0.0:
            # the rib load -Q_rib n along the normal, which meets the skewed roller axis at x_n (the
            # end-sphere centre; for the torus docs/roller_end_torus.md): the contact point and that
            # normal lie in the meridian plane at azimuth phi = psi x_n / r_centre; its moment about v'
            # (as the slices' normal loads)
            phi = psi * x_n / r_centre
            ev[EV_MS] -= Qrib[j] * phi * (Xrib[j, 0] * (nz * vr - nr * vz) + nr * (dr * vz - dz * vr))
            ev[EV_FT] -= Qrib[j] * phi * nr
            ev[EV_RING_T] += Qrib[j] * phi * nr


@internal_kernel
def cage_pocket_loads(wR, psi, wc, wi, active, case, loads):
    """Friction loads of every active roller's contacts in its meridian plane [N, N mm]
    (:func:`friction_loads`): on the roller the cage pocket friction force mu_c F_cage sign(omega_R)
    along v' (module docstring), F_cage = F_D - F_t the tangential force the cage supplies, and
    with skew psi (Z,) [rad] the lateral raceway tractions; on the inner ring the reaction of its
    contacts' tractions; at roller
    speeds wR and cage speed wc [rad/s]. The friction load the quasi-static balance takes back
    (BearingModel.solve(op, roller_loads, ring_loads)). ``loads`` (Z, NFL) is written (layout
    :data:`FRICTION_LOADS`, :func:`friction_loads`), zero for the inactive rollers.
    """
    ev = np.empty(NEV)
    for j in range(wR.shape[0]):
        for a in range(loads.shape[1]):
            loads[j, a] = 0.0
        if active[j]:
            friction_loads(ev, roller_friction(j, wR[j], psi[j], wc, wi, case, ev), loads[j])
