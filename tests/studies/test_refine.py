"""The final local stage (studies.refine, issue 16 item 2) on closed-form problems whose
constrained optimum, active constraints and active bounds are known exactly."""
import numpy as np
import pytest

from studies.refine import distinct_starts, local_refine

SETTINGS = dict(max_evaluations=200, initial_step=0.1, final_step=1e-6, active_tolerance=1e-4)


def test_optimum_on_a_curved_constraint():
    """min -(u0 + u1) subject to u0^2 + u1^2 <= 1/2: the optimum is (1/2, 1/2) with f = -1 and the
    constraint active (Lagrange: the gradient of f is parallel to the circle's normal there).
    COBYLA stops at trust radius 1e-6: the point within 1e-4 (linear models of a curved
    boundary converge to it at the order of the radius), the constraint within 1e-4."""
    r = local_refine(lambda u: (-(u[0] + u[1]), np.array([(u[0] ** 2 + u[1] ** 2) / 0.5 - 1.0, -1.0])),
                     [0.1, 0.2], ["circle", "slack"], **SETTINGS)
    np.testing.assert_allclose(r.u, [0.5, 0.5], atol=1e-4)
    assert r.value == pytest.approx(-1.0, abs=1e-4)
    assert r.feasible and r.active_constraints == ["circle"] and r.active_bounds == []
    assert r.start_value == pytest.approx(-0.3) and r.evaluations <= SETTINGS["max_evaluations"]


def test_optimum_on_a_search_bound_is_reported_as_such():
    """min u0 + (u1 - 0.3)^2 with no binding constraint: the optimum (0, 0.3) lies on the lower
    bound of input 0, which the result names; input 1 is interior."""
    r = local_refine(lambda u: (u[0] + (u[1] - 0.3) ** 2, np.array([-1.0])), [0.7, 0.9], ["slack"], **SETTINGS)
    np.testing.assert_allclose(r.u, [0.0, 0.3], atol=1e-3)
    assert r.active_bounds == [(0, "low")] and r.active_constraints == []


def test_points_without_result_are_avoided_and_never_reported():
    """Above u0 = 0.8 the 'simulation' fails (NaN objective, margin +1). min -u0 - u1 subject to
    u0 + u1 <= 1.5 with the optimum on that line: every evaluated failed point is kept out of
    the result, which is feasible and on the constraint; each point is evaluated once."""
    calls = []

    def evaluate(u):
        calls.append(u.tobytes())
        if u[0] > 0.8:
            return np.nan, np.array([1.0, 0.0])
        return -(u[0] + u[1]), np.array([0.0, (u[0] + u[1]) / 1.5 - 1.0])

    r = local_refine(evaluate, [0.2, 0.2], ["simulation", "sum"], **SETTINGS)
    assert r.feasible and np.isfinite(r.value)
    assert r.value == pytest.approx(-1.5, abs=1e-4) and "sum" in r.active_constraints
    assert len(calls) == len(set(calls)) == r.evaluations


def test_budget_limits_the_evaluations():
    """max_evaluations caps the distinct points (the start included)."""
    r = local_refine(lambda u: (float(np.sum((u - 0.37) ** 2)), np.array([-1.0])), [0.9, 0.9, 0.9], ["slack"],
                     max_evaluations=12, initial_step=0.1, final_step=1e-9, active_tolerance=1e-4)
    assert r.evaluations <= 12


def _kinked(u):
    """min u0 + u1 + 0.3 |u0 - u1| subject to max(1 - u0 - 3 u1, 1 - 3 u0 - u1, 0.6 - u0 - u1) <= 0: a
    constraint with corners (like pmax, a maximum over slices) and a kinked objective; optimum
    (0.3, 0.3), f = 0.6, on the third piece."""
    return float(u[0] + u[1] + 0.3 * abs(u[0] - u[1])), np.array([max(1 - u[0] - 3 * u[1], 1 - 3 * u[0] - u[1],
                                                                       0.6 - u[0] - u[1])])


