"""The same sweep serially, through a Dask LocalCluster and in local processes gives identical tables."""

import math
import warnings
from dataclasses import dataclass

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson import sweeps

distributed = pytest.importorskip("distributed")

SPEEDS = np.array([1e-3, 1e-1, 10.0])


@dataclass(frozen=True)
class _Warns(persson.effects.Effect):
    """An effect that warns in the worker (adds no friction)."""

    def friction_term(self, state):
        warnings.warn(f"warned at {state.conditions.pressure:g} Pa", persson.ConvergenceWarning)


_Warns.name = "warns"  # set after creation: not registered in persson.effects.available()
PARAMS = {"pressure": [0.1e6, 0.4e6], "surface.hurst": [0.7, 0.85]}


@pytest.fixture(scope="module")
def model():
    s = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=0.35e-3, qL=2 * math.pi / 0.1)
    return persson.Model(s, materials.example_tread())


@pytest.fixture(scope="module")
def serial(model):
    return sweeps.bands(model, "decades", n=4, mode="both", params=PARAMS, speed=SPEEDS)


@pytest.fixture(scope="module")
def cluster():
    with distributed.LocalCluster(n_workers=1, processes=False, threads_per_worker=1, dashboard_address=None,
                                  silence_logs=50) as c:
        yield c


def test_dask_client_gives_the_serial_result_exactly(model, serial, cluster):
    with distributed.Client(cluster) as client:
        t = sweeps.bands(model, "decades", n=4, mode="both", params=PARAMS, speed=SPEEDS, scheduler=client)
    assert len(t) == len(serial) == 2 * 2 * SPEEDS.size * (1 + 4 + 4)
    assert t.equals(serial)
    assert any("dask client" in c for c in t.comments)


def test_dask_scheduler_address_gives_the_serial_result_exactly(model, serial, cluster):
    t = sweeps.bands(model, "decades", n=4, mode="both", params=PARAMS, speed=SPEEDS,
                     scheduler=cluster.scheduler_address)
    assert t.equals(serial)


def test_local_processes_give_the_serial_result_exactly(model, serial):
    t = sweeps.bands(model, "decades", n=4, mode="both", params=PARAMS, speed=SPEEDS, scheduler="processes",
                     workers=2)
    assert t.equals(serial)


def test_cli_sweep_on_a_dask_scheduler_writes_the_serial_csv(tmp_path, cluster, capsys):
    from persson.commands.cli import main

    (tmp_path / "case.toml").write_text('name = "dask-cli"\n[surface]\nexample = "road"\n'
                                        '[material]\nexample = "tread"\n[conditions]\nspeeds_m_s = [0.01, 1.0]\n')
    if not hasattr(surfaces, "example_road"):
        pytest.skip("surfaces.example_road not available yet")
    args = ["sweep", str(tmp_path / "case.toml"), "--bands", "decades", "--param", "pressure=0.1e6:0.9e6:3",
            "--no-progress"]
    assert main([*args, "-o", str(tmp_path / "serial.csv")]) == 0
    assert main([*args, "-o", str(tmp_path / "dask.csv"), "--scheduler", cluster.scheduler_address]) == 0
    assert sweeps.read_table(tmp_path / "dask.csv").equals(sweeps.read_table(tmp_path / "serial.csv"))
    assert "dask.csv" in capsys.readouterr().out


@pytest.mark.parametrize("where", ["serial", "dask"])
def test_worker_warnings_are_reissued_and_recorded(model, cluster, where):
    m = model.with_effect(_Warns())
    with distributed.Client(cluster) as client, warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        t = sweeps.grid(m, {"pressure": [1e5, 2e5]}, speed=1.0, scheduler=client if where == "dask" else None)
    assert sorted(str(w.message) for w in caught if w.category is persson.ConvergenceWarning) == [
        "sweep point 0, T = 20 C, p = 100000 Pa: warned at 100000 Pa",
        "sweep point 1, T = 20 C, p = 200000 Pa: warned at 200000 Pa"]
    assert [c for c in t.comments if c.startswith("warning:") and "warned at" in c] == ["warning: warned at 100000 Pa",
                                                                    "warning: warned at 200000 Pa"]
