"""Property-based tests of the input boundary, seeded and bounded.

For any input: either a valid result with finite outputs, or an :class:`InputError` (a
``ValueError``) with a one-line message that names the key or option.  Hypothesis is
derandomised (the same examples every run) and each test has a fixed example budget, so
the whole file takes well under a minute on 2 cores.
"""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from springdyn.app.cli.common import parse_range
from springdyn.core.errors import InputError
from springdyn.core.units import to_si
from tests.paths import ROOT

SETTINGS = settings(
    max_examples=150,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)

UNITS = ["", " mm", "mm", " m", " um", " kg", " GPa", " rpm", " Hz", " %", " N", " deg", " cSt", " furlong", " s"]
numbers = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(min_value=-(10**30), max_value=10**30),
    st.sampled_from([0, -1, 5e-324, 1e-300, 1e300, 10**400]),
)
texts = st.one_of(
    st.text(max_size=30),
    st.builds(lambda x, u: f"{x!r}{u}", st.floats(allow_nan=True, allow_infinity=True), st.sampled_from(UNITS)),
    st.builds(lambda a, b: f"{a},{b}", st.integers(), st.integers()),
    st.builds(lambda a, b, c: f"{a}:{b}:{c}", st.integers(-10, 5000), st.integers(-10, 5000), st.integers(-5, 500)),
)
values = st.one_of(
    numbers,
    texts,
    st.booleans(),
    st.none(),
    st.lists(st.integers(), max_size=3),
    st.dictionaries(st.text(max_size=3), st.integers(), max_size=2),
)


def _one_line_naming(exc: Exception, name: str) -> None:
    text = str(exc)
    assert "\n" not in text, f"message of several lines: {text!r}"
    assert name in text, f"message does not name {name!r}: {text!r}"


@SETTINGS
@given(value=values, unit=st.sampled_from(["m", "", "rad/s", "rpm", "Pa", "N/m", "kg/m^3", "Hz"]))
def test_to_si_is_finite_or_names_the_field(value, unit):
    try:
        out = to_si(value, unit, "the_field")
    except InputError as exc:
        _one_line_naming(exc, "the_field")
    else:
        assert isinstance(out, float) and math.isfinite(out)


@SETTINGS
@given(text=texts)
def test_parse_range_is_finite_or_names_the_option(text):
    try:
        out = parse_range(text, "rad/s", "--cam-rpm", bare_unit="rpm")
    except InputError as exc:
        _one_line_naming(exc, "--cam-rpm")
    else:
        assert out.size >= 1 and np.all(np.isfinite(out))


def _table(path: Path, table: str) -> dict:
    doc = tomllib.loads(path.read_text(encoding="utf-8"))
    return doc[table]


def _valve(mapping):
    from springdyn.valve import ValveSpring

    s = ValveSpring.from_dict(mapping)
    p = s.spring_model.internal_parameters()
    f = float(s.spring_model.static_force(s.installed_length))
    return [*p.values(), f, *s.spring_model.modes(s.installed_length, 3)]


def _cam(mapping):
    from springdyn.valve import Cam

    c = Cam.from_dict(mapping)
    return [c.max_lift, *c.sampled(360)[0]]


def _cfcs(mapping):
    from springdyn.cfcs import CFCS, CFCSParams

    m = CFCS(CFCSParams.from_dict(mapping))
    return list(m.static().summary.values())


def _lsd(mapping):
    from springdyn.lsd import LSDModel, LSDParameters

    m = LSDModel(LSDParameters.from_dict(mapping))
    c = m.coefficients([1000.0], amplitude=20e-6)
    return [*np.ravel(c.K), *np.ravel(c.C)]


LOADERS = {
    "spring": (ROOT / "examples" / "valve" / "one_step_spring.toml", "spring", _valve),
    "cam": (ROOT / "examples" / "valve" / "cam_345.toml", "cam", _cam),
    "cfcs": (ROOT / "examples" / "cfcs" / "table1.toml", "cfcs", _cfcs),
    "lsd": (ROOT / "examples" / "lsd" / "type_c.toml", "lsd", _lsd),
}


def _finite(outputs) -> bool:
    flat = []
    for v in outputs:
        if isinstance(v, (list, tuple)):
            flat += list(v)
        else:
            flat.append(v)
    return all(math.isfinite(float(v)) for v in flat if isinstance(v, (int, float, np.floating)) and v is not None)


@pytest.mark.parametrize("table", sorted(LOADERS))
def test_definitions_with_one_key_mutated_are_valid_or_rejected_naming_the_key(table):
    path, section, evaluate = LOADERS[table]
    base = _table(path, section)
    keys = sorted(base) + ["an_unknown_key"]

    @SETTINGS
    @given(key=st.sampled_from(keys), value=values)
    def check(key, value):
        mapping = dict(base)
        mapping[key] = value
        try:
            outputs = evaluate(mapping)
        except InputError as exc:
            assert "\n" not in str(exc), str(exc)
            named = [k for k in keys if re.search(rf"\b{re.escape(k)}\b", str(exc))]
            assert named, f"{key} = {value!r}: the message names no key: {exc}"
        else:
            assert _finite(outputs), f"{key} = {value!r} gave a non-finite output"

    check()


@pytest.mark.parametrize("table", sorted(LOADERS))
def test_definitions_with_a_key_removed(table):
    path, section, evaluate = LOADERS[table]
    base = _table(path, section)
    for key in base:
        mapping = {k: v for k, v in base.items() if k != key}
        try:
            outputs = evaluate(mapping)
        except InputError as exc:
            assert "\n" not in str(exc) and key in str(exc), str(exc)
        else:
            assert _finite(outputs)