@pytest.mark.parametrize("start", [[0.9, 0.1], [0.8, 0.6], [0.2, 0.9], [0.95, 0.95]])
def test_restarts_start_from_the_best_point_and_stop_when_one_gains_nothing(start):
    """With restarts, each COBYLA run starts from the best point so far, so the result is never
    worse than one run's; the sequence stops after a run that does not improve on the best (or
    after ``restarts`` more runs), within the budget of distinct points."""
    one = local_refine(_kinked, start, ["g"], **SETTINGS)
    more = local_refine(_kinked, start, ["g"], **SETTINGS, restarts=3, restart_shrink=0.2)
    assert one.runs == 1 and 2 <= more.runs <= 4
    assert more.value <= one.value and more.feasible
    assert more.value == pytest.approx(0.6, abs=1e-4)
    assert more.evaluations <= SETTINGS["max_evaluations"]
    capped = local_refine(_kinked, start, ["g"], max_evaluations=20, initial_step=0.1, final_step=1e-6,
                          active_tolerance=1e-4, restarts=3, restart_shrink=0.2)
    assert capped.evaluations <= 20   # the restarts share the budget of the stage


def _two_basins(u):
    """min of two bowls, f = min(0.1 + |u - a|^2, |u - b|^2) with a = (0.2, 0.2), b = (0.8, 0.8),
    subject to u0 <= 0.9: local optima at a (f = 0.1) and at b (f = 0, the global one)."""
    a, b = np.array([0.2, 0.2]), np.array([0.8, 0.8])
    return float(min(0.1 + np.sum((u - a) ** 2), np.sum((u - b) ** 2))), np.array([u[0] / 0.9 - 1.0])


def test_several_starts_leave_the_basin_of_the_best_start():
    """A local method stays in the basin of its start: from (0.25, 0.25) (the best start, f = 0.105,
    in the basin of the local optimum a) COBYLA ends at a (f = 0.1). With a second, worse start
    (0.5, 0.55) (f = 0.1525, but in b's basin) its screening run finds b, and the result is the
    global optimum f = 0 (at b within 1e-4, the trust radius 1e-6 on a smooth bowl); the budget
    covers every start."""
    one = local_refine(_two_basins, [0.25, 0.25], ["g"], **SETTINGS, restarts=2, restart_shrink=0.2)
    assert one.value == pytest.approx(0.1, abs=1e-6)
    both = local_refine(_two_basins, [[0.25, 0.25], [0.5, 0.55]], ["g"], **SETTINGS, restarts=2,
                        restart_shrink=0.2, start_evaluations=50)
    np.testing.assert_allclose(both.u, [0.8, 0.8], atol=1e-4)
    assert both.value == pytest.approx(0.0, abs=1e-6) and both.runs >= 2
    assert both.start_value == pytest.approx(0.105) and both.evaluations <= SETTINGS["max_evaluations"]


def _recorded(u0, **more):
    """local_refine on the two basins from ``u0`` (one or several starts), with the points it
    evaluated in order: (LocalResult, list of their bytes)."""
    calls = []

    def evaluate(u):
        calls.append(u.tobytes())
        return _two_basins(u)
    kw = dict(initial_step=0.1, final_step=1e-9, active_tolerance=1e-4, restarts=2, restart_shrink=0.2)
    return local_refine(evaluate, u0, ["g"], **kw, **more), calls


def test_the_first_start_runs_as_alone_and_the_others_screen_within_the_budget():
    """With k starts the first (the verified best) runs exactly as it would alone on the budget
    less the others' share, k x start_evaluations (a screening run from each other start and a
    polish of a better point they find): the same points in the same order (so a study whose best
    start is in the right basin reaches it as fast as with one start). Each other start then
    evaluates at most start_evaluations new points, and all of it stays within max_evaluations; a
    tight budget leaves starts out."""
    starts = [[0.25, 0.25], [0.5, 0.55], [0.1, 0.9], [0.9, 0.1]]
    alone, first = _recorded(starts[0], max_evaluations=40)
    multi, calls = _recorded(starts, max_evaluations=80, start_evaluations=10)
    assert calls[:len(first)] == first
    # the first start stops at its share (it would use any budget: alone on 40 it takes all 40), and
    # the next point is the second start's: 40 of the 80 are left for 3 screens and the polish
    assert len(first) == 40 and calls[len(first)] == np.asarray(starts[1], dtype=float).tobytes()
    assert multi.evaluations <= 80 and multi.runs >= alone.runs + 3
    assert multi.value <= alone.value
    tight, calls = _recorded(starts, max_evaluations=12, start_evaluations=10)
    assert tight.evaluations <= 12
    assert tight.runs < len(starts)


