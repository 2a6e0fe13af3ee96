"""Robustness of the quasi-static solver (MODEL.md 4 and 8, level 2): large imposed tilts (thesis
Fig. 6.10), a contact that migrates to the roller edge (thesis Table A.6, geometry 1), the
roller-load interface for friction, and honest status flags of the roller kernel.

Every converged state is checked by physics recomputed outside the solver's bookkeeping: the
slice loads and kernel normals give the forces on the inner ring (and on the rollers from the
outer ring), which must balance the applied loads; each loaded roller must balance its
contact, body and external loads.
"""
import numpy as np
import pytest

from sim.physics.contact import roller_axes
from sim.api.bearing_model import BearingModel, case_results
from sim.physics.roller_contact import empty_roller_contact, roller_contact
from sim.solvers.quasi_static import LoadControl, QuasiStaticProblem, RollerWork, solve_roller
from tests.helpers import case, race_forces, roller_residuals

PINION_PCR200 = ["bearing=tsrb_pinion", "bearing.PCR=200", "bearing.aPk=6.05", "bearing.kappa=0.99"]


# ------------------------------------------------------------------ item 2: large imposed tilt
@pytest.mark.parametrize("Fr,tilt", [(0.0, 0.25), (2000.0, 0.25), (0.0, 0.5), (2000.0, 0.5)])
def test_prototype_large_tilt_converges_and_balances(model_for, Fr, tilt):
    """Thesis Fig. 6.10 (prototype, Fa = 4.5 kN, 2000 rpm, tilt 0.25-0.5 deg): the case converges
    and the inner ring balances Fa and Fr with the slice loads recomputed at the returned state
    (tilted inner raceway), every loaded roller balances its loads. Tolerance 1e-8 of the load:
    the solver's force tolerance 1e-9 with a 10x margin for the recomputation (as in
    tests/balance)."""
    model, _ = model_for("bearing=tsrb_prototype")
    op = case(4500.0, Fr, tilt=tilt)
    raw = model.solve(op)
    assert raw["converged"]
    Fx, Fz = race_forces(model, raw, 1, tilt)
    np.testing.assert_allclose([Fx + Fr, Fz + 4500.0], 0.0, atol=1e-8 * 4500.0)
    res = roller_residuals(model, raw, op, np.zeros((model.geometry.Z, 3)))
    assert len(res) > 0 and np.all(res < 1e-8)


def test_tilted_solution_does_not_depend_on_the_start(model_for):
    """The large-tilt solution is unique: starting the ring at 0.3x and 3x the Hertz estimate or
    0.05 mm off radially gives the same ring displacement and roller loads. Tolerances: ring
    1e-9 mm and loads 1e-7 of the largest: far below the differences a second equilibrium would
    show, far above the solver tolerance (1e-9 of the load, observed differences ~1e-10)."""
    model, _ = model_for("bearing=tsrb_prototype")
    op = case(4500.0, 0.0, tilt=0.25)
    ref = model.solve(op)
    assert ref["converged"]
    estimate = BearingModel.initial_ring(model, op)
    for start in (0.3 * estimate, 3.0 * estimate, estimate + np.array([0.0, -0.05, 0.0])):
        model.initial_ring = lambda _op, s=start: s.copy()
        raw = model.solve(op)
        assert raw["converged"]
        np.testing.assert_allclose(raw["ring"], ref["ring"], atol=1e-9)
        np.testing.assert_allclose(raw["Q"], ref["Q"], atol=1e-7 * ref["Q"].max())


# ------------------------------------------------- item 3: Table A.6 geometry 1, edge contact
def test_pinion_PCR200_contact_migrates_to_the_roller_edge(model_for):
    """Thesis Table A.6, geometry 1 (PCR 200, Fa = 35 kN, 1100 rpm): the rib-free balance point
    x* = PCR sin(gamma) = 14.5 mm lies beyond the roller end (12.1 mm, MODEL.md 4), so the roller
    has to shift until its large end carries the load: the thesis reports 2.0 mm axial
    displacement and L_eff = 4.68 mm. Checked: convergence; Fa carried by the inner-ring
    contacts (1e-8, solver tolerance with margin); load centroid beyond the large-end contact
    point x_large and the end slice the most loaded (edge contact); axial displacement within a
    factor 2 of the thesis (same order, the thesis's MBS slicing differs; 3.5 mm here), L_eff
    within a factor 3 (the edge contact spans 2-3 slices of 1.21 mm at 20 slices). Its edge
    contact runs at 4450 MPa (slice pmax, static safety 0.81): beyond ISO 76's 4000 MPa, so the
    static limit is raised (solver.max_static_load_ratio, 1 / 0.81 < 4) to read the outputs the
    thesis reports; at the default limit the case is reported as not converged."""
    model, cfg = model_for(*PINION_PCR200, "solver.max_static_load_ratio=4")
    op = case(35000.0, 0.0, speed=1100.0)
    raw = model.solve(op)
    assert raw["converged"]
    Fx, Fz = race_forces(model, raw)
    np.testing.assert_allclose([Fx, Fz + 35000.0], 0.0, atol=1e-8 * 35000.0)
    g = model.geometry
    q = raw["line_load"][0]
    centroid = np.sum(q * g.arrays["x"][None, :]) / np.sum(q)
    assert centroid > g.contact_points_x[1]
    assert np.argmax(q[0]) == 0 and np.argmax(q[1]) == 0  # slice 0 is at the large end
    res = case_results(model, op, raw, cfg.output)
    assert 2.0 / 2 < res["axial_displacement"] < 2.0 * 2
    assert 4.68 / 3 < res["L_eff"] < 4.68 * 3


