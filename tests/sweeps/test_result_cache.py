"""The result cache of sim.api.sweep: a re-run computes nothing, an interrupted run resumes, a damaged
or unconverged entry is recomputed, and the key follows what is computed, not where it is written.
Cache files are JSON (issue 13 item 6): bit-exact arrays, nothing ever unpickled, normal file modes.
"""
import json
import logging
import os
import pickle

import numpy as np
import pytest
import xarray as xr
from omegaconf import OmegaConf

import sim
from sim._math import jit
import sim.api.sweep
from sim.api.cases import operating_points
from sim.api.sweep import CACHE_SUFFIX, _key_base, cache_file, case_key, decode_case, encode_case, run_cases
from tests.sweeps.common import FAST

GRID = ["load.Fa=[3000,5000]", "load.Fr=[0,2000]"]  # 4 cases in one run


@pytest.fixture
def calls(monkeypatch):
    """Counts sim.simulate calls made by sim.api.sweep; ``calls.fail_at = n`` interrupts the n-th call."""

    class Counter:
        n = 0
        fail_at = None

    def counting(cfg, grid=None):
        Counter.n += 1
        if Counter.n == Counter.fail_at:
            raise KeyboardInterrupt  # what a killed process leaves: no result for this case
        return real(cfg, grid=grid)

    real = sim.api.sweep.simulate
    monkeypatch.setattr(sim.api.sweep, "simulate", counting)
    return Counter


def config(cache, *extra):
    return sim.load_config([*FAST, *GRID, f"output.cache_dir={cache}", *extra])


def without_run_times(ds):
    return ds.drop_vars("wall_time").drop_attrs()


def test_second_run_computes_nothing(tmp_path, calls):
    """The same config again: every case from the cache, no simulate call, the identical Dataset."""
    first, n1 = run_cases(config(tmp_path), progress=False)
    assert calls.n == 4 and n1["computed"] == 4
    second, n2 = run_cases(config(tmp_path), progress=False)
    assert calls.n == 4 and n2 == {"cases": 4, "cached": 4, "computed": 0, "not_converged": 0}
    xr.testing.assert_identical(first.drop_attrs(), second.drop_attrs())


def test_interrupted_run_resumes_to_the_same_result(tmp_path, calls):
    """Interrupted in its third case, a run keeps the two finished ones; the re-run computes only
    the other two and gives what an uninterrupted run (own cache) gives."""
    calls.fail_at = 3
    with pytest.raises(KeyboardInterrupt):
        run_cases(config(tmp_path / "a"), progress=False)
    assert len(list((tmp_path / "a").rglob(f"*{CACHE_SUFFIX}"))) == 2
    calls.n, calls.fail_at = 0, None
    resumed, n = run_cases(config(tmp_path / "a"), progress=False)
    assert calls.n == 2 and n["cached"] == 2
    whole, _ = run_cases(config(tmp_path / "b"), progress=False)
    xr.testing.assert_identical(without_run_times(resumed), without_run_times(whole))


def test_damaged_entry_is_recomputed(tmp_path, calls, caplog):
    """A cache entry that cannot be read is reported, deleted and recomputed, never trusted."""
    first, _ = run_cases(config(tmp_path), progress=False)
    entry = sorted(tmp_path.rglob(f"*{CACHE_SUFFIX}"))[0]
    entry.write_bytes(entry.read_bytes()[:100])
    with caplog.at_level(logging.WARNING, logger="sim.api.sweep"):
        again, n = run_cases(config(tmp_path), progress=False)
    assert n["computed"] == 1 and calls.n == 5
    assert "unreadable" in caplog.text
    xr.testing.assert_identical(without_run_times(first), without_run_times(again))


def test_unconverged_cases_are_recomputed(tmp_path, calls):
    """With one ring iteration the combined-load cases cannot converge: they are written with
    converged False but not cached, so a re-run computes exactly them again (issue 4: failed
    points are recomputed); the converged pure axial cases come from the cache."""
    ds, n = run_cases(config(tmp_path, "solver.max_iterations=1"), progress=False)
    unconverged = int((~ds.converged).sum())
    assert unconverged == n["not_converged"] >= 2
    assert len(list(tmp_path.rglob(f"*{CACHE_SUFFIX}"))) == 4 - unconverged
    run_cases(config(tmp_path, "solver.max_iterations=1"), progress=False)
    assert calls.n == 4 + unconverged


def test_key_follows_what_is_computed():
    """Where results go does not change the key, nor 17 vs 17.0; a parameter or a case does."""
    base = sim.load_config([*FAST, *GRID])
    op = operating_points(base.load)

    def key(case=0, **changes):
        cfg = base.copy()
        for path, value in changes.items():
            OmegaConf.update(cfg, path.replace("__", "."), value)
        return case_key(_key_base(cfg), op[case])

    assert key() == key(output__file="other.nc", output__cache_dir="/elsewhere") == key(bearing__Z=17.0)
    assert key() != key(bearing__PCR=101.0) and key() != key(case=1) and key() != key(solver__n_slices=9)
    base.output.cache_dir = None
    assert cache_file(base, op[0]) is None  # no cache: always computed


