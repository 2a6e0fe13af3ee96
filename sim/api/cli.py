"""One error path for the command lines (issue 15, item 3).

Every entry point (``python -m sim.run``, ``python -m sim.api.sweep collect``,
``python -m studies.optimize``, ``python -m studies.sensitivity``) turns the project's own
errors into one line on stderr, ``error: <message>``, and exit status 2, before it creates any
output folder; any other exception is a bug and keeps its traceback (exit status 1). A
message that lists several problems (a :class:`sim.errors.ConfigError` names every bad key, one
per line) is joined with "; " into that one line. Ctrl-C (SIGINT) ends a run with one line
``interrupted: ...`` saying what is kept and exit status :data:`INTERRUPTED`, no traceback.
"""
import sys

from sim.errors import GeometryError, InputError

#: the project's own errors: bad input, named by key, value and allowed range (ConfigError is an
#: InputError), and impossible geometry
PROJECT_ERRORS = (InputError, GeometryError)
#: exit status of a refused input
REFUSED = 2
#: exit status of a run interrupted by Ctrl-C (128 + SIGINT, as a shell reports it)
INTERRUPTED = 130


def one_line(message):
    """The lines of ``message`` (an exception or text) joined with "; ", surrounding blanks removed."""
    return "; ".join(line.strip() for line in str(message).splitlines() if line.strip())


def refused(message, status=REFUSED):
    """Print ``error: <message>`` as one line on stderr; return ``status`` (for a ``main`` to return)."""
    print(f"error: {one_line(message)}", file=sys.stderr, flush=True)
    return status


def refuse(message, status=REFUSED):
    """Print ``error: <message>`` as one line on stderr and exit with ``status``."""
    raise SystemExit(refused(message, status))


def run(main, argv=None, errors=()):
    """``main(argv)`` with the project's errors (and ``errors``) refused as one line and exit 2."""
    try:
        return main(argv)
    except PROJECT_ERRORS + tuple(errors) as exc:
        refuse(exc)
