"""The static force of the spring's series chain, compiled (the engine's twin of
:func:`springdyn.valve.spring.statics.series_force`): the static force along a cam at every output
sample of a simulation."""

from __future__ import annotations

import numpy as np

from ...numerics.jit import kernel

__all__ = ["series_force_compiled"]


@kernel
def series_force_compiled(total_compression, laws, out, table_x, table_f):
    """Compiled twin of :func:`springdyn.valve.spring.statics.series_force` (Newton's method).

    For each total compression [m], the common force [N] of the series chain, by Newton's
    method on each element's closed-form inverse law.  The total compression is a concave
    function of the force (every law stiffens), so from any start the iterates fall below
    the root after one step and rise to it monotonically.  The start is the linear
    interpolation of the force table ``table_x`` [m], ``table_f`` [N] (ascending; it lies
    above the convex force curve), or the all-linear force, below the root, outside the
    table or when it is empty.  Each point's start depends on its compression alone, so a
    result does not depend on the other points (sweeps chunked differently agree bit for
    bit); a compression equal to its predecessor's (the base circle) repeats its force.
    Used for the static force along a cam; the tests check it against the NumPy
    implementation.
    """
    n_el = laws.shape[0]
    k_lin = 0.0
    for j in range(n_el):
        k_lin += 1.0 / laws[j, 0, 2]
    k_lin = 1.0 / k_lin
    nt = table_x.shape[0]
    for i in range(total_compression.shape[0]):
        dl = total_compression[i]
        if i > 0 and dl == total_compression[i - 1]:
            out[i] = out[i - 1]
            continue
        force = dl * k_lin
        if nt > 1 and table_x[0] <= dl < table_x[nt - 1]:
            lo = 0  # bisection for table_x[lo] <= dl < table_x[lo + 1] (np.searchsorted
            hi = nt - 1  # costs a quarter of this kernel's compilation)
            while hi - lo > 1:
                mid = (lo + hi) // 2
                if table_x[mid] <= dl:
                    lo = mid
                else:
                    hi = mid
            k = lo
            w = (dl - table_x[k]) / (table_x[k + 1] - table_x[k])
            force = table_f[k] + w * (table_f[k + 1] - table_f[k])
        for _ in range(100):
            total = 0.0
            comp = 0.0
            for j in range(n_el):
                seg = 0
                for s in range(1, laws.shape[1]):
                    xs = laws[j, s, 0]
                    if xs < np.inf:
                        fs = (laws[j, s, 1] * xs + laws[j, s, 2]) * xs + laws[j, s, 3]
                        if force >= fs:
                            seg = s
                a = laws[j, seg, 1]
                b = laws[j, seg, 2]
                d = force - laws[j, seg, 3]
                x = 2.0 * d / (b + np.sqrt(max(b * b + 4.0 * a * d, 0.0)))
                total += x
                comp += 1.0 / (2.0 * a * x + b)
            step = (dl - total) / comp
            force += step
            if abs(step) <= 1e-12 * abs(force) + 1e-300:
                break
        out[i] = force
