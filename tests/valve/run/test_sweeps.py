"""Speed sweeps: consistency with single runs, parallel = serial = Dask, design
variables, outputs and bad input."""

import csv
import math

import numpy as np
import pytest

from springdyn.app.cli.main import main
from springdyn.core.errors import InputError
from springdyn.valve import ValveSpring
from springdyn.valve.cam.definition import Cam
from springdyn.valve.run.simulation import simulate
from springdyn.valve.run.sweeps import connect, sweep
from springdyn.valve.train.definition import ValveTrain
from tests.paths import EXAMPLES

CAM = Cam(law="3-4-5", lift=9e-3, duration=math.radians(120))
VT = ValveTrain(valve_mass=0.045, retainer_mass=0.010, follower_mass=0.035)
SPEEDS = np.array([800.0, 1900.0, 3000.0, 3700.0])
EX = EXAMPLES / "valve"


@pytest.fixture(scope="module")
def spring():
    return ValveSpring.example("one-step")


@pytest.fixture(scope="module")
def local(spring):
    return sweep(spring, CAM, SPEEDS, valve_train=VT, points_per_revolution=360)


def test_sweep_matches_single_simulations(spring):
    """With a given number of revolutions from rest, the sweep's in-kernel force evaluation
    equals simulate()'s (same engine, same steps: agreement to round-off, 1e-9 relative)."""
    local = sweep(spring, CAM, SPEEDS, revolutions=2, valve_train=VT, points_per_revolution=360)
    for i, rpm in enumerate(SPEEDS):
        sim = simulate(spring, CAM, rpm, 2, valve_train=VT, points_per_revolution=360)
        np.testing.assert_allclose(local.data["retainer"][0, i], sim.retainer_force, rtol=1e-9)
        np.testing.assert_allclose(local.data["seat"][0, i], sim.seat_force, rtol=1e-9)
        np.testing.assert_allclose(local.data["cam_contact"][0, i], sim.cam_contact_force, rtol=1e-9, atol=1e-6)
        s = sim.summary
        row = local.summary_table()
        assert row["max_retainer_force_N"][i] == pytest.approx(s["max_retainer_force_N"], rel=1e-9)
        assert bool(row["liftoff"][i]) == bool(s["liftoff"])
        assert local.data["periodicity"][0, i] == pytest.approx(sim.periodicity_error, rel=1e-6, abs=1e-12)


def test_periodic_sweep_agrees_with_single_simulations(spring, local):
    """To the periodic steady state, a sweep continues each speed from the slower one before
    it and simulate() starts from rest: both settle to the same periodic state, so their
    extremes agree within the periodicity tolerance (0.2 % of Fset)."""
    fset = spring.spring_model.internal_parameters()["Fset"]
    row = local.summary_table()
    for i, rpm in enumerate(SPEEDS[:2]):  # below float (3000 and 3700 cam rpm float and bounce)
        sim = simulate(spring, CAM, rpm, valve_train=VT, points_per_revolution=360)
        s = sim.summary
        assert sim.periodic and row["periodic"][i]
        for key in ("max_retainer_force_N", "min_retainer_force_N", "max_seat_force_N", "min_seat_force_N"):
            assert abs(row[key][i] - s[key]) <= 0.002 * fset, (rpm, key)


def test_threads_and_serial_identical(spring, local):
    serial = sweep(spring, CAM, SPEEDS, valve_train=VT, points_per_revolution=360, workers=1)
    for key in local.data:
        np.testing.assert_array_equal(serial.data[key], local.data[key])