def test_grid_run_equals_simulate(tmp_path):
    """Case by case through the cache or all at once with sim.simulate: the same Dataset."""
    cfg = config(tmp_path)
    cached, _ = run_cases(cfg, progress=False)
    direct = sim.simulate(cfg)
    xr.testing.assert_identical(without_run_times(cached), without_run_times(direct))


def test_code_fingerprint_covers_every_layer_of_sim():
    """A change to any kernel (physics, solvers, numerics) must invalidate the cache."""
    names = {str(path.relative_to(jit.SIM_ROOT)) for path in jit.sim_sources()}
    for required in ("physics/friction.py", "solvers/quasi_static.py", "_math/jit.py", "geometry.py", "api/simulation.py"):
        assert required in names


def assert_bit_identical(a, b):
    """Same data variables and coordinates, each in order, with the same dims, dtype, shape, attrs and bytes."""
    assert list(a.data_vars) == list(b.data_vars) and list(a.coords) == list(b.coords)
    assert a.attrs == b.attrs
    for name, v in a.variables.items():
        w = b.variables[name]
        assert (v.dims, v.dtype, v.shape, v.attrs) == (w.dims, w.dtype, w.shape, w.attrs), name
        assert v.values.tobytes() == w.values.tobytes(), name


def test_cached_result_round_trips_bit_identically(tmp_path):
    """A full case (friction on: every output, bools, int32 iterations, text coordinates) read back
    from its cache file equals the computed Dataset bit for bit; NaN (two payloads), infinities,
    0-d, empty and non-native-endian arrays and numpy attributes survive the format too."""
    cfg = sim.load_config(["solver.n_slices=8", "load.Fa=3000", "load.Fr=2000", f"output.cache_dir={tmp_path}"])
    op = operating_points(cfg.load)[0]
    computed, hit = sim.api.sweep.compute_case(cfg.copy(), op, cache_file(cfg, op))
    assert not hit and "torque_component" in computed
    read, hit = sim.api.sweep.compute_case(cfg.copy(), op, cache_file(cfg, op))
    assert hit
    assert_bit_identical(computed, read)
    xr.testing.assert_identical(computed, read)

    odd = computed.copy(deep=True)
    nan2 = np.frombuffer(np.uint64(0x7FF8_0000_DEAD_BEEF).tobytes(), dtype=np.float64)[0]
    odd["pmax"].values[0, 0] = [np.nan, nan2]
    odd["L_eff"].values[0, 0] = np.inf
    odd["scalar"] = xr.Variable((), np.int16(-7))
    odd["empty"] = xr.Variable(("nothing",), np.zeros(0, dtype=np.float32))
    odd["big_endian"] = xr.Variable(("slice",), np.arange(8, dtype=">i8"))
    odd["when"] = xr.Variable(("design",), np.array(["2024-01-02T03:04:05"], dtype="datetime64[ns]"))
    odd.attrs.update(number=np.float32(1.5), flags=np.array([1, 2], dtype=np.uint8), nan=float("nan"))
    back = decode_case(encode_case(odd))
    assert_bit_identical(odd.drop_attrs(deep=False), back.drop_attrs(deep=False))
    assert back.attrs["number"].dtype == np.float32 and back.attrs["flags"].tolist() == [1, 2]
    assert np.isnan(back.attrs["nan"]) and back["pmax"].values.tobytes() == odd["pmax"].values.tobytes()


def test_object_arrays_are_not_cached():
    ds = xr.Dataset({"x": ("a", np.array([{"code": 1}], dtype=object))})
    with pytest.raises(TypeError, match="dtype object"):
        encode_case(ds)


class Payload:
    """What a crafted pickle does when loaded: here it only makes a folder, the proof it ran."""

    def __init__(self, marker):
        self.marker = str(marker)

    def __reduce__(self):
        return os.mkdir, (self.marker,)


def foreign_entries(marker, other_entry):
    """Files an attacker or a crash could leave at a cache path, none of which may be used."""
    dtype_object = json.loads(other_entry)
    next(iter(dtype_object["data_vars"].values()))["dtype"] = "|O"
    return {"pickle": pickle.dumps(Payload(marker)), "garbage": os.urandom(3000), "empty": b"",
            "json of another format": b'{"format": "pickle", "version": 1}',
            "object dtype": json.dumps(dtype_object).encode(), "another case": other_entry}


@pytest.mark.parametrize("kind", ["pickle", "garbage", "empty", "json of another format", "object dtype",
                                  "another case"])
