"""Issue 16 item 8: killing the main job leaves no worker process alive (sim.api.worker_pool,
used by the design search's simulations)."""
import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

SCRIPT = textwrap.dedent("""
    import os, sys, time
    from sim.api import worker_pool

    def task(folder):
        open(os.path.join(folder, str(os.getpid())), "w").close()
        time.sleep(120)

    if __name__ == "__main__":
        with worker_pool(2) as pool:
            list(pool.map(task, [sys.argv[1]] * 2))
""")


def _alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    with open(f"/proc/{pid}/stat") as f:            # a zombie (already dead, not yet reaped) counts as gone
        return f.read().split(")")[-1].split()[0] != "Z"


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="prctl(PR_SET_PDEATHSIG) is Linux only")
def test_workers_die_when_the_parent_is_killed(tmp_path):
    """Two workers sleep in their tasks; the parent gets SIGKILL (no clean-up can run); within
    10 s both workers are gone. Without PR_SET_PDEATHSIG they would sleep out their 120 s
    (joblib's loky workers do: measured)."""
    script = tmp_path / "parent.py"
    script.write_text(SCRIPT)
    pids_dir = tmp_path / "pids"
    pids_dir.mkdir()
    parent = subprocess.Popen([sys.executable, str(script), str(pids_dir)], cwd=tmp_path,
                              env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)})
    try:
        deadline = time.monotonic() + 60
        while len(os.listdir(pids_dir)) < 2:
            assert time.monotonic() < deadline and parent.poll() is None, "workers did not start"
            time.sleep(0.1)
        workers = [int(p) for p in os.listdir(pids_dir)]
        assert all(_alive(pid) for pid in workers)
        parent.send_signal(signal.SIGKILL)
        parent.wait()
        deadline = time.monotonic() + 10
        while any(_alive(pid) for pid in workers) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not any(_alive(pid) for pid in workers), workers
    finally:
        if parent.poll() is None:
            parent.kill()
        for pid in [int(p) for p in os.listdir(pids_dir)]:
            if _alive(pid):
                os.kill(pid, signal.SIGKILL)
