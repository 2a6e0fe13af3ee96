"""Kernel signatures stay short (issue 13 item 2): state travels in named-tuple bundles
(docs/architecture.md, "Kernel argument bundles"), not in long positional lists."""
import importlib
import os
import pkgutil

import pytest

import sim

pytestmark = pytest.mark.skipif(os.environ.get("NUMBA_DISABLE_JIT") == "1",
                                reason="without the JIT the decorators return plain functions: no dispatchers to find")

# The architecture step's bound: "the largest kernel signature drops below ~10 arguments" (the
# positional lists it replaced reached 32). Scalar formula kernels sit at 8-10 (pressure, speed,
# film, load share, viscosity and their parameter bundles).
MAX_KERNEL_ARGUMENTS = 10


def _kernels():
    """(module, name, argument count) of every numba kernel defined in sim/ (kernel and internal_kernel
    both leave a dispatcher with the Python function as ``py_func``)."""
    found = []
    for info in pkgutil.walk_packages(sim.__path__, "sim."):
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            func = getattr(obj, "py_func", None)
            if func is not None and func.__module__ == info.name:
                found.append((info.name, name, func.__code__.co_argcount))
    return found


def test_the_kernels_are_found():
    """The walk sees the kernels of every layer (a test that finds none would pass vacuously)."""
    modules = {m for m, _, _ in _kernels()}
    assert {"sim.physics.contact", "sim.physics.elasticity", "sim.physics.friction", "sim.solvers.quasi_static",
            "sim.solvers.kinematics", "sim.solvers.dynamic"} <= modules
    assert len(_kernels()) >= 60


def test_no_kernel_takes_more_than_ten_arguments():
    long = sorted((n, f"{m}.{k}") for m, k, n in _kernels() if n > MAX_KERNEL_ARGUMENTS)
    assert not long, f"kernels above {MAX_KERNEL_ARGUMENTS} arguments (bundle them): {long}"