# ---------------------------------------------------------- item 4: external roller loads
def _system_balance(model, raw, op, ext):
    """Force balance of inner ring + rollers along x and z [N]: applied Fa, Fr, the external
    roller loads and centrifugal forces (world components, loaded rollers only: the cage holds
    the others) and the outer raceway's slice loads on the rollers (-q w n, n into the ring)."""
    g = model.geometry
    body = model.body_loads(op)
    Fx_out, Fz_out = race_forces(model, raw, 0, op.tilt_deg)
    Fx, Fz = op.Fr - Fx_out, op.Fa - Fz_out
    for j in range(g.Z):
        if raw["Q"][j].sum() == 0.0:
            continue
        psi = 2 * np.pi * j / g.Z
        ur, uz, vr, vz = roller_axes(g.alpha, raw["poses"][j, 2])
        Fr_j = ext[j, 0] * ur + ext[j, 1] * vr + body.centrifugal
        Fx += Fr_j * np.cos(psi)
        Fz += ext[j, 0] * uz + ext[j, 1] * vz
    return Fx, Fz


@pytest.mark.parametrize("bearing", ["tsrb_reference", "trb_32208"])
def test_axial_roller_load_shifts_the_roller_and_the_bearing_balances(model_for, bearing):
    """A load on every roller along its axis towards the large end (20 N, 1.5 % of the roller
    load, the order of the axial friction forces) moves each TSRB roller towards its large end
    (xi grows; the TRB rib takes it: Q_rib grows), the opposite load the other way; the inner
    ring still balances Fa and Fr, every roller its contact, body and external loads, and the
    whole bearing (inner ring + rollers) balances Fa, Fr and the roller loads against the outer
    raceway's contact forces. Tolerance 1e-8 of the load: solver force tolerance 1e-9, 10x
    margin for the recomputation."""
    model, _ = model_for(f"bearing={bearing}")
    Z = model.geometry.Z
    op = case(4500.0, 2000.0)
    raws = {}
    for F in (-20.0, 0.0, 20.0):
        ext = np.tile([F, 0.0, 0.0], (Z, 1))
        raw = model.solve(op, roller_loads=ext)
        assert raw["converged"]
        np.testing.assert_allclose(raw["residual"], 0.0, atol=1e-8 * 4500.0)
        if bearing != "trb_32208":  # the TRB rib carries part of Fa and Fr besides the raceway
            Fx, Fz = race_forces(model, raw, 1, 0.0)
            np.testing.assert_allclose([Fx + 2000.0, Fz + 4500.0], 0.0, atol=1e-8 * 4500.0)
        assert np.all(roller_residuals(model, raw, op, ext) < 1e-8)
        np.testing.assert_allclose(_system_balance(model, raw, op, ext), 0.0, atol=1e-8 * 4500.0)
        raws[F] = raw
    loaded = raws[0.0]["Q"].sum(axis=1) > 0
    if bearing == "trb_32208":
        assert np.all(np.diff([raws[F]["Q_rib"][loaded] for F in (-20.0, 0.0, 20.0)], axis=0) > 0)
    else:
        xi = np.array([raws[F]["poses"][loaded, 0] for F in (-20.0, 0.0, 20.0)])
        assert np.all(np.diff(xi, axis=0) > 0)


