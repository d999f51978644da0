"""Element force laws: the document's 3x3 systems, C1 continuity, monotonicity, inverse."""

import numpy as np
import pytest

from springdyn.valve import ValveSpring
from springdyn.valve.spring.elements import (
    damping_coefficient,
    law_compression,
    law_force,
    law_stiffness,
    quadratic_through,
)

SPRINGS = ["one-step", "two-step"]


def test_quadratic_matches_document_matrix():
    """quadratic_through is the solution of the document's system
    [[x0^2, x0, 1], [x1^2, x1, 1], [2 x0, 1, 0]] (a, b, c) = (F0, F1, k0)."""
    x0, x1, f0, f1, k0 = 4.96e-3, 6.23e-3, 400.6, 518.2, 80744.0
    a, b, c = quadratic_through(x0, f0, k0, x1, f1)
    m = np.array([[x0**2, x0, 1], [x1**2, x1, 1], [2 * x0, 1, 0]])
    ref = np.linalg.solve(m, [f0, f1, k0])
    # the matrix is ill-conditioned (cond ~1e9), so compare the resulting forces/slopes
    xs = np.linspace(x0, x1, 7)
    np.testing.assert_allclose(a * xs**2 + b * xs + c, ref[0] * xs**2 + ref[1] * xs + ref[2], rtol=1e-6)
    assert a * x1**2 + b * x1 + c == pytest.approx(f1, rel=1e-12)
    assert 2 * a * x0 + b == pytest.approx(k0, rel=1e-12)


def _breakpoints(spring, j):
    law = spring.spring_model.chain.laws[j]
    return [x for x in law[1:, 0] if np.isfinite(x)]


@pytest.mark.parametrize("name", SPRINGS)
def test_c1_continuity_at_every_breakpoint(name):
    """Force and slope continuous at each breakpoint: compare both one-sided limits
    evaluated 1e-12 m either side (slope error ~ 2a*h, force error ~ k*h)."""
    s = ValveSpring.example(name)
    for j, law in enumerate(s.spring_model.chain.laws):
        for xb in _breakpoints(s, j):
            h = 1e-12
            fl, fr = law_force(xb - h, law), law_force(xb + h, law)
            kl, kr = law_stiffness(xb - h, law), law_stiffness(xb + h, law)
            assert fr - fl == pytest.approx(0.0, abs=2 * h * kr * 1.01 + 1e-9)
            assert kr == pytest.approx(kl, rel=1e-6)
            # and exactly at the breakpoint, the segment formulas agree to round-off
            s_lo = law[np.searchsorted(law[:, 0], xb) - 1]
            s_hi = law[np.searchsorted(law[:, 0], xb)]
            f_lo = s_lo[1] * xb**2 + s_lo[2] * xb + s_lo[3]
            f_hi = s_hi[1] * xb**2 + s_hi[2] * xb + s_hi[3]
            assert f_hi == pytest.approx(f_lo, rel=1e-11)
            assert 2 * s_hi[1] * xb + s_hi[2] == pytest.approx(2 * s_lo[1] * xb + s_lo[2], rel=1e-11)


@pytest.mark.parametrize("name", SPRINGS)
def test_breakpoint_forces_are_the_document_ones(name):
    s = ValveSpring.example(name)
    p, bp = s.spring_model.internal_parameters(), s.spring_model.breakpoints()
    laws = dict(zip(s.spring_model.chain.element_names, s.spring_model.chain.laws))
    for k, tag in (("Kh1", "1"), ("Kh2", "2")):
        law = laws[k]
        assert law_force(bp[f"x{tag}1"], law) == pytest.approx(p["F1"], rel=1e-12)
        assert law_force(bp[f"x{tag}2"], law) == pytest.approx(p["F2"], rel=1e-12)
        assert law_force(bp[f"x{tag}3"], law) == pytest.approx(p["Fcon"], rel=1e-12)
        assert law_force(bp[f"x{tag}4"], law) == pytest.approx(2 * p["Fcon"], rel=1e-12)
        assert bp[f"x{tag}4"] - bp[f"x{tag}3"] == pytest.approx(p["Pc"] / 10, rel=1e-12)
        # the first quadratic's secant from x?1 to x?2 is the stiffened rate Kh'
        secant = (p["F2"] - p["F1"]) / (bp[f"x{tag}2"] - bp[f"x{tag}1"])
        assert secant == pytest.approx(bp[f"{k}p"], rel=1e-12)
    if name == "two-step":
        law = laws["Ks"]
        assert law_force(bp["x1"], law) == pytest.approx(p["Fset"], rel=1e-12)
        assert law_force(bp["x2"], law) == pytest.approx(5 * p["Ks"] * bp["x2"], rel=1e-12)


