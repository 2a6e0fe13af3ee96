"""Private numerics layer: the numba setup (:mod:`jit`), small dense linear algebra
(:mod:`linalg`) and one bracketed root finder (:mod:`roots`). Imports nothing above it."""
