"""A throw-away PostgreSQL server for the scale-out tests (issue 17, item 3).

``initdb`` into a temporary directory, ``postgres`` on 127.0.0.1 at a free port with its socket
in that directory, trust authentication (loopback only, nothing else can connect), stopped and
removed after the session. initdb refuses to run as root: as root the server runs as ``nobody``.
``fsync=off``: the server holds test data only; concurrency and transactions are unchanged.

The binaries come from PATH or the Debian packages (/usr/lib/postgresql/<version>/bin; .ci/run
installs them). Without them the tests are skipped, except in CI (CI=true), where they fail.
"""
import glob
import os
import pwd
import shutil
import signal
import socket
import subprocess
import tempfile
import time
from pathlib import Path

import pytest

START_TIMEOUT = 60.0  # s, initdb and start of an empty cluster take ~2-5 s on the 2-core machine


def postgres_bindir():
    """Folder with initdb, pg_ctl and postgres; None if PostgreSQL is not installed."""
    candidates = [str(Path(p).resolve().parent) for p in (shutil.which("initdb"),) if p]
    candidates += sorted(glob.glob("/usr/lib/postgresql/*/bin"), key=lambda d: int(d.split("/")[-2]), reverse=True)
    for d in candidates:
        if all(os.access(Path(d) / exe, os.X_OK) for exe in ("initdb", "pg_ctl", "postgres")):
            return Path(d)
    return None


def missing(what):
    """Skip a test whose server is not installed, but fail it in CI (CI=true) so that a missing
    server never passes silently there."""
    if os.environ.get("CI", "").lower() == "true":
        pytest.fail(f"{what} is not installed in CI: .ci/run installs it with apt-get")
    pytest.skip(f"{what} is not installed (CI installs it: .ci/run)")


def stop(process, sig, timeout=30):
    """Send ``sig`` to a server process and wait ``timeout`` s for it to exit; then kill it."""
    process.send_signal(sig)
    try:
        process.wait(timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="session")
def postgres_server():
    """(host, port) of a running throw-away PostgreSQL server."""
    bindir = postgres_bindir()
    if bindir is None:
        missing("PostgreSQL (initdb, pg_ctl, postgres)")
    import psycopg  # the test extra

    root = Path(tempfile.mkdtemp(prefix="tsrb-pg-"))
    run_as = {}
    if os.geteuid() == 0:
        user = pwd.getpwnam("nobody")
        run_as = {"user": user.pw_uid, "group": user.pw_gid, "extra_groups": []}
        os.chown(root, user.pw_uid, user.pw_gid)
    data, port = root / "data", free_port()
    log = open(root / "server.log", "w")
    subprocess.run([bindir / "initdb", "-D", data, "-U", "postgres", "--auth=trust", "-E", "UTF8", "--no-sync"],
                   check=True, stdout=log, stderr=subprocess.STDOUT, cwd=root, **run_as)
    server = subprocess.Popen([bindir / "postgres", "-D", data, "-p", str(port), "-c", "listen_addresses=127.0.0.1",
                               "-c", f"unix_socket_directories={root}", "-c", "fsync=off", "-c", "max_connections=100"],
                              stdout=log, stderr=subprocess.STDOUT, cwd=root, **run_as)
    try:
        deadline = time.monotonic() + START_TIMEOUT
        while True:
            try:
                psycopg.connect(host="127.0.0.1", port=port, user="postgres", dbname="postgres").close()
                break
            except psycopg.OperationalError:
                if server.poll() is not None or time.monotonic() > deadline:
                    raise RuntimeError(f"PostgreSQL did not start: {(root / 'server.log').read_text()}")
                time.sleep(0.1)
        yield "127.0.0.1", port
    finally:
        stop(server, signal.SIGINT)  # fast shutdown: open client connections are closed
        log.close()
        shutil.rmtree(root, ignore_errors=True)


@pytest.fixture
def postgres_url(postgres_server, request):
    """SQLAlchemy URL of a new, empty database on the test server (one per test)."""
    import psycopg

    host, port = postgres_server
    name = "t_" + "".join(c if c.isalnum() else "_" for c in request.node.name.lower())[:50] + f"_{os.getpid()}"
    with psycopg.connect(host=host, port=port, user="postgres", dbname="postgres", autocommit=True) as con:
        con.execute(f'DROP DATABASE IF EXISTS "{name}"')
        con.execute(f'CREATE DATABASE "{name}"')
    return f"postgresql+psycopg://postgres@{host}:{port}/{name}"
