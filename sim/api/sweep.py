"""Sweeps: cached cases, multirun jobs, the Hydra callback and the collector of ``sweep.nc``.

Result cache (nothing lost, nothing redone)
    Every load case of every run is keyed by a SHA-256 of its resolved config without the
    ``load`` node and without where-to-write keys (``output.file``, ``output.cache_dir``), plus
    the case (Fa, Fr, speed, tilt, oil_temperature) and a fingerprint of the code (the sources
    of ``sim/``, numpy, numba and xarray versions). A converged case is written atomically to
    ``<output.cache_dir>/<key[:2]>/<key>.json`` (:func:`encode_case`: JSON with every array as
    dtype, shape and raw bytes in base64, bit exact and never unpickled; a few ms to read against
    60 ms for a NetCDF file); a run first looks there and only computes what is missing, and an
    entry that does not parse as one converged case of that key is deleted and recomputed.
    Failed and unconverged cases are never cached, so a re-run recomputes them.
    The cache does not depend on the sweep folder: the same command in a new folder (Hydra's
    ``${now:...}``), an overlapping sweep or a single run reuses every finished case, and a
    killed sweep loses at most the cases that were being computed. Runs sharing the cache at
    the same time claim each case they compute (``<key>.claim``, :func:`compute_case`), so no
    case is computed twice; temporaries and claims of interrupted runs are removed by the next
    run (:func:`remove_stale_files`). A cache that cannot be written is reported once; the run
    goes on.

Multirun (``python -m sim.run --multirun ...``, :class:`SweepCallback`)
    Before the first job the callback composes every job's config, refuses the whole sweep if
    any value is outside its schema (:func:`sim.api.schema.validate`), writes the job list
    ``sweep.json`` and computes, in the launching process, the first uncached case of each
    kind of job, which compiles (or loads) every numba kernel once into the on-disk cache,
    before parallel workers start: no two processes compile the same kernel at once. Each job
    writes ``<sweep dir>/<job>/result.nc`` atomically, or ``failed.json`` with the error (an
    impossible geometry fails that point, not the sweep) and logs one line. After the last job
    :func:`collect` merges the jobs into ``<sweep dir>/sweep.nc``; a job whose files are
    unreadable or incomplete is recorded as damaged, never sinking the sweep.

Command line: ``python -m sim.api.sweep collect DIR`` re-collects any sweep folder (exit 1 with
a one-line summary when a job is missing or damaged, 2 when DIR is not a sweep folder).
"""
import argparse
import base64
import copy
import hashlib
import itertools
import json
import logging
import os
import secrets
import shutil
import socket
import sys
import threading
import time
from functools import lru_cache
from importlib import import_module
from pathlib import Path

import numpy as np
import xarray as xr
from hydra.experimental.callback import Callback
from omegaconf import OmegaConf
from tqdm import tqdm

from sim import io
from sim._math.jit import source_fingerprint
from sim.api.cases import operating_points
from sim.api.cli import PROJECT_ERRORS, one_line, refuse
from sim.api.schema import ConfigError, validate
from sim.api.simulation import build_friction, build_model, simulate
from sim.errors import InputError

log = logging.getLogger(__name__)

MANIFEST = "sweep.json"       # job list written before the first job
FAILED = "failed.json"        # a job's error, written instead of its result
SWEEP_FILE = "sweep.nc"       # the merged dataset
NOT_IN_KEY = ("file", "cache_dir")  # output keys that say where to write, not what to compute
BASIC_SWEEPER = "basic"       # the hydra/sweeper choice whose job list sweep_jobs forms


# ------------------------------------------------------------------ cache keys and cached cases
@lru_cache(maxsize=1)
def code_fingerprint():
    """SHA-256 over the sources of ``sim/`` (:func:`sim._math.jit.source_fingerprint`, which also
    names the numba cache) and the numpy, numba and xarray versions."""
    import numba

    h = hashlib.sha256(f"numpy {np.__version__} numba {numba.__version__} xarray {xr.__version__}".encode())
    h.update(source_fingerprint().encode())
    return h.hexdigest()


def _plain(node):
    """Config as plain data with every number a float (17 and 17.0 give one key)."""
    if isinstance(node, dict):
        return {k: _plain(v) for k, v in node.items()}
    if isinstance(node, list):
        return [_plain(v) for v in node]
    if isinstance(node, (int, float)) and not isinstance(node, bool):
        return float(node)
    return node


def design_config(cfg):
    """The resolved config without ``load``, ``hydra`` and the where-to-write output keys (a dict)."""
    data = OmegaConf.to_container(cfg, resolve=True)
    for group in ("load", "hydra"):
        data.pop(group, None)
    for name in NOT_IN_KEY:
        data.get("output", {}).pop(name, None)
    return data


def _key_base(cfg):
    """What every case key of one config shares: its design config and the code fingerprint."""
    return {"config": _plain(design_config(cfg)), "code": code_fingerprint()}


def case_key(base, op):
    """Cache key of one load case ``op`` (sim.api.simulation.OperatingPoint) of a config (``_key_base``)."""
    payload = dict(base, case=list(op.values()))
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()


def cache_file(cfg, op, base=None):
    """Path of the cached result of case ``op`` of ``cfg`` (None when ``output.cache_dir`` is null)."""
    if cfg.output.cache_dir is None:
        return None
    key = case_key(base or _key_base(cfg), op)
    return Path(cfg.output.cache_dir) / key[:2] / f"{key}{CACHE_SUFFIX}"


# ------------------------------------------------------------------ the cache file format
CACHE_SUFFIX = ".json"
CACHE_FORMAT = "sim.api.sweep case cache"
CACHE_VERSION = 1
ARRAY_KINDS = "biufcUSMm"   # bool, integers, floats, complex, fixed-width text, dates: raw bytes, no objects


def _encode_array(values):
    """A numpy array as JSON-able ``{"dtype", "shape", "data"}``: its C-order bytes in base64 (bit exact)."""
    arr = np.asarray(values)
    if arr.dtype.kind not in ARRAY_KINDS:
        raise TypeError(f"cannot cache an array of dtype {arr.dtype} (only {ARRAY_KINDS} kinds, no objects)")
    return {"dtype": arr.dtype.str, "shape": list(arr.shape),
            "data": base64.b64encode(np.ascontiguousarray(arr).tobytes()).decode("ascii")}