def test_foreign_file_at_a_cache_path_is_never_used(tmp_path, calls, caplog, kind):
    """A crafted pickle (at the cache path and at the old ``.pkl`` name), random bytes, or JSON that
    is not one converged case of that key: never executed nor trusted; the case is recomputed,
    gives the result of a clean run and replaces the file with a valid entry."""
    clean, _ = run_cases(config(tmp_path / "clean"), progress=False)
    cfg = config(tmp_path / "cache")
    ops = operating_points(cfg.load)
    path, other = cache_file(cfg, ops[0]), cache_file(config(tmp_path / "clean"), ops[1])
    marker = tmp_path / "payload_ran"
    path.parent.mkdir(parents=True)
    path.write_bytes(foreign_entries(marker, other.read_bytes())[kind])
    path.with_suffix(".pkl").write_bytes(pickle.dumps(Payload(marker)))
    calls.n = 0
    with caplog.at_level(logging.WARNING, logger="sim.api.sweep"):
        ds, n = run_cases(cfg, progress=False)
    assert not marker.exists()
    assert n["computed"] == 4 and calls.n == 4
    assert "unreadable" in caplog.text and str(path) in caplog.text
    xr.testing.assert_identical(without_run_times(ds), without_run_times(clean))
    assert decode_case(path.read_bytes()).Fa.item() == ops[0].Fa
    assert path.with_suffix(".pkl").exists()  # an old-format file is ignored, not read


def test_no_pickle_is_read_anywhere_in_the_sweep_module(monkeypatch, tmp_path):
    """Belt and braces: with pickle.loads/load unusable, caching and reading back still work."""
    def refuse(*args, **kwargs):
        raise AssertionError("pickle used")

    monkeypatch.setattr(pickle, "loads", refuse)
    monkeypatch.setattr(pickle, "load", refuse)
    run_cases(config(tmp_path), progress=False)
    _, n = run_cases(config(tmp_path), progress=False)
    assert n["cached"] == 4


@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o027, 0o640), (0o002, 0o664)])
def test_cache_files_are_ordinary_files(tmp_path, umask, mode):
    """Entries get 0o666 minus the umask (not mkstemp's 0o600); no temporary file is left behind."""
    old = os.umask(umask)
    try:
        run_cases(config(tmp_path), progress=False)
    finally:
        os.umask(old)
    entries = list(tmp_path.rglob("*"))
    files = [p for p in entries if p.is_file()]
    assert len(files) == 4 and all(p.suffix == CACHE_SUFFIX for p in files)
    assert {p.stat().st_mode & 0o777 for p in files} == {mode}


def test_interrupted_write_leaves_the_old_entry_or_none(tmp_path, monkeypatch):
    """A crash between writing the temporary file and the rename: the entry is absent (recomputed
    next time), no partial file is at the cache path and the temporary file is removed."""
    cfg = config(tmp_path)
    op = operating_points(cfg.load)[0]

    def crash(src, dst):
        raise KeyboardInterrupt

    monkeypatch.setattr(sim.api.sweep.os, "replace", crash)
    with pytest.raises(KeyboardInterrupt):
        sim.api.sweep.compute_case(cfg.copy(), op, cache_file(cfg, op))
    assert [p for p in tmp_path.rglob("*") if p.is_file()] == []


def test_a_dynamic_kind_warms_up_with_a_short_uncached_run(tmp_path, monkeypatch):
    """warm_up of a time-domain job: its case with DYNAMIC_WARM_UP (two windows of one roller pass), not
    the job's own settings, and nothing cached: a job whose case reaches no steady state is not cached, so
    a warm-up with its own settings was computed twice (24 s of warm-up, then 26 s in its job, for a
    case capped at 2 windows; an independent check of session 31). The short run warms its kind once
    it integrated, converged or not."""
    seen = []

    def fake(cfg, op, path, grid=False):
        seen.append((OmegaConf.to_container(cfg.solver, resolve=True), path))
        return xr.Dataset({"converged": (("design", "case"), [[False]])}, coords={"time": [0.0, 1e-3]})

    monkeypatch.setattr(sim.api.sweep, "_simulate_case", fake)
    cfg = sim.load_config(["solver=dynamic", f"output.cache_dir={tmp_path}", "load.Fa=3000", "load.Fr=1000"])
    sim.api.sweep.warm_up([cfg, cfg])
    assert len(seen) == 1                                     # one run warms the kind
    solver, path = seen[0]
    assert path is None and not list(tmp_path.rglob(f"*{CACHE_SUFFIX}"))
    assert {k: solver["dynamic"][k] for k in sim.api.sweep.DYNAMIC_WARM_UP} == sim.api.sweep.DYNAMIC_WARM_UP
    assert cfg.solver.dynamic.max_windows != 2                # the job's own config is untouched
