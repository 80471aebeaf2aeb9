"""Flights, atmosphere and vehicles against the host-sim CLI's own output."""

import csv
import io
import json
from pathlib import Path

import numpy as np
import pytest

import reentry

REPO = Path(__file__).resolve().parents[2]
BETTS = REPO / "examples" / "betts-shuttle.toml"


def test_default_mission_summary_equals_host_sim_simulate_summary_json(host_sim, tmp_path):
    host_sim("simulate", "--quiet", "--out", tmp_path / "run")
    expected = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert reentry.fly().summary == expected
    assert reentry.fly_summary() == expected


def test_default_mission_trajectory_equals_trajectory_csv(host_sim, tmp_path):
    host_sim("simulate", "--quiet", "--out", tmp_path / "run")
    rows = list(csv.DictReader(io.StringIO((tmp_path / "run" / "trajectory.csv").read_text())))
    df = reentry.fly().to_dataframe()
    assert len(df) == len(rows)
    # The CSV prints 6 decimals (km, deg): compare within half a unit of the last digit.
    col = lambda name: np.array([float(r[name]) for r in rows])  # noqa: E731
    np.testing.assert_allclose(df["time_s"], col("time_s"), rtol=0, atol=5.1e-7)
    np.testing.assert_allclose(df["altitude_m"] / 1e3, col("altitude_km"), rtol=0, atol=5.1e-7)
    np.testing.assert_allclose(np.degrees(df["sigma_rad"]), col("sigma_deg"), rtol=0, atol=5.1e-7)
    np.testing.assert_allclose(df["speed_m_s"], col("speed_m_s"), rtol=0, atol=5.1e-7)
    assert list(df["event"]) == [r["event"] for r in rows]


def test_scenario_file_toml_text_and_dict_fly_like_host_sim(host_sim, tmp_path):
    host_sim("simulate", "--quiet", "--scenario", BETTS, "--out", tmp_path / "betts")
    expected = json.loads((tmp_path / "betts" / "summary.json").read_text())
    assert reentry.fly(BETTS).summary == expected
    assert reentry.fly(str(BETTS)).summary == expected
    text = BETTS.read_text()
    # TOML text and a dict of it: the vehicle file is relative to the scenario's folder.
    vehicle = str(REPO / "examples" / "betts-shuttle-vehicle.toml")
    text = text.replace('"betts-shuttle-vehicle.toml"', json.dumps(vehicle))
    assert reentry.fly(text).summary == expected
    import tomllib

    assert reentry.fly(tomllib.loads(text)).summary == expected


def test_builtin_and_its_scenario_dict(host_sim, tmp_path):
    host_sim("simulate", "--quiet", "--builtin", "srm-glide", "--out", tmp_path / "srm")
    expected = json.loads((tmp_path / "srm" / "summary.json").read_text())
    assert reentry.fly(builtin="srm-glide").summary == expected
    # The built-in's whole stack flies, as a campaign's nominal case in its fullest mode: the
    # same miss as `host-sim dispersions`' nominal record.
    target = expected["target"]
    assert target["mode"] == "replan-estimation" and target["reached_interface"]
    host_sim("dispersions", "--builtin", "srm-glide", "-n", "1", "--threads", "1", "--quiet",
             "--modes", "replan-estimation", "--out", tmp_path / "campaign")
    campaign = json.loads((tmp_path / "campaign" / "summary.json").read_text())
    (nominal,) = campaign["nominal"]
    assert target["miss_km"] == nominal["miss_m"] / 1e3
    assert (target["reversals"], target["replans"]) == (nominal["reversals"], nominal["replans"])
    stored = reentry.fly(builtin="horus-2b-stored").summary
    assert "target" not in stored
    assert set(reentry.builtin_scenarios()) == {"horus-2b-reference", "horus-2b-stored", "srm-glide"}
    assert reentry.scenario_toml() == host_sim("simulate", "--print-scenario").stdout


def test_dataframe_columns_and_units():
    fl = reentry.fly()
    df = fl.trajectory
    assert list(df.columns) == list(reentry.TRAJECTORY_COLUMNS) + ["event"]
    assert df["altitude_m"].iloc[0] == pytest.approx(122e3)
    assert df["event"].iloc[0] == "start" and df["event"].iloc[-1] == "end"
    assert all(v.dtype == np.float64 for v in fl.arrays.values())
    assert np.all(np.diff(df["time_s"]) > 0)