def _decode_array(node):
    """Inverse of :func:`_encode_array`; refuses object and structured dtypes and a wrong byte count."""
    dtype = np.dtype(node["dtype"])
    if dtype.kind not in ARRAY_KINDS or dtype.fields is not None:
        raise ValueError(f"dtype {node['dtype']!r} is not a plain array dtype")
    shape = tuple(int(n) for n in node["shape"])
    return np.frombuffer(base64.b64decode(node["data"], validate=True), dtype=dtype).reshape(shape).copy()


def _encode_attrs(attrs):
    """Attributes as JSON: str, bool, int, float and lists of them as they are, numpy values tagged."""
    out = {}
    for name, value in attrs.items():
        if isinstance(value, (np.ndarray, np.generic)):
            out[name] = {"ndarray": _encode_array(value)}
        elif isinstance(value, (str, bool, int, float)) or (
                isinstance(value, (list, tuple)) and all(isinstance(v, (str, bool, int, float)) for v in value)):
            out[name] = value
        else:
            raise TypeError(f"cannot cache attribute {name!r} of type {type(value).__name__}")
    return out


def _decode_attrs(node):
    if not isinstance(node, dict):
        raise TypeError("attributes are not a JSON object")
    return {name: _decode_array(v["ndarray"]) if isinstance(v, dict) else v for name, v in node.items()}


def encode_case(ds):
    """A Dataset as the bytes of a cache file: UTF-8 JSON, every array as raw bytes in base64.

    Layout (``CACHE_VERSION`` 1)::

        {"format": "sim.api.sweep case cache", "version": 1, "attrs": {...},
         "coords": {name: variable, ...}, "data_vars": {name: variable, ...}}
        variable = {"dims": [...], "dtype": "<f8", "shape": [...], "data": "<base64>", "attrs": {...}}

    Arrays keep dtype, shape and every bit (NaN payloads included); names, dimensions,
    attributes and their order are kept. Plain data only: nothing is ever unpickled.
    """
    def variables(mapping):
        return {str(name): {"dims": list(v.dims), **_encode_array(v.values), "attrs": _encode_attrs(v.attrs)}
                for name, v in mapping.items()}

    doc = {"format": CACHE_FORMAT, "version": CACHE_VERSION, "attrs": _encode_attrs(ds.attrs),
           "coords": variables(ds.coords), "data_vars": variables(ds.data_vars)}
    return json.dumps(doc, allow_nan=True).encode()


def decode_case(data):
    """The Dataset of :func:`encode_case` bytes; ValueError (or another Exception) if they are not one."""
    doc = json.loads(data.decode("utf-8"))
    if not isinstance(doc, dict) or doc.get("format") != CACHE_FORMAT or doc.get("version") != CACHE_VERSION:
        raise ValueError(f"not a {CACHE_FORMAT!r} file of version {CACHE_VERSION}")

    def variables(node):
        return {name: xr.Variable(tuple(v["dims"]), _decode_array(v), _decode_attrs(v["attrs"]))
                for name, v in node.items()}

    return xr.Dataset(variables(doc["data_vars"]), coords=variables(doc["coords"]), attrs=_decode_attrs(doc["attrs"]))


def _cached(path, op):
    """The cached one-case Dataset of case ``op`` at ``path``, or None (absent, or unreadable: then removed).

    An entry is used only if it parses as :func:`encode_case` JSON, is one converged case and
    is the case ``op``; anything else (a damaged or foreign file) is reported, deleted and
    recomputed. Nothing is unpickled or executed.
    """
    if path is None or not path.exists():
        return None
    try:
        ds = decode_case(path.read_bytes())
        if ds.sizes.get("case") != 1 or not bool(ds["converged"].all()):
            raise ValueError("not one converged case")
        case = [float(ds[name].values[0]) for name in io.CASE_COORDS]
        if case != list(op.values()):
            raise ValueError(f"holds case {case}, not {op}")
        return ds
    except Exception as exc:  # a damaged entry is recomputed, never trusted
        log.warning("cache entry %s unreadable (%s): recomputing", path, exc)
        try:
            path.unlink(missing_ok=True)
        except OSError:  # a read-only cache: the entry stays, the case is computed here
            pass
        return None


# ------------------------------------------------------------------ files of interrupted writers
#: A temporary or claim file whose writer cannot be asked (another host, or a name without its
#: pid) is stale after this long [s]: engineering choice, far above the write of one result file
#: or the computation of one case (seconds to minutes), so a live writer is never disturbed.
STALE_AFTER = 3600.0
TMP_SUFFIX = io.TMP_SUFFIX
CLAIM_SUFFIX = ".claim"
BROKEN_SUFFIX = ".broken"
HOST_TAG = io.HOST_TAG