def test_roller_load_sign_conventions(model_for):
    """Sign conventions of the roller loads (BearingModel.solve docstring): a force along v'
    (outwards) moves load from the inner to the outer raceway by about that force (Q_o - Q_i
    grows by 0.8-1.2 x 50 N: the contact normals are inclined by the taper and crown angles to
    v'); a positive moment about u' x v' increases the roller tilt theta."""
    model, _ = model_for("bearing=tsrb_reference")
    Z = model.geometry.Z
    op = case(4500.0, 0.0)
    ref = model.solve(op)
    up = model.solve(op, roller_loads=np.tile([0.0, 50.0, 0.0], (Z, 1)))
    turn = model.solve(op, roller_loads=np.tile([0.0, 0.0, 500.0], (Z, 1)))
    assert ref["converged"] and up["converged"] and turn["converged"]
    gain = (up["Q"][:, 0] - up["Q"][:, 1]) - (ref["Q"][:, 0] - ref["Q"][:, 1])
    assert np.all((gain > 0.8 * 50.0) & (gain < 1.2 * 50.0))
    assert np.all(turn["poses"][:, 2] > ref["poses"][:, 2])


def test_unequal_roller_loads_solve_every_roller(model_for):
    """Loads on rollers psi and -psi that differ break the mirror symmetry: all Z rollers are
    solved, the loaded one moves and the whole bearing still balances (tolerance as above)."""
    model, _ = model_for("bearing=tsrb_reference")
    Z = model.geometry.Z
    op = case(4500.0, 2000.0)
    ext = np.zeros((Z, 3))
    ext[3, 0] = 20.0
    ref = model.solve(op)
    raw = model.solve(op, roller_loads=ext)
    assert raw["converged"] and raw["solver_info"]["roller_classes"] == Z
    assert raw["poses"][3, 0] > ref["poses"][3, 0]
    assert np.all(roller_residuals(model, raw, op, ext) < 1e-8)
    np.testing.assert_allclose(_system_balance(model, raw, op, ext), 0.0, atol=1e-8 * 4500.0)


def test_rib_contact_is_returned(model_for):
    """The TRB rib contact of every roller: a unit normal into the rib pointing along the roller
    axis towards its large end (the rib stops the roller there; n . u' > 0.99 for the ASSUMED
    rib geometry, inclined by about 2 deg), and the TSRB has none."""
    model, _ = model_for("bearing=trb_32208")
    raw = model.solve(case(4500.0, 2000.0))
    g = model.geometry
    n = raw["rib_contact"][:, 2:]
    np.testing.assert_allclose(np.hypot(n[:, 0], n[:, 1]), 1.0, rtol=1e-12)
    for j in range(g.Z):
        ur, uz, _, _ = roller_axes(g.alpha, raw["poses"][j, 2])
        assert n[j, 0] * ur + n[j, 1] * uz > 0.99
    tsrb, _ = model_for("bearing=tsrb_reference")
    assert np.all(tsrb.solve(case(4500.0, 2000.0))["rib_contact"] == 0.0)


# ------------------------------------------------------------- honest roller status flags
def test_roller_kernel_reports_its_status_honestly(model_for):
    """solve_roller from the rigid start pose of a TSRB roller: with one Newton iteration allowed
    it reports status 0 (not converged), with its contact state (f, Q) the one of the returned
    pose (recomputed); with the configured iterations it reports 1 and the residual meets the
    tolerance (1e-10 of the roller's loads)."""
    model, _ = model_for("bearing=tsrb_reference")
    g = model.geometry
    n = g.n_slices
    ring = np.array([0.04, 0.0])  # near the solved ring of Fa = 4.5 kN
    body = model.body_loads(case(4500.0))
    for max_it, expected in ((1, 0), (model.newton.roller_max_iterations, 1)):
        problem = QuasiStaticProblem(model.bearing, model.elasticity,
                                     model.newton._replace(roller_max_iterations=max_it), body, False)
        work = RollerWork(empty_roller_contact(n), np.zeros(2), np.zeros(4), np.zeros(4), np.zeros(4), np.zeros(4),
                          np.zeros((4, 4)), np.zeros((4, 4)), np.zeros(4))
        state = empty_roller_contact(n)
        state.pose[:] = [0.0, 0.5 * 0.04 * np.sin(g.alpha), 0.0]
        st, its, nev = solve_roller(ring, 0.0, 1.0, np.zeros(3), problem, 1e-10, LoadControl(0.0, 0.04, 0.0), state, work)
        assert st == expected and np.all(np.isfinite(state.pose))
        check = empty_roller_contact(n)
        check.pose[:] = state.pose
        check.q[:] = state.q
        check.active[:] = state.active
        roller_contact(ring, 0.0, 1.0, model.bearing, model.elasticity, check)
        np.testing.assert_allclose(check.f, state.f, rtol=1e-9, atol=1e-9 * state.Q[:2].sum())
        if st == 1:
            Q, R = state.Q, work.residual
            assert R[3] <= 1e-10 * (Q[0] + Q[1] + abs(body.centrifugal))