@pytest.mark.parametrize("name", SPRINGS)
def test_force_monotonic_and_inverse(name):
    s = ValveSpring.example(name)
    x = np.linspace(-2e-3, 12e-3, 20001)
    for law in s.spring_model.chain.laws:
        f = law_force(x, law)
        assert np.all(np.diff(f) > 0)
        assert np.all(np.diff(law_stiffness(x, law)) >= -1e-6)  # stiffness never drops
        np.testing.assert_allclose(law_compression(f, law), x, rtol=1e-9, atol=1e-15)


def test_damping_law():
    """c(x) = C0 sqrt(k(x)/k(0)): C0 in the linear range, larger once the element stiffens."""
    s = ValveSpring.example("one-step")
    law = s.spring_model.chain.laws[1]
    c0 = s.spring_model.internal_parameters()["C0"]
    assert damping_coefficient(1e-4, law, c0) == pytest.approx(c0, rel=1e-15)
    x = 6.5e-3
    assert damping_coefficient(x, law, c0) == pytest.approx(c0 * np.sqrt(law_stiffness(x, law) / law[0, 2]), rel=1e-15)
    assert s.spring_model.internal_parameters()["C0"] == pytest.approx(
        2 * 0.05 * np.sqrt(s.spring_model.internal_parameters()["M"] * s.spring_model.internal_parameters()["K1"]),
        rel=1e-15,
    )


def test_the_engines_element_force_is_the_element_law_with_its_damping():
    """The compiled engine evaluates each element with equations.element_force; it must be
    law_force + damping_coefficient * rate of elements.py (the one law), and zero in tension
    for an end contact (MMS-7).  Tolerance: round-off (1e-12 relative)."""
    from springdyn.valve.engine.equations import element_force
    from springdyn.valve.spring.elements import damping_coefficient, law_force

    chain = ValveSpring.example("two-step").spring_model.chain
    c0 = chain.c0_array
    for j, law in enumerate(chain.laws):
        for x in np.linspace(-1e-3, 1.2 * law[2, 0] if np.isfinite(law[2, 0]) else 5e-3, 37):
            for rate in (-0.3, 0.0, 0.7):
                want = float(law_force(x, law)) + float(damping_coefficient(x, law, c0[j])) * rate
                got = element_force(chain.laws, c0, j, x, rate, False)
                assert got == pytest.approx(want, rel=1e-12, abs=1e-9)
                end = element_force(chain.laws, c0, j, x, rate, True)
                assert end == (0.0 if (x <= 0.0 or want < 0.0) else pytest.approx(want, rel=1e-12, abs=1e-9))


def test_laws_of_a_whole_chain_at_once_match_them_one_by_one():
    """Issue 42 (the statics of a synthesis): ``law_force``, ``law_stiffness`` and
    ``law_compression`` take the ``(E, S, 4)`` laws of a chain with the element as the first
    axis.  Reference: the same functions element by element (identical to round-off)."""
    import warnings

    from springdyn.valve import ValveSpring
    from springdyn.valve.spring.elements import law_compression, law_force, law_stiffness

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for model in ("type-c", "distributed"):
            laws = ValveSpring.example("two-step").with_model(model).spring_model.chain.laws
            x = np.linspace(-1e-4, 3e-3, 37)[None, :] * np.linspace(0.5, 1.5, laws.shape[0])[:, None]
            f = np.linspace(-10.0, 900.0, 37)
            for fn, arg in ((law_force, x), (law_stiffness, x)):
                one = np.stack([fn(arg[j], laws[j]) for j in range(laws.shape[0])])
                np.testing.assert_allclose(fn(arg, laws), one, rtol=1e-14, atol=0)
            fb = np.broadcast_to(f, (laws.shape[0], f.size))
            one = np.stack([law_compression(f, laws[j]) for j in range(laws.shape[0])])
            np.testing.assert_allclose(law_compression(fb, laws), one, rtol=1e-14, atol=1e-18)