def test_errors_carry_host_sim_messages(host_sim, tmp_path):
    bad = tmp_path / "bad.toml"
    # A complete scenario (scenarios state what they fly) with one bad value.
    text = reentry.scenario_toml()
    assert "altitude_km = 122.0" in text
    bad.write_text(text.replace("altitude_km = 122.0", "altitude_km = -5.0", 1))
    cli = host_sim("simulate", "--scenario", bad, "--out", tmp_path / "x", check=False)
    assert cli.returncode != 0
    with pytest.raises(reentry.ScenarioError) as e:
        reentry.fly(bad)
    assert cli.stderr.strip() == f"error: {e.value}"
    assert "altitude_km" in str(e.value) and "-5" in str(e.value)
    with pytest.raises(reentry.ScenarioError, match="nonsense"):
        reentry.fly({"entry": {"nonsense": 1.0}})
    with pytest.raises(reentry.ScenarioError, match="no-such"):
        reentry.fly(builtin="no-such")
    assert issubclass(reentry.ScenarioError, reentry.ReentryError)


def test_atmosphere_equals_host_sim_atmosphere(host_sim):
    alts_km = [0, 11, 50, 86, 100]
    out = host_sim("atmosphere", *alts_km).stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    atm = reentry.atmosphere(np.array(alts_km) * 1e3)
    for k, r in enumerate(rows):
        assert atm["temperature_k"][k] == pytest.approx(float(r["temperature_k"]), abs=5e-5)
        assert atm["density_kg_m3"][k] == pytest.approx(float(r["density_kg_m3"]), rel=1e-6)
        assert atm["pressure_pa"][k] == pytest.approx(float(r["pressure_pa"]), rel=1e-6)
    exp = reentry.atmosphere(7200.0, model="exponential")
    assert exp["density_kg_m3"][0] == pytest.approx(1.225 / np.e, rel=1e-12)
    with pytest.raises(ValueError, match="unknown"):
        reentry.atmosphere(0.0, model="mars")
    with pytest.raises(ValueError, match="finite"):
        reentry.atmosphere(float("nan"))


def test_vehicles_equal_host_sim_vehicles(host_sim):
    rows = list(csv.DictReader(io.StringIO(host_sim("vehicles").stdout)))
    vs = reentry.vehicles()
    assert [v["name"] for v in vs] == [r["name"] for r in rows]
    for v, r in zip(vs, rows):
        assert v["mass_kg"] == float(r["mass_kg"])
        assert v["max_heat_flux_w_m2"] == pytest.approx(float(r["max_heat_flux_kw_m2"]) * 1e3)


STACK = REPO / "examples" / "horus-2b-stack.toml"

#: Every dispersion zero (host-sim/tests/it/stack_everywhere.rs flies the same settings).
_ZERO = "[dispersions]\ncases = 1\nseed = 11\nimu_noise_m_s2 = 0.0\n" + "".join(
    f'{k} = {{ distribution = "normal", three_sigma = 0.0 }}\n'
    for k in (
        "altitude_km", "speed_m_s", "flight_path_angle_deg", "heading_deg", "latitude_deg",
        "longitude_deg", "density_bias", "density_wave", "lift", "drag", "mass",
        "imu_bias_m_s2", "imu_scale_factor",
    )
)


def test_the_one_stack_file_flies_in_python_as_in_simulate_and_a_one_case_campaign(host_sim, tmp_path):
    """Issue 19's one-file check, its Python leg: ``examples/horus-2b-stack.toml`` (every
    layer on) flown by ``reentry.fly`` is ``host-sim simulate --scenario``'s flight, and by a
    1-case ``DispersionCampaign`` with every dispersion zero it is ``host-sim dispersions``'
    record, whose nominal flight and undispersed case are the simulated flight."""
    host_sim("simulate", "--quiet", "--scenario", STACK, "--out", tmp_path / "sim")
    expected = json.loads((tmp_path / "sim" / "summary.json").read_text())
    flight = reentry.fly(STACK)
    assert flight.summary == expected
    target = expected["target"]
    assert target["mode"] == "replan-estimation" and target["reached_interface"]
    assert target["replans"] > 10 and target["reversals"] > 0
    end = flight.trajectory.iloc[-1]

    settings = tmp_path / "zero.toml"
    settings.write_text(_ZERO)
    campaign = reentry.DispersionCampaign(
        STACK, settings=settings, cases=1, modes=["replan-estimation"]
    )
    (text,) = campaign.run_local(threads=1)
    host_sim(
        "dispersions", "--scenario", STACK, "--settings", settings, "-n", "1", "--threads", "1",
        "--quiet", "--modes", "replan-estimation", "--out", tmp_path / "cli",
    )
    cli = json.loads((tmp_path / "cli" / "cases" / "replan-estimation" / "000000.json").read_text())
    case = json.loads(text)
    assert case == cli
    (nominal,) = json.loads((tmp_path / "cli" / "summary.json").read_text())["nominal"]
    # The undispersed case flies the nominal flight, which is simulate's, bit for bit.
    for record in (case, nominal):
        assert record["miss_m"] / 1e3 == target["miss_km"]
        assert (record["replans"], record["reversals"]) == (target["replans"], target["reversals"])
        assert record["final_speed_m_s"] == end["speed_m_s"]
        assert record["final_latitude_rad"] == end["latitude_rad"]
