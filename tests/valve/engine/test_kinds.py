"""The kinds of valve train in the engine (issue 38 item 4): the equations choose by the kind code
``VT_KIND``, never by the degrees of freedom; each kind has its function, the compiled twin
agrees with it, and a code of no kind is refused (a new 6-dof train must not run as the bucket).

References: the plain-Python equations themselves (the compiled twins are compared with them)
and the layout's tables (TRAIN_KINDS, TRAIN_DOF).
"""

import math

import numpy as np
import pytest

from springdyn.valve import Cam, ValveSpring, ValveTrain
from springdyn.valve.engine import equations as eq
from springdyn.valve.engine import layout as L
from springdyn.valve.engine import loop
from springdyn.valve.run.runner import engine_args
from springdyn.valve.run.setup import prepare
from tests.paths import example

SPRING = ValveSpring.example("one-step")
#: The example cams lift close to these springs' solid length (said as a warning, not tested here).
pytestmark = pytest.mark.filterwarnings("ignore:coil bind")

#: One example of each kind: train file, cam file.
KINDS = {
    L.TRAIN_DIRECT: ("valve_train.toml", "cam_polydyne_ramps.toml"),
    L.TRAIN_LEVER: ("finger_follower_geometry.toml", "cam_finger.toml"),
    L.TRAIN_PUSHROD: ("pushrod.toml", "cam_pushrod.toml"),
    L.TRAIN_BUCKET_HLA: ("bucket_hla.toml", "cam_345.toml"),
    L.TRAIN_LEVER_HLA: ("finger_follower_hla.toml", "cam_finger.toml"),
}
#: The function of each kind, plain Python and NumPy.
RHS = {
    L.TRAIN_DIRECT: "direct_acting_rhs",
    L.TRAIN_LEVER: "lever_rhs",
    L.TRAIN_PUSHROD: "pushrod_rhs",
    L.TRAIN_BUCKET_HLA: "bucket_hla_rhs",
    L.TRAIN_LEVER_HLA: "lever_hla_rhs",
}
RESPONSE = {
    L.TRAIN_DIRECT: "direct_acting_response",
    L.TRAIN_LEVER: "lever_response",
    L.TRAIN_PUSHROD: "pushrod_response",
    L.TRAIN_BUCKET_HLA: "bucket_hla_response",
    L.TRAIN_LEVER_HLA: "lever_hla_response",
}


def _setup(kind):
    train, cam = KINDS[kind]
    return prepare(SPRING, Cam.from_toml(example(f"valve/{cam}")), ValveTrain.from_toml(example(f"valve/{train}")))


def _probe(setup, rng):
    """A state near the set-up's initial one, a time in the event and the engine's model."""
    omega = 2 * math.pi * 3000 / 60
    y = setup.y0 * (1.0 + rng.normal(0.0, 1e-3, setup.y0.size)) + rng.normal(0.0, 1e-7, setup.y0.size)
    t = rng.uniform(0.0, 2 * math.pi / omega)
    return t, y, eq.model_of(engine_args(setup, omega)), omega