def test_the_first_start_keeps_at_least_half_the_budget():
    """A budget below the starts' share (100 against 3 starts x 35, an independent check of session
    32) left the verified best's own run n_min = d + 2 points: no COBYLA step, the best reported
    unchanged. The other starts are now as many as their share fits in half the budget, so with
    100 the first start runs alone on all of it (as with one start: the same points in the same
    order), and with 220 (the shipped studies) all 3 starts run as before."""
    starts = [[0.25, 0.25], [0.5, 0.55], [0.1, 0.9]]
    alone, first = _recorded(starts[0], max_evaluations=100)
    small, calls = _recorded(starts, max_evaluations=100, start_evaluations=35)
    assert small.starts == 1 and calls == first and small.value == alone.value
    assert len(first) > 2 + 2                     # more than the start and one simplex
    ample = _recorded(starts, max_evaluations=220, start_evaluations=35)[0]
    assert ample.starts == 3


def test_distinct_starts_keeps_the_best_of_each_neighbourhood():
    """Rows closer than the distance (max norm) to a row chosen before are skipped, in order."""
    U = np.array([[0.5, 0.5], [0.52, 0.49], [0.7, 0.5], [0.51, 0.7], [0.9, 0.9]])
    chosen = distinct_starts(U, 3, 0.1)
    np.testing.assert_array_equal(np.array(chosen), U[[0, 2, 3]])


def test_the_backoff_aims_each_run_inside_and_the_restarts_return_to_the_boundary():
    """The circle problem above with a 'simulation' margin (0 for a result) and a back-off of 0.02
    on the circle's margin only. Each COBYLA run solves margin + 0.02 x (its first step /
    initial_step) <= 0, the points being judged by their true margins: one run alone ends inside
    the circle (measured margin -0.006; its best truly feasible point, past the tightened
    boundary); with 3 restarts (back-offs 0.004, 0.0008, 0.00016) the result is feasible and
    within 2e-4 of the optimum f = -1 (measured 7e-5: the last back-off's cost, ~ its half, plus
    COBYLA's 1e-4 on a curved boundary). Applied to the simulation margin the back-off would
    leave no point feasible."""
    def circle(u):
        return -(u[0] + u[1]), np.array([0.0, (u[0] ** 2 + u[1] ** 2) / 0.5 - 1.0])

    kw = dict(max_evaluations=200, initial_step=0.1, final_step=1e-6, active_tolerance=1e-4, restart_shrink=0.2,
              backoff=[0.0, 0.02])
    one = local_refine(circle, [0.1, 0.2], ["simulation", "circle"], restarts=0, **kw)
    assert one.feasible and one.margins[1] < -1e-3
    more = local_refine(circle, [0.1, 0.2], ["simulation", "circle"], restarts=3, **kw)
    assert more.feasible and more.runs == 4
    assert more.value == pytest.approx(-1.0, abs=2e-4) and more.value < one.value


def test_a_constraint_inside_the_backoff_band_of_the_run_that_found_the_point_is_active():
    """The circle problem with the back-off: one run alone ends pressed against its tightened circle,
    inside the true one (margin between -0.02 and 0): the circle is what stopped it, so it is
    reported active, the slack (margin -1) is not; a start that no run improves on carries no band.
    Before, a first run that ended on its evaluation limit at the pinion's margins
    of -2.3e-3 (back-off 2e-3, tolerance 1e-3) reported no active constraint (session 31 check)."""
    def circle(u):
        return -(u[0] + u[1]), np.array([0.0, (u[0] ** 2 + u[1] ** 2) / 0.5 - 1.0, -1.0])

    kw = dict(max_evaluations=200, initial_step=0.1, final_step=1e-6, active_tolerance=1e-4, restart_shrink=0.2)
    one = local_refine(circle, [0.1, 0.2], ["simulation", "circle", "slack"], restarts=0, backoff=[0.0, 0.02, 0.02],
                       **kw)
    assert -0.02 - 1e-4 <= one.margins[1] < -1e-3           # inside the circle, within the back-off band
    assert one.active_constraints == ["simulation", "circle"]
    # a start that no run improves on was found before any run: no back-off band. The unconstrained
    # minimum (0.3, 0.3) lies inside the circle at margin -0.64, and inside the constraint c = u0 - 0.31
    # at -0.01, within that one's back-off 0.02 but not what holds the point: nothing is active
    def bowl(u):
        return float(np.sum((u - 0.3) ** 2)), np.array([(u[0] ** 2 + u[1] ** 2) / 0.5 - 1.0, u[0] - 0.31])

    still = local_refine(bowl, [0.3, 0.3], ["circle", "c"], restarts=0, backoff=[0.02, 0.02], **kw)
    np.testing.assert_allclose(still.u, [0.3, 0.3])
    assert still.margins[1] == pytest.approx(-0.01) and still.active_constraints == []