# in the fast tier (some 10 s), so that every run exercises the dask extra on a real cluster
def test_dask_local_cluster_bit_for_bit(spring, local, tmp_path):
    """A LocalCluster on loopback (2 worker processes) gives exactly the local results."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    ) as cluster:
        with distributed.Client(cluster) as client:
            remote = sweep(spring, CAM, SPEEDS, valve_train=VT, points_per_revolution=360, client=client)
        address = cluster.scheduler_address
        for key in local.data:
            np.testing.assert_array_equal(remote.data[key], local.data[key])
        # and through the CLI with --scheduler, with no client of the test's open: the CLI's own
        # client is no process default (the README's --scheduler sweep failed so, issue 39)
        code = main(
            [
                "valve",
                "sweep",
                str(EX / "one_step_spring.toml"),
                "--cam",
                str(EX / "cam_345.toml"),
                "--cam-rpm",
                "1000,3000",
                "--scheduler",
                address,
                "--out",
                str(tmp_path),
                "--quiet",
            ]
        )
        assert code == 0 and (tmp_path / "sweep.nc").exists()
    import dask  # the clients are gone and none stays the default (later xarray work runs locally)

    assert dask.config.get("scheduler", None) != "dask.distributed"


def test_float_speed_from_sweep(local):
    f = local.float_speeds()
    assert f.shape == (1,) and f[0] in (3000.0, 3700.0)
    assert not local.summary_table()["liftoff"][0]


def test_vary_adds_a_dimension_and_skips_invalid(spring):
    with pytest.warns(UserWarning, match="installed_length = 20 mm skipped"):
        res = sweep(
            spring,
            CAM,
            [1000.0, 2000.0],
            vary=("installed_length", np.array([0.020, 0.037, 0.039])),
            on_invalid="skip",
            points_per_revolution=180,
        )
    ds = res.to_xarray()
    assert ds["retainer_force"].dims == ("vary", "cam_rpm", "cam_angle")
    np.testing.assert_allclose(ds["vary"].values, [0.037, 0.039])
    assert res.skipped and res.skipped[0][0] == 0.020
    # a longer installed length gives a smaller set-up force: static min follows Fset
    fset = [s.spring_model.internal_parameters()["Fset"] for s in res.springs]
    np.testing.assert_allclose(ds["min_static_force_N"].values[:, 0], fset, rtol=1e-12)
    with pytest.raises(InputError, match=r"vary: installed_length = 20 mm is at or below"):  # named once
        sweep(spring, CAM, [1000.0], vary=("installed_length", np.array([0.020])))
    with pytest.raises(InputError, match=r"vary = 'colour': not a numeric spring field"):
        sweep(spring, CAM, [1000.0], vary=("colour", np.array([1.0])))


def test_outputs(tmp_path, local):
    written = local.write(tmp_path)
    names = {p.name for p in written}
    assert {
        "sweep.nc",
        "sweep_summary.csv",
        "sweep_forces.png",
        "sweep_map.png",
        "sweep_campbell.png",
        "sweep_contact.png",
    } <= names
    import xarray as xr

    with xr.open_dataset(tmp_path / "sweep.nc") as ds:
        assert ds["retainer_force"].dims == ("cam_rpm", "cam_angle")
        np.testing.assert_array_equal(ds["retainer_force"].values, local.data["retainer"][0])
    rows = list(csv.DictReader(open(tmp_path / "sweep_summary.csv")))
    assert len(rows) == SPEEDS.size
    assert {
        "cam_rpm",
        "max_retainer_force_N",
        "min_retainer_force_N",
        "retainer_surge_amplitude_N",
        "coil_contact",
        "liftoff",
    } <= set(rows[0])


@pytest.mark.parametrize(
    "speeds,pattern",
    [
        ([], "cam_rpm is empty"),
        ([1000.0, -5.0], "cam_rpm = -5 must be positive"),
        ([0.0], "cam_rpm = 0 must be positive"),
    ],
)
def test_bad_speeds(spring, speeds, pattern):
    with pytest.raises(InputError, match=pattern):
        sweep(spring, CAM, speeds)


def test_unreachable_scheduler_fails_fast():
    import time

    t = time.monotonic()
    with pytest.raises(
        InputError, match=r"scheduler = 'tcp://127.0.0.1:9': cannot reach a Dask scheduler there \(Connection refused\)"
    ):
        connect("tcp://127.0.0.1:9", timeout=1.0)
    assert time.monotonic() - t < 10


def _server(reply):
    """A local TCP server on a free port that answers each connection with ``reply`` (None:
    accepts and says nothing); returns its address and a function that stops it."""
    import socket
    import threading

    listener = socket.socket()
    listener.bind(("127.0.0.1", 0))
    listener.listen()
    listener.settimeout(0.1)
    stop, held = threading.Event(), []

    def serve():
        while not stop.is_set():
            try:
                conn, _ = listener.accept()
            except OSError:
                continue
            held.append(conn)
            if reply is not None:
                conn.sendall(reply)

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()

    def close():
        stop.set()
        thread.join()
        for c in held:
            c.close()
        listener.close()

    return f"tcp://127.0.0.1:{listener.getsockname()[1]}", close


@pytest.mark.parametrize(
    "reply, words",
    [
        (
            b"HTTP/1.1 400 Bad Request\r\n\r\n",
            "is not a Dask scheduler (it sent 'HTTP/1.1 400 Bad Request', not a Dask",
        ),
        (
            b"\xff" * 64,
            "is not a Dask scheduler (it sent the bytes ff ff ff ff ff ff ff ff ff ff ff ff ff ff ff ff, not",
        ),  # dask read this as a 3 EiB message (exit 70)
        (None, "something listens there but sent no Dask greeting within 1 s"),  # dask waited for ever
    ],
    ids=["http", "garbage", "silent"],
)
def test_a_port_that_is_not_a_dask_scheduler_is_refused_within_the_timeout(reply, words):
    """Issue 40: --scheduler at a port that is not a Dask scheduler's allocated 3 EiB (exit 70)
    or hung.  The address is probed first: what answers must greet as a Dask scheduler does
    (its handshake) within the timeout; anything else is refused naming the address and what
    is expected, within about the timeout."""
    import time

    address, close = _server(reply)
    try:
        t = time.monotonic()
        with pytest.raises(InputError) as caught:
            connect(address, timeout=1.0)
        assert time.monotonic() - t < 3.0
    finally:
        close()
    text = str(caught.value)
    assert text.startswith(f"scheduler = {address!r}: ") and words in text
    assert text.endswith(
        "expected a Dask scheduler's address, e.g. tcp://127.0.0.1:8786 (the one `dask scheduler` prints)"
    )


def test_the_cli_refuses_a_port_that_is_not_a_dask_scheduler(capsys):
    """The same through ``valve sweep --scheduler``: exit 2, one line naming --scheduler."""
    address, close = _server(b"SSH-2.0-OpenSSH_9.6\r\n")
    try:
        args = [
            "valve",
            "sweep",
            str(EX / "one_step_spring.toml"),
            "--cam",
            str(EX / "cam_345.toml"),
            "--cam-rpm",
            "1000,2000",
        ]
        code = main([*args, "--scheduler", address])
    finally:
        close()
    err = capsys.readouterr().err
    assert code == 2
    assert err.startswith(f"springdyn: error: --scheduler = {address!r}: what answers there is not a Dask scheduler")
    assert "SSH-2.0-OpenSSH_9.6" in err and "Traceback" not in err and err.count("\n") == 1


def test_a_dask_scheduler_passes_the_probe():
    """A real scheduler (in this process, no workers) greets as the probe expects."""
    from dask.distributed import LocalCluster

    with LocalCluster(n_workers=0, processes=False, dashboard_address=None) as cluster:
        client = connect(cluster.scheduler_address, timeout=5.0)
        client.close()


def test_cli_sweep(capsys, tmp_path):
    code = main(
        [
            "valve",
            "sweep",
            str(EX / "one_step_spring.toml"),
            "--cam",
            str(EX / "cam_345.toml"),
            "--engine-rpm",
            "2000:6000:2000",
            "--vary",
            "installed_length=37mm:39mm:1mm",
            "--out",
            str(tmp_path),
            "--points-per-revolution",
            "180",
            "--quiet",
        ]
    )
    out, err = capsys.readouterr()
    assert code == 0, err
    assert "swept 3 speeds (1000-3000 cam rpm, 2000-6000 engine rpm) x 3 values of installed_length" in out
    assert (tmp_path / "sweep.nc").exists() and (tmp_path / "sweep_map_2.png").exists()
    code = main(
        [
            "valve",
            "sweep",
            str(EX / "one_step_spring.toml"),
            "--cam",
            str(EX / "cam_345.toml"),
            "--cam-rpm",
            "3000:1000:100",
            "--out",
            str(tmp_path),
        ]
    )
    assert code == 2 and "is empty" in capsys.readouterr().err