def test_every_kind_has_its_function_and_dof():
    assert set(RHS) == set(L.TRAIN_KINDS) - {L.TRAIN_SPRING_ALONE} == set(eq.RESPONSES)
    for kind, name in RESPONSE.items():
        assert eq.RESPONSES[kind] is getattr(eq, name)
    assert L.TRAIN_DOF == {0: 0, 1: 1, 2: 2, 3: 3, 4: 6, 5: 7}


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_each_kind_dispatches_to_its_function(kind, monkeypatch):
    """train_rhs calls the kind's function and no other; train_response likewise."""
    setup = _setup(kind)
    assert setup.vt[L.VT_KIND] == kind
    called = []
    for name in RHS.values():
        real = getattr(eq, name)
        monkeypatch.setattr(eq, name, lambda *a, _n=name, _f=real: called.append(_n) or _f(*a))
    t, y, m, omega = _probe(setup, np.random.default_rng(kind))
    eq.chain_rhs(t, y, m, omega, eq.train_of(setup.vt), np.empty(y.size), eq.NO_EXTRA)
    assert called == [RHS[kind]]
    called.clear()
    for k, name in RESPONSE.items():
        real = eq.RESPONSES[k]
        monkeypatch.setitem(eq.RESPONSES, k, lambda *a, _n=name, _f=real: called.append(_n) or _f(*a))
    nm, nf = setup.n_masses, setup.nfree
    out = eq.train_response(setup.vt, np.zeros(1), np.zeros(1), y[nm:nf, None], y[nf + nm :, None], np.zeros(1), omega)
    assert called == [RESPONSE[kind]]
    assert list(out)[:3] == ["cam_contact_force", "valve_seat_force", "valve_lift"]
    assert ("hla_pressure" in out) == (kind in (L.TRAIN_BUCKET_HLA, L.TRAIN_LEVER_HLA))


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_compiled_twin_agrees_with_each_kinds_function(kind):
    """The compiled right-hand side (the kinds' functions inlined, the adjuster's called) and
    the plain-Python one: derivatives and extra outputs to round-off (fma, reciprocals)."""
    setup = _setup(kind)
    size = L.extra_layout(setup.n_masses)["size"]
    rng = np.random.default_rng(10 + kind)
    vt = eq.train_of(setup.vt)
    for _ in range(5):
        t, y, m, omega = _probe(setup, rng)
        a, b = np.empty(y.size), np.empty(y.size)
        ea, eb = np.empty(size), np.empty(size)
        eq.chain_rhs(t, y, m, omega, vt, a, ea)
        eq.rhs_call(t, y, m, omega, vt, b, eb)
        np.testing.assert_allclose(b, a, rtol=1e-9, atol=1e-9 * np.max(np.abs(a)))
        np.testing.assert_allclose(eb, ea, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("code", [6.0, 99.0, -1.0, 2.5, math.nan, 0.0])
def test_a_made_up_kind_is_refused_not_run_as_another(code):
    """A 6-dof train of a new kind (code 6, VT_DOF 6) once took the bucket's equations: now the
    kind code chooses, and a code of no kind (or an enabled train without one) is an error
    in Python (train_of, the plain equations, the NumPy twin) and in the compiled code."""
    setup = _setup(L.TRAIN_BUCKET_HLA)
    vt = setup.vt.copy()
    vt[L.VT_KIND] = code
    with pytest.raises(ValueError, match="no kind of valve train"):
        eq.train_of(vt)
    with pytest.raises(ValueError, match="no kind of valve train"):
        eq.train_response(vt, np.zeros(1), np.zeros(1), np.zeros((6, 1)), np.zeros((6, 1)))
    t, y, m, omega = _probe(setup, np.random.default_rng(3))
    if math.isfinite(code) and code == int(code):
        with pytest.raises(ValueError, match="no kind of valve train"):
            eq.chain_rhs(t, y, m, omega, vt, np.empty(y.size), eq.NO_EXTRA)
        with pytest.raises(ValueError, match="no kind of valve train"):
            eq.rhs_call(t, y, m, omega, vt, np.empty(y.size), eq.NO_EXTRA)


def test_the_dof_must_be_the_kinds():
    setup = _setup(L.TRAIN_LEVER)
    vt = setup.vt.copy()
    vt[L.VT_DOF] = 3.0
    with pytest.raises(ValueError, match="has 2 degrees of freedom"):
        eq.train_of(vt)


def test_the_engine_refuses_a_made_up_kind_before_it_runs():
    from springdyn.valve import engine

    setup = _setup(L.TRAIN_DIRECT)
    vt = setup.vt.copy()
    vt[L.VT_KIND] = 6.0
    args = (*engine_args(setup, 300.0)[:9], vt)
    with pytest.raises(ValueError, match="no kind of valve train"):
        engine.integrate(setup.y0, np.linspace(0.0, 1e-3, 3), args, rtol=1e-6, atol=1e-9, h_max=1e-4)


def test_the_extra_outputs_are_read_where_they_are_written():
    """The periodicity channel of an adjuster reads the slot ``extra_layout`` names ``hla_check``,
    the end forces the pack's totals, the monitor's lift-off channel the ``cam_gap``."""
    for n, chains in ((5, 1), (12, 1), (10, 2), (15, 3)):
        lay = L.extra_layout(n, chains)
        e = np.arange(lay["size"], dtype=float)
        row = np.empty(L.N_CHECK)
        loop.check_channels.py_func(e, n + chains, n, row)
        assert row[L.CHK_HLA] == lay["hla_check"]
        assert (row[L.CHK_SEAT], row[L.CHK_RETAINER]) == (lay["seat_total"], lay["retainer_total"])
        assert lay["size"] == lay["dissipation"] + 1
        assert [lay[k] for k in ("cam_gap", "hla_collapse", "hla_pressure", "socket_force")] == list(
            range(lay["cam_gap"], lay["cam_gap"] + 4)
        )


def test_the_variants_are_one_table():
    """Every pair and model has one row; the templates' unbound names say who binds them."""
    from springdyn.numerics import erk
    from springdyn.valve.engine import stepping

    models = ("spring", "train", "spring-pack", "train-pack")
    assert set(loop.VARIANTS) == {(p, m) for p in erk.TABLEAUS for m in models}
    hot = {
        "spring": eq.spring_rhs_hot,
        "train": eq.train_rhs_hot,
        "spring-pack": eq.spring_rhs_hot_pack,
        "train-pack": eq.train_rhs_hot_pack,
    }
    for (pair, model), v in loop.VARIANTS.items():
        assert v.step is getattr(stepping, f"{pair}_step") and v.dense is getattr(stepping, f"{pair}_dense")
        assert v.rhs is hot[model]
    with pytest.raises(RuntimeError, match="loop.VARIANTS"):
        loop.attempt_step(*[None] * 14)
    with pytest.raises(RuntimeError, match="loop.VARIANTS"):
        stepping.rhs_hot(*[None] * 7)