def _pid_alive(pid):
    """Whether process ``pid`` runs on this host (a pid of another user's process counts as alive)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True
    return True


def _writer(name):
    """(host tag, pid) of a temporary file written by :func:`sim.io.write_bytes_atomic` or
    :func:`sim.io.write_netcdf_atomic` (:func:`sim.io.temporary_path`), or None (another writer)."""
    if not name.endswith(TMP_SUFFIX):
        return None
    parts = name[: -len(TMP_SUFFIX)].rsplit(".", 1)[-1].split("-")
    if len(parts) != 3 or len(parts[0]) != len(HOST_TAG) or not parts[1].isdigit():
        return None
    return parts[0], int(parts[1])


def _is_stale(path, writer, now=None):
    """Whether a file of ``writer`` (host tag, pid, or None) at ``path`` has no live writer: its pid is
    dead on this host, or it is older than STALE_AFTER."""
    if writer is not None:
        host, pid = writer
        if host == HOST_TAG and pid != os.getpid():
            return not _pid_alive(pid)
    try:
        age = (now or time.time()) - path.stat().st_mtime
    except FileNotFoundError:
        return False
    return age > STALE_AFTER


def remove_stale_files(folder, shards=False):
    """Remove temporary files (``.*.tmp``) and case claims (``*.claim``) of interrupted writers.

    Only stale ones (:func:`_is_stale`): a concurrent run's files in progress are left alone.
    ``shards``: look in the two-character subfolders of a result cache. A folder that cannot be
    read or written is left as it is. Returns the number of files removed.
    """
    folder = Path(folder)
    folders = [folder]
    if shards:
        try:
            folders += [d for d in folder.iterdir() if d.is_dir() and len(d.name) == 2]
        except OSError:
            return 0
    removed = 0
    for d in folders:
        try:
            entries = list(d.iterdir())
        except OSError:
            continue
        for path in entries:
            name = path.name
            if name.startswith(".") and name.endswith(TMP_SUFFIX):
                stale = _is_stale(path, _writer(name))
            elif name.startswith(".") and name.endswith(BROKEN_SUFFIX):
                stale = _is_stale(path, None)   # a stale claim set aside by a run killed while removing it
            elif name.endswith(CLAIM_SUFFIX):
                stale = _claim_is_stale(path)
            else:
                continue
            if stale:
                try:
                    path.unlink()
                    removed += 1
                except OSError:
                    pass
    if removed:
        log.info("removed %d stale temporary or claim file(s) of interrupted runs in %s", removed, folder)
    return removed


# ------------------------------------------------------------------ claims: no case computed twice
# A run that computes an uncached case first creates ``<key>.claim`` beside the cache entry
# (O_CREAT | O_EXCL: one process wins) holding its host, pid and a token, and removes it when
# done. Another run that finds the claim computes other cases first and then waits for the
# entry; a claim whose process died (same host) or that is older than STALE_AFTER is broken.
POLL = (0.05, 1.0)   # s: first and longest pause between looks at a claimed case
_held = set()        # claim files held by this process (threads share its pid)
_held_lock = threading.Lock()
_warned = set()      # cache folders already reported as unwritable


def _claim_file(path):
    return path.with_name(path.name[: -len(CACHE_SUFFIX)] + CLAIM_SUFFIX)


def _read_claim(claim):
    try:
        return json.loads(claim.read_text())
    except (OSError, ValueError):
        return None


def _claim_is_stale(claim):
    """Whether a claim's process is gone: dead pid on this host (or this process, not holding it),
    or older than STALE_AFTER; an unreadable claim after a short grace (a claim is written right
    after it is created)."""
    info = _read_claim(claim)
    if not isinstance(info, dict):
        try:
            return time.time() - claim.stat().st_mtime > 10.0
        except FileNotFoundError:
            return False
    if info.get("host") == HOST_TAG and isinstance(info.get("pid"), int):
        if info["pid"] == os.getpid():
            with _held_lock:
                return claim not in _held
        return not _pid_alive(info["pid"])
    return _is_stale(claim, None)


def _break_claim(claim, seen):
    """Remove a stale claim whose content was ``seen``; a claim renewed meanwhile is put back."""
    aside = claim.with_name(f".{claim.name}.{secrets.token_hex(4)}{BROKEN_SUFFIX}")
    try:
        os.rename(claim, aside)
    except OSError:
        return  # another run broke it first (or the cache is read-only)
    if _read_claim(aside) != seen:
        try:
            os.link(aside, claim)  # a fresh claim was taken between our look and the rename: restore it
        except OSError:
            pass
    aside.unlink(missing_ok=True)
    log.warning("removed the claim %s of a run that is gone (%s)", claim, seen)


def _warn_unwritable(folder, exc):
    if str(folder) not in _warned:
        _warned.add(str(folder))
        log.warning("the result cache %s cannot be written (%s): computed cases are kept in this run's own "
                    "result file only, and runs sharing the cache may compute a case twice", folder, exc)


def _claim(path):
    """Claim the case cached at ``path``: ("mine", token) to compute it, ("theirs", None) when a live
    run holds it, ("none", None) when the cache cannot be written (compute without a claim)."""
    claim = _claim_file(path)
    for _ in range(3):
        try:
            claim.parent.mkdir(parents=True, exist_ok=True)
            fd = os.open(claim, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        except FileExistsError:
            seen = _read_claim(claim)
            if not _claim_is_stale(claim):
                return "theirs", None
            _break_claim(claim, seen)
            continue
        except OSError as exc:
            _warn_unwritable(path.parent.parent, exc)
            return "none", None
        token = secrets.token_hex(8)
        with _held_lock:
            _held.add(claim)
        try:
            with os.fdopen(fd, "w") as f:
                json.dump({"host": HOST_TAG, "hostname": socket.gethostname(), "pid": os.getpid(),
                           "token": token, "time": time.time()}, f)
        except OSError as exc:  # a full disk: the empty claim still holds the case
            log.warning("claim %s written empty (%s)", claim, exc)
        return "mine", token
    return "theirs", None


def _release(path, token):
    """Remove our claim of the case at ``path`` (not a claim another run took after breaking ours)."""
    claim = _claim_file(path)
    with _held_lock:
        _held.discard(claim)
    info = _read_claim(claim)
    if info is None or info.get("token") == token:
        try:
            claim.unlink(missing_ok=True)
        except OSError:
            pass


def _await_case(path, op):
    """Wait while another run holds the claim of the case at ``path``: its Dataset once cached, or
    None when the claim is gone without a cache entry (not converged, failed) or went stale."""
    pause = POLL[0]
    claim = _claim_file(path)
    while True:
        ds = _cached(path, op)
        if ds is not None:
            return ds
        if not claim.exists():
            return _cached(path, op)  # written just before the claim was removed, or None
        if _claim_is_stale(claim):
            _break_claim(claim, _read_claim(claim))
            return None
        time.sleep(pause)
        pause = min(2 * pause, POLL[1])


def _store(path, ds):
    """Cache a converged case; a cache that cannot be written (full, read-only) is reported once and
    the run goes on (the case is in the run's own result)."""
    try:
        io.write_bytes_atomic(path, encode_case(ds))
    except OSError as exc:
        _warn_unwritable(path.parent.parent, exc)


def _simulate_case(cfg, op, path, grid=False):
    cfg.load.update(dict(zip(io.CASE_COORDS, op.values())), zip=[])
    ds = simulate(cfg, grid=grid)
    log.debug("computed case %s %s", path.stem if path is not None else "(no cache)", op)
    if path is not None and bool(ds.converged.all()):
        _store(path, ds)
    return ds


def compute_case(cfg, op, path, wait=True, grid=False):
    """Dataset of one load case: from the cache file ``path`` or computed (and cached when converged).
    ``grid``: the case is one of a grid (:func:`sim.api.simulation.simulate`: beyond the model's
    validity limits it is a case without a result, not refused input).

    Returns the Dataset and whether it came from the cache. ``cfg`` is a private copy whose
    ``load`` node this function sets to the case. The case is claimed while it is computed
    (:func:`_claim`); when another run holds the claim, this waits for its result
    (``wait=False``: returns ``(None, False)`` at once, to come back later). A case that the
    other run could not cache (not converged, failed) is computed here after it.
    """
    ds = _cached(path, op)
    if ds is not None:
        return ds, True
    if path is None:
        return _simulate_case(cfg, op, None, grid), False
    while True:
        state, token = _claim(path)
        if state == "theirs":
            if not wait:
                return None, False
            ds = _await_case(path, op)
            if ds is not None:
                return ds, True
            continue
        try:
            ds = _cached(path, op)   # finished by another run between our first look and the claim
            if ds is not None:
                return ds, True
            return _simulate_case(cfg, op, path, grid), False
        finally:
            if state == "mine":
                _release(path, token)


def run_cases(cfg, progress=True):
    """All load cases of ``cfg.load`` (one or a grid), each from the cache or computed.

    Cases that another run is computing (claimed in the shared cache) are left for last and
    then taken from the cache once it is there. A case of a grid beyond the model's validity
    limits is a case without a result, its refusal the reason (as a multirun's job of it); a
    single case beyond them is refused input (OutOfRangeError).

    Parameters
    ----------
    cfg : omegaconf.DictConfig
        Composed config.
    progress : bool
        Show a tqdm bar over the cases (runs with more than one case, on a terminal).

    Returns
    -------
    (xarray.Dataset, dict)
        The run's Dataset (``design`` 1, ``case`` = the grid) and counts ``cases``, ``cached``,
        ``computed``, ``not_converged``.
    """
    ops = operating_points(cfg.load)
    base, one, grid = _key_base(cfg), copy.deepcopy(cfg), len(ops) > 1
    paths = [cache_file(cfg, op, base) for op in ops]
    done = [None] * len(ops)
    for i in tqdm(range(len(ops)), desc="cases", unit="case", disable=None if progress and grid else True):
        ds, hit = compute_case(one, ops[i], paths[i], wait=False, grid=grid)
        if ds is not None:
            done[i] = ds, hit
    for i in (i for i, d in enumerate(done) if d is None):   # claimed by another run: its result, or ours
        done[i] = compute_case(one, ops[i], paths[i], grid=grid)
    cached = sum(hit for _, hit in done)
    config_yaml = OmegaConf.to_yaml(cfg, resolve=True)
    ds = io.combine_cases([ds for ds, _ in done], config_yaml)
    ds.attrs["code_fingerprint"] = code_fingerprint()  # the code part of the cache keys (sources of sim/)
    stats = {"cases": len(ops), "cached": cached, "computed": len(ops) - cached,
             "not_converged": int((~ds.converged.values.astype(bool)).sum())}
    return ds, stats


# ------------------------------------------------------------------ one multirun job
def run_job(cfg, out_dir, job, overrides):
    """Run one multirun job into ``out_dir``: ``result.nc`` or ``failed.json``, one log line.

    Never raises for a failed point (the sweep goes on and the collector records it). A result
    that cannot be written (full disk, read-only folder) is a failed job whose message names the
    file; its converged cases are in the result cache, so a re-run only writes them.
    """
    out_dir = Path(out_dir)
    result, failed = out_dir / cfg.output.file, out_dir / FAILED
    remove_stale_files(result.parent)   # temporaries of an interrupted write of this job
    result.unlink(missing_ok=True)   # a re-used sweep folder must not show an old result
    failed.unlink(missing_ok=True)
    head = f"job {job} [{' '.join(overrides)}]"
    t0 = time.perf_counter()
    try:
        validate(cfg)
        ds, n = run_cases(cfg, progress=False)
        write_result(ds, result, cfg)
    except Exception as exc:
        message = f"{type(exc).__name__}: {exc}"
        (log.warning if isinstance(exc, ValueError) else log.exception)("%s failed: %s", head, message)
        try:
            marker = {"job": job, "overrides": list(overrides), "error": message}
            io.write_bytes_atomic(failed, json.dumps(marker).encode())
        except OSError as err:
            log.error("%s: %s cannot be written either (%s): the collector will report the job as missing",
                      head, failed, err)
        return
    log.info("%s: %d cases (%d from cache, %d computed, %d not converged) in %.1f s", head, n["cases"],
             n["cached"], n["computed"], n["not_converged"], time.perf_counter() - t0)


class WriteError(OSError):
    """A result file that cannot be written (full disk, read-only folder); the message names it."""


def write_result(ds, path, cfg=None):
    """``sim.io.write_netcdf_atomic`` with a failure named: WriteError giving the path, the cause,
    the free space there and where the finished cases are (the result cache)."""
    try:
        return io.write_netcdf_atomic(ds, path)
    except (OSError, RuntimeError) as exc:  # netCDF4 reports a full disk as RuntimeError "HDF error"
        try:
            free = shutil.disk_usage(Path(path).parent).free
            free = f"{free / 1e3:.0f} kB free there" if free < 1e7 else f"{free / 1e6:.0f} MB free there"
        except OSError:
            free = "its folder cannot be read"
        cache = cfg.output.cache_dir if cfg is not None else None
        kept = (f"; its converged cases are in the result cache {cache}, so a re-run only writes the file"
                if cache is not None else "")
        raise WriteError(f"cannot write {path}: {type(exc).__name__}: {exc} ({free}; is the disk full or the "
                         f"folder read-only?){kept}") from exc


def output_path_problem(file, run_dir, multirun=False):
    """Why ``output.file`` cannot be written from ``run_dir`` (None if it can).

    A path inside the run (or job) folder is always fine (it is created); a path outside it must
    be in an existing folder, so that a typo never creates folders elsewhere (``/x/result.nc``
    would create ``/x``); in a multirun every job writes its own file, inside its job folder.
    """
    run_dir = os.path.abspath(run_dir)
    target = os.path.abspath(os.path.join(run_dir, str(file)))
    if os.path.commonpath([run_dir, target]) == run_dir and target != run_dir:
        return None
    if multirun:
        return (f"output.file = {str(file)!r} is outside the job folder: in a multirun each job writes its own "
                f"result, so it must be a path inside the job folder (e.g. result.nc)")
    if not os.path.isdir(os.path.dirname(target)):
        return (f"output.file = {str(file)!r} is outside the run folder and its folder {os.path.dirname(target)} "
                "does not exist: a path outside the run folder must be in an existing folder")
    return None


# ------------------------------------------------------------------ the multirun around the jobs
def sweep_jobs(config):
    """Override lists of the jobs of a multirun, in job order, as Hydra's basic sweeper forms them.

    Public Hydra API only (``OverridesParser``, ``Override``): the sweeper's ``params`` then the
    command-line overrides, one column per key (a later override of a key replaces an earlier
    one), each a discrete sweep's values or the single value; the jobs are the Cartesian product
    of the columns, the last key varying fastest (Hydra's documented ``a=1,2 b=x,y`` order).
    """
    from hydra.core.override_parser.overrides_parser import OverridesParser

    params = OmegaConf.select(config, "hydra.sweeper.params") or {}
    arguments = [f"{k}={v}" for k, v in params.items()] + list(config.hydra.overrides.task)
    columns = {}
    for override in OverridesParser.create().parse_overrides(arguments):
        key = override.get_key_element()
        if not override.is_sweep_override():
            columns[key] = [f"{key}={override.get_value_element_as_str()}"]
        elif override.is_discrete_sweep():
            columns[key] = [f"{key}={value}" for value in override.sweep_string_iterator()]
        else:
            raise ValueError(f"{key}: the basic sweeper does not support sweep type {override.value_type.name}")
    return [list(job) for job in itertools.product(*columns.values())]


def _kind(cfg):
    """Jobs of one kind run the same numba kernels: same bearing type and non-geometry config."""
    data = design_config(cfg)
    data.pop("bearing")
    return json.dumps([cfg.bearing.type, _plain(data)], sort_keys=True)


def _is_cached(cfg, op, base):
    path = cache_file(cfg, op, base)
    return path is not None and path.exists()


#: the warm-up run of a time-domain job (:func:`warm_up`): its case with the shortest run the schema
#: allows, two windows of one roller pass each (window_revolutions is rounded up to whole roller
#: passes), which runs every kernel of the time-domain solver in its first steps
DYNAMIC_WARM_UP = {"window_revolutions": 1e-3, "samples_per_window": 2, "max_windows": 2}


def warm_up(configs, attempts=3):
    """Compute cases of each kind of job here, before any worker starts, until one converges.

    A converged case runs every numba kernel of its kind (the friction kernels only run after
    the load distribution converged), so they are compiled, or loaded, into numba's on-disk
    cache once, here; workers started afterwards only load them. Up to ``attempts`` uncached
    cases per kind are tried; the cases computed go to the result cache as usual.

    A time-domain job (``solver=dynamic``) warms up with :data:`DYNAMIC_WARM_UP` instead of its own
    settings: a case takes minutes, and one that reaches no steady state is not cached, so a
    warm-up of the job's own run was computed again by its job (a case capped at max_windows = 2
    took 24 s here and 26 s in its job; at the default 30 windows up to ~10 min each). That short
    run is not cached (its settings are not the job's); it warms its kind once it integrated
    (its time series has samples), converged or not.
    """
    done, tried = set(), {}
    for cfg in configs:
        kind = _kind(cfg)
        base = _key_base(cfg)
        dynamic = OmegaConf.select(cfg, "solver.name") == "dynamic"
        ops = operating_points(cfg.load)
        grid = len(ops) > 1
        for op in ops:
            if kind in done or tried.get(kind, 0) >= attempts:
                break
            if _is_cached(cfg, op, base):
                continue
            try:
                if dynamic:
                    short = copy.deepcopy(cfg)
                    short.solver.dynamic.update(DYNAMIC_WARM_UP)
                    ds = _simulate_case(short, op, None, grid)
                else:
                    ds, _ = compute_case(copy.deepcopy(cfg), op, cache_file(cfg, op, base), wait=False, grid=grid)
            except Exception:  # the job records the error; another job of this kind warms up
                break
            if ds is None:
                continue  # another run is computing it (and compiling the kernels there)
            tried[kind] = tried.get(kind, 0) + 1
            if bool(ds.converged.all()) or (dynamic and ds.sizes.get("time", 0) > 0):
                done.add(kind)


def _refuse(problems, what="sweep refused before any job ran"):
    """One line on stderr, exit 2 (:mod:`sim.api.cli`): SystemExit passes Hydra's callback guard,
    which only turns Exceptions into warnings."""
    refuse(f"{what}: " + "; ".join(one_line(p) for p in problems))


#: run folders that did not exist when a single run started (sim.run removes them again when
#: the run is refused after Hydra created them)
NEW_RUN_DIRS = set()


def preflight(cfg):
    """Everything a run checks before it computes, without computing: the schema
    (:func:`validate`), the geometry's feasibility and the friction inputs (the models are built
    as :func:`simulate` builds them). Raises the project's errors (ConfigError, GeometryError,
    InputError)."""
    validate(cfg)
    build_friction(cfg, build_model(cfg))


class SweepCallback(Callback):
    """Hydra callback (``conf/config.yaml``, ``hydra.callbacks.sweep``).

    Parameters
    ----------
    after_collect : str, optional
        Dotted name of a function called with the path of ``sweep.nc`` once it is written
        (``studies.sensitivity.plot_figures`` draws the figures of thesis 7.2).
    """

    def __init__(self, after_collect=None):
        self.after_collect = after_collect

    def on_run_start(self, config, **kwargs):
        """A single run: refuse bad input (one line, exit 2) before Hydra creates the run folder."""
        run_dir = Path(config.hydra.run.dir)
        try:
            preflight(config)
        except PROJECT_ERRORS as exc:
            _refuse([str(exc)], "run refused before anything ran")
        problem = output_path_problem(config.output.file, run_dir)
        if problem:
            _refuse([problem], "run refused before anything ran")
        if not run_dir.exists():
            NEW_RUN_DIRS.add(str(run_dir.resolve()))
        if config.output.cache_dir is not None:
            remove_stale_files(config.output.cache_dir, shards=True)

    def on_multirun_start(self, config, **kwargs):
        from hydra import compose

        sweeper = (OmegaConf.select(config, "hydra.runtime.choices") or {}).get("hydra/sweeper")
        if sweeper != BASIC_SWEEPER:
            log.warning("sweep: hydra/sweeper=%s is not the basic sweeper; no job list, no collection", sweeper)
            return
        jobs = sweep_jobs(config)
        configs, problems = [], []
        for num, overrides in enumerate(jobs):
            try:
                cfg = compose(config_name=kwargs.get("config_name"), overrides=list(overrides))
                validate(cfg)
                configs.append(cfg)
            except ConfigError as exc:
                problems += [f"job {num} [{' '.join(overrides)}]: {line}" for line in str(exc).splitlines()]
                continue
            except Exception as exc:  # composition: an unknown key (the cause names it and its schema)
                text = " ".join(str(exc).split()) + (f" {exc.__cause__}".split("\n")[0] if exc.__cause__ else "")
                problems.append(f"job {num} [{' '.join(overrides)}]: {text}")
                continue
            problem = output_path_problem(cfg.output.file, Path(config.hydra.sweep.dir) / str(num), multirun=True)
            if problem:
                problems.append(f"job {num} [{' '.join(overrides)}]: {problem}")
        if problems:
            _refuse(problems)
        sweep_dir = Path(config.hydra.sweep.dir)
        sweep_dir.mkdir(parents=True, exist_ok=True)
        remove_stale_files(sweep_dir)
        for cache_dir in {str(cfg.output.cache_dir) for cfg in configs if cfg.output.cache_dir is not None}:
            remove_stale_files(cache_dir, shards=True)
        manifest = {"overrides": list(config.hydra.overrides.task),
                    "config": OmegaConf.to_yaml(OmegaConf.masked_copy(config, [k for k in config if k != "hydra"]),
                                                resolve=True),
                    "jobs": [{"job": num, "overrides": list(o), "config": OmegaConf.to_container(cfg, resolve=True)}
                             for num, (o, cfg) in enumerate(zip(jobs, configs))]}
        io.write_bytes_atomic(sweep_dir / MANIFEST, json.dumps(manifest, indent=1).encode())
        cases = [(cfg, op, base) for cfg, base in ((c, _key_base(c)) for c in configs)
                 for op in operating_points(cfg.load)]
        log.info("sweep: %d jobs, %d cases, %d already in the cache; results in %s", len(jobs), len(cases),
                 sum(_is_cached(*case) for case in cases), sweep_dir)
        t0 = time.perf_counter()
        warm_up(configs)
        log.info("sweep: numba kernels compiled or loaded in this process in %.1f s", time.perf_counter() - t0)

    def on_multirun_end(self, config, **kwargs):
        """Collect ``sweep.nc``; exit 1 with a summary when a job left no readable result. Points without a
        result (an error, not converged) are results of their jobs: exit 0, with their count as the last
        line on stderr (:func:`unsolved_summary`; README, "Errors and exit status")."""
        sweep_dir = Path(config.hydra.sweep.dir)
        if not (sweep_dir / MANIFEST).exists():
            return
        try:
            path, incomplete = collect_jobs(sweep_dir)
        except WriteError as exc:
            refuse(exc, status=1)
        if self.after_collect:
            module, _, name = self.after_collect.rpartition(".")
            getattr(import_module(module), name)(path)
        if incomplete:
            refuse(incomplete_summary(path, incomplete), status=1)
        unsolved = unsolved_summary(path)
        if unsolved:        # every job left a result (exit 0), but some points of it are none: said last, on stderr
            print(unsolved, file=sys.stderr, flush=True)


def unsolved_summary(path):
    """One line for a collected ``sweep.nc`` whose cases include some without a result (not converged or
    failed with an error: its failure table), or "" when every case converged."""
    with xr.open_dataset(path) as ds:
        if ds.sizes.get("failure", 0) == 0:
            return ""
        reasons = failure_reasons(ds)
        total = ds.sizes["design"] * ds.sizes["case"]
    return (f"{path}: {sum(reasons.values())} of {total} cases without a result ("
            + ", ".join(f"{n} {r}" for r, n in reasons.items()) + "; listed in its failed_* variables); exit "
            "status 0: every job left its result")


# ------------------------------------------------------------------ the collector
NOT_FINISHED = "the job did not finish (killed, or not run yet)"
DAMAGED = "damaged"       # failure reason of a job whose files are there but unreadable or incomplete
INCOMPLETE = ("missing", DAMAGED)   # reasons that leave a sweep unfinished (a re-run completes it)
#: results that a converged case always has as finite numbers (sim.io; the contract checker's list and more)
FINITE_WHEN_CONVERGED = ("pmax", "axial_displacement", "torque", "power_loss", "C_eff")


class SweepError(InputError):
    """A folder that is not a sweep folder (no or an unreadable ``sweep.json``)."""


def result_problem(ds, cfg):
    """Why a job's result Dataset is not the whole result of its config (DATA.md), or "".

    Checks what the collector relies on: one design, the job's cases exactly, every variable
    that sim.io writes for the job's config (the optional ones of sim.io.written_optional: friction
    and skew outputs as the config enables them) with its dimensions, and finite key results
    wherever a case is marked converged.
    """
    if ds.sizes.get("design") != 1 or "case" not in ds.sizes:
        return f"dimensions {dict(ds.sizes)}: not one design over cases"
    absent = [c for c in io.CASE_COORDS if c not in ds.coords]
    if absent:
        return f"no case coordinate {', '.join(absent)}"
    want = sorted(o.values() for o in operating_points(cfg.load))
    got = sorted(_case_tuples(ds))
    if got != want:
        return f"holds {len(got)} cases that are not the job's {len(want)} (a result of another job or run?)"
    if "converged" not in ds:
        return "no variable converged"
    conv = np.asarray(ds["converged"].values, dtype=bool)
    optional = io.written_optional(bool(OmegaConf.select(cfg, "friction.enabled")),
                                   bool(OmegaConf.select(cfg, "friction.skew.enabled")),
                                   OmegaConf.select(cfg, "solver.name") == "dynamic")
    names = [n for n in io.CASE_VARIABLES if n not in io.OPTIONAL_VARIABLES or n in optional]
    expected = {n: ("design", "case") + io.CASE_VARIABLES[n][0] for n in names} | {"C": ("design",), "C0": ("design",)}
    absent = [n for n in expected if n not in ds.data_vars]
    if absent:
        return f"no variable {', '.join(absent)}"
    for name, dims in expected.items():
        if ds[name].dims != dims:
            return f"{name} has dimensions {ds[name].dims}, not {dims}"
    for name in FINITE_WHEN_CONVERGED:
        if name in ds and ds[name].dtype.kind == "f":
            values = ds[name].values.reshape(conv.shape + (-1,))
            if not np.isfinite(values[conv]).all():
                return f"{name} is not finite for a case marked converged"
    for name in ("C", "C0"):
        if not np.isfinite(ds[name].values).all():
            return f"{name} is not finite"
    return ""


def _job_outcome(sweep_dir, job, cfg):
    """(Dataset, None, None), or (None, reason, message) with reason "error", "missing" or "damaged".

    Never raises for what a job left behind: an unreadable ``overrides.yaml``, ``failed.json``
    or result file, or a result that :func:`result_problem` refuses, is a damaged job whose
    message says which file and why.
    """
    job_dir = sweep_dir / str(job["job"])
    saved = job_dir / ".hydra" / "overrides.yaml"
    if not saved.exists():
        return None, "missing", NOT_FINISHED   # never started
    try:
        overrides = list(OmegaConf.load(saved))
    except Exception as exc:
        return None, DAMAGED, f"{saved} unreadable: {type(exc).__name__}: {one_line(exc)}"
    if overrides != job["overrides"]:
        return None, "missing", NOT_FINISHED   # a folder of another sweep
    failed = job_dir / FAILED
    if failed.exists():
        try:
            error = json.loads(failed.read_text())["error"]
            if not isinstance(error, str):
                raise TypeError(f"its error is a {type(error).__name__}, not text")
        except Exception as exc:
            return None, DAMAGED, f"{failed} unreadable: {type(exc).__name__}: {one_line(exc)}"
        return None, "error", error
    result = job_dir / cfg.output.file
    if not result.exists():
        return None, "missing", NOT_FINISHED
    try:
        ds = xr.load_dataset(result)
    except Exception as exc:  # truncated, empty or not NetCDF at all
        return None, DAMAGED, f"{result} unreadable: {type(exc).__name__}: {one_line(exc)}"
    problem = result_problem(ds, cfg)
    if problem:
        return None, DAMAGED, f"{result} incomplete: {problem}"
    return ds, None, None


def _is_load(key):
    return key == "load" or key.startswith("load.")


def _case_tuples(ds):
    return list(zip(*(ds[c].values.tolist() for c in io.CASE_COORDS)))


def _group_designs(jobs, configs):
    """Job indices per design, in order: jobs whose config and non-load overrides agree."""
    designs = {}
    for i, (job, cfg) in enumerate(zip(jobs, configs)):
        others = sorted(o for o in job["overrides"] if not _is_load(o.partition("=")[0].lstrip("+~")))
        designs.setdefault(json.dumps([_plain(design_config(cfg)), others], sort_keys=True), []).append(i)
    return list(designs.values())


def _design_dataset(members, outcomes, configs):
    """One design's Dataset from its jobs (a failed or missing job as a placeholder), each case once."""
    parts, seen = [], set()
    for i in members:
        ds, _, message = outcomes[i]
        if ds is None:
            cfg = configs[i]
            ds = io.failed_dataset(cfg.bearing, operating_points(cfg.load), OmegaConf.to_yaml(cfg), message)
        parts.append(ds.isel(case=[c for c, t in enumerate(_case_tuples(ds)) if t not in seen]))
        seen.update(_case_tuples(ds))
    return parts[0] if len(parts) == 1 else io.combine_cases(parts, OmegaConf.to_yaml(configs[members[0]]))


def _swept_coords(jobs, configs, designs, datasets):
    """Design coordinates of the non-load overrides that differ between jobs, and all swept names.

    ``bearing.<p>`` is named ``p`` (already a coordinate for the geometry: PCR, kappa, ...); other
    keys by their path with "_" (``solver_n_slices``), a group choice by the group (``bearing``,
    ``variant``) with the option name as value.
    """
    from hydra.core.override_parser.overrides_parser import OverridesParser

    parser = OverridesParser.create()
    parsed = [{o.key_or_group: o for o in parser.parse_overrides(job["overrides"])} for job in jobs]
    extra, names = {}, []
    for key in dict.fromkeys(k for p in parsed for k in p if not _is_load(k)):
        shown = [p[key].get_value_element_as_str() if key in p else "" for p in parsed]
        if len(set(shown)) < 2:
            continue
        name = key.rpartition(".")[2] if key.startswith("bearing.") else key.replace(".", "_")
        names.append(name)
        if name in datasets[0].coords and key.startswith("bearing."):
            continue
        values = []
        for members in designs:
            value = OmegaConf.select(configs[members[0]], key) if key in parsed[members[0]] else None
            values.append(value if isinstance(value, (int, float, str, bool)) else shown[members[0]])
        array = np.asarray(values)
        extra[name] = (array.astype(str) if array.dtype.kind == "O" else array, {"long_name": f"swept {key}"})
    return extra, names


def _failure_rows(ds, jobs, configs, designs, outcomes):
    """One row per point of ``ds`` without a valid result: error, not converged or missing."""
    design_of = {i: d for d, members in enumerate(designs) for i in members}
    case_values = _case_tuples(ds)
    case_index = {t: c for c, t in enumerate(case_values)}
    rows = []
    for i, (job, (job_ds, reason, message)) in enumerate(zip(jobs, outcomes)):
        d = design_of[i]
        points = _case_tuples(job_ds) if job_ds is not None else [
            o.values() for o in operating_points(configs[i].load)]
        for c in (case_index[t] for t in points):
            if job_ds is not None:
                if bool(ds.converged.values[d, c]):
                    continue
                reason = "not converged"
                message = (io.case_failure(job_ds, case_values[c])
                           or f"converged = False after {int(ds.iterations.values[d, c])} ring iterations")
            rows.append({"design": d, "case": c, "job": job["job"], "overrides": " ".join(job["overrides"]),
                         "reason": reason, "message": message})
    return rows


def collect(sweep_dir):
    """Merge the jobs of a multirun folder into ``<sweep_dir>/sweep.nc`` (DATA.md).

    Jobs that differ only in their load form one design; designs and cases fill the flat
    ``design`` x ``case`` grid, swept parameters are design coordinates (attribute ``swept``
    names them), and every point without a valid result (error, not converged, missing, or a
    damaged job: an unreadable or incomplete result file, a corrupt ``failed.json``) is a row of
    the failure table (``failed_*`` variables on dimension ``failure``) and keeps its slot as NaN
    with ``converged = False``. Every other job is merged. Re-collecting the same results gives
    the same data.

    Parameters
    ----------
    sweep_dir : str or pathlib.Path
        A sweep folder of ``python -m sim.run --multirun`` (it holds ``sweep.json``).

    Returns
    -------
    pathlib.Path
        The path of ``sweep.nc``.

    Raises
    ------
    SweepError
        ``sweep_dir`` has no readable ``sweep.json``.
    WriteError
        ``sweep.nc`` cannot be written (full disk, read-only folder).
    """
    return collect_jobs(sweep_dir)[0]


def collect_jobs(sweep_dir):
    """:func:`collect`, and the jobs that left the sweep unfinished: a list of (job, reason,
    message) with reason "missing" or "damaged"."""
    sweep_dir = Path(sweep_dir)
    try:
        manifest = json.loads((sweep_dir / MANIFEST).read_text())
        jobs = manifest["jobs"]
        configs = [OmegaConf.create(job["config"]) for job in jobs]
    except FileNotFoundError:
        raise SweepError(f"{sweep_dir} is not a sweep folder: it has no {MANIFEST} "
                         "(python -m sim.run --multirun writes it before the first job)") from None
    except Exception as exc:
        raise SweepError(f"{sweep_dir / MANIFEST} unreadable: {type(exc).__name__}: {one_line(exc)}") from exc
    remove_stale_files(sweep_dir)
    outcomes = [_job_outcome(sweep_dir, job, cfg) for job, cfg in zip(jobs, configs)]
    designs = _group_designs(jobs, configs)
    datasets = [_design_dataset(members, outcomes, configs) for members in designs]
    extra, swept = _swept_coords(jobs, configs, designs, datasets)
    ds = io.combine_designs(datasets, extra)
    ds["design_config"] = xr.Variable(
        ("design",), [OmegaConf.to_yaml(OmegaConf.create(design_config(configs[m[0]]))) for m in designs],
        {"long_name": "resolved config of the design without load (YAML)"})
    ds = ds.merge(io.failure_table(_failure_rows(ds, jobs, configs, designs, outcomes)))
    provenance = next((d.attrs for d in datasets if "error" not in d.attrs), datasets[0].attrs)
    ds.attrs = {k: v for k, v in provenance.items() if k != "error"}
    ds.attrs.update({"title": f"sweep of {ds.sizes['design']} designs x {ds.sizes['case']} cases",
                     "config": manifest["config"], "sweep_overrides": " ".join(manifest["overrides"]),
                     "swept": " ".join(swept), "sweep_dir": str(sweep_dir.resolve()),
                     "created": io.utc_now()})
    path = write_result(ds, sweep_dir / SWEEP_FILE)
    _report(ds, path)
    incomplete = [(job["job"], reason, message) for job, (_, reason, message) in zip(jobs, outcomes)
                  if reason in INCOMPLETE]
    return path, incomplete


def incomplete_summary(path, incomplete, shown=5):
    """One line: how many jobs left no result, and why (the first ``shown`` of them)."""
    counts = {r: sum(1 for _, reason, _ in incomplete if reason == r) for r in INCOMPLETE}
    head = ", ".join(f"{n} {r}" for r, n in counts.items() if n)
    rows = "; ".join(f"job {job} {reason}: {message}" for job, reason, message in incomplete[:shown])
    more = f"; ... {len(incomplete) - shown} more in the failed_* variables" if len(incomplete) > shown else ""
    return (f"{path} written, but {len(incomplete)} job(s) left no readable result ({head}); re-run the sweep to "
            f"complete it: {rows}{more}")


def failure_reasons(ds):
    """{reason: number of rows} of a sweep Dataset's failure table."""
    return {str(r): int((ds.failed_reason.values == r).sum()) for r in np.unique(ds.failed_reason.values)}


def _report(ds, path, shown=10):
    """Log the size of the sweep and the first ``shown`` rows of its failure table."""
    conv = ds.converged.values.astype(bool)
    reasons = failure_reasons(ds)
    log.info("sweep.nc: %d designs x %d cases, %d converged, failed: %s -> %s", ds.sizes["design"],
             ds.sizes["case"], int(conv.sum()), reasons or "none", path)
    for r in range(min(shown, ds.sizes["failure"])):
        log.info("  design %d case %d (job %d: %s): %s: %s", int(ds.failed_design[r]), int(ds.failed_case[r]),
                 int(ds.failed_job[r]), str(ds.failed_overrides.values[r]), str(ds.failed_reason.values[r]),
                 str(ds.failed_message.values[r]))
    if ds.sizes["failure"] > shown:
        log.info("  ... %d more in the failed_* variables of sweep.nc", ds.sizes["failure"] - shown)


def main(argv=None):
    """``python -m sim.api.sweep collect DIR``: (re)build ``DIR/sweep.nc`` from the jobs in DIR.

    Exit status 0 when every job has a result (an error or a non-converged case is a result),
    1 with a summary on stderr when a job is missing or damaged (sweep.nc is written with the
    others) or sweep.nc cannot be written, 2 when DIR is not a sweep folder.
    """
    parser = argparse.ArgumentParser(prog="python -m sim.api.sweep", description=main.__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("collect", help="merge the jobs of a sweep folder into sweep.nc").add_argument("dir", type=Path)
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    try:
        path, incomplete = collect_jobs(args.dir)
    except WriteError as exc:
        refuse(exc, status=1)
    print(path)
    if incomplete:
        refuse(incomplete_summary(path, incomplete), status=1)
    return 0


if __name__ == "__main__":
    from sim.api.cli import run

    sys.exit(run(main))
