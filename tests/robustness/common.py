"""Helpers of the robustness tests: the command lines as a user runs them (subprocesses)."""
import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
FAST = ["friction.enabled=false", "solver.n_slices=8"]


def run(args, cwd, timeout=600, env=None, **kwargs):
    """``python <args>`` in ``cwd`` with this checkout first on the path; CompletedProcess (text)."""
    environ = dict(os.environ, PYTHONPATH=str(REPO), PYTHONDONTWRITEBYTECODE="1", **(env or {}))
    return subprocess.run([sys.executable, *args], cwd=cwd, capture_output=True, text=True, timeout=timeout,
                          env=environ, **kwargs)


def assert_refused(out, *fragments, status=2):
    """Exit ``status``, no traceback, and stderr's last line is one ``error: ...`` line holding every fragment."""
    assert out.returncode == status, (out.returncode, out.stdout[-2000:], out.stderr[-3000:])
    assert "Traceback" not in out.stderr, out.stderr[-3000:]
    lines = [line for line in out.stderr.splitlines() if line.strip()]
    assert lines and lines[-1].startswith("error: "), out.stderr[-3000:]
    errors = [line for line in lines if line.startswith("error: ")]
    assert len(errors) == 1, out.stderr[-3000:]
    for fragment in fragments:
        assert fragment in lines[-1], (fragment, lines[-1])
    return lines[-1]
