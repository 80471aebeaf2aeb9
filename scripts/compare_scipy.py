#!/usr/bin/env python3
"""Side-by-side timing of the simulator from Python (`reentry.fly`, `reentry.fly_summary`)
and SciPy's DOP853 on the same equations: the planar case.

Not part of CI. Setup (once, from the repository root; the package compiles for minutes):

    python3 -m venv .venv && .venv/bin/pip install scipy numpy ./python

Run:

    .venv/bin/python scripts/compare_scipy.py                    # 200 repeats, 5 rounds
    .venv/bin/python scripts/compare_scipy.py --repeats 50 --rounds 3
    .venv/bin/python scripts/compare_scipy.py --profile          # + the native call alone
    .venv/bin/python scripts/compare_scipy.py --write-scenario planar.toml   # the case as a file

The planar case: the SRM capsule (trim C_L = 1.2786, L/D = 2.27, host-sim/src/vehicle/srm.rs),
non-rotating spherical Earth, central gravity, exponential atmosphere, Chapman heat flux; from
100 km at 5 km/s and -3 deg on the equator heading east, bank 0 (lift up: the flight stays in
the equatorial plane), guidance clock 2 s, rtol 1e-8, until 25 km altitude. Both sides read
the same constants from the scenario dict below.

SciPy integrates the same Cartesian inertial equations as host-sim (position, velocity, heat
load, flown range; `Dynamics::cartesian_derivative`) in the orbit plane, with
`solve_ivp(method="DOP853", rtol=1e-8)` and host-sim's absolute tolerances
(`sim::state_atol`), two ways:

* "clocked": one `solve_ivp` per 2 s guidance tick, as a Python guidance loop flies it (the
  command is held over a tick and may change at the next);
* "one call": a single `solve_ivp` over the whole flight, which is only possible because this
  case's command never changes (SciPy's best case; not a closed loop).

Times are CPU times (`time.process_time`) of one flight: the median over `--rounds` rounds of
the mean over `--repeats` flights each, all in this one process. Printed: the times, the
ratios SciPy / ours, the right-hand-side evaluations of each, and the final states' agreement.
"""

import argparse
import json
import math
import os
import statistics
import time

import numpy as np
from scipy.integrate import solve_ivp

import reentry

MU = 3.986004418e14
RADIUS = 6378137.0
RHO0, SCALE_H = 1.225, 7200.0
C_STAR, RHO_REF, V_REF, M_EXP = 1.1097e8, 1.225, 7905.4, 3.15
# The SRM capsule (host-sim/src/vehicle/srm.rs).
MASS, AREA, NOSE = 38.77, 0.441, 0.90
CL = 1.2786
CD = CL / 2.27
RTOL = 1e-8
PERIOD = 2.0
H_END = 25e3

SCENARIO = {
    "name": "planar-srm",
    "vehicle": "srm",
    "environment": {
        "atmosphere": "exponential",
        "gravity": "central",
        "rotating": False,
        "planet": {"radius_m": RADIUS, "mu_m3_s2": MU, "j2": 0.0, "rotation_rate_rad_s": 0.0},
        "exponential": {"rho0_kg_m3": RHO0, "scale_height_m": SCALE_H},
    },
    "heat_flux": {
        "coefficient": C_STAR,
        "reference_density_kg_m3": RHO_REF,
        "reference_speed_m_s": V_REF,
        "speed_exponent": M_EXP,
        "nose_radius_m": NOSE,
    },
    "entry": {
        "altitude_km": 100.0,
        "longitude_deg": 0.0,
        "latitude_deg": 0.0,
        "speed_m_s": 5000.0,
        "flight_path_angle_deg": -3.0,
        "heading_deg": 90.0,
    },
    "guidance": {
        "independent": "time",
        "interpolation": "linear",
        "period_s": PERIOD,
        "alpha_rate_deg_s": 5.0,
        "sigma_rate_deg_s": 15.0,
        "initial_alpha_deg": 0.0,
        "initial_sigma_deg": 0.0,
        "nodes": [[0.0, 0.0, 0.0], [5000.0, 0.0, 0.0]],
    },
    "termination": {"altitude_km": H_END / 1e3, "max_time_s": 5000.0},
    "integrator": {"rtol": RTOL},
    "output": {"interval_s": 0.0},
}

# host-sim's absolute tolerances (sim::state_atol) for [x, z, vx, vz, heat load, range].
ATOL = [1e6 * RTOL, 1e6 * RTOL, 1e3 * RTOL, 1e3 * RTOL, 1e9 * RTOL, RTOL]
Q_K = C_STAR / math.sqrt(NOSE) / math.sqrt(RHO_REF)
K_AERO = 0.5 * AREA / MASS


class Rhs:
    """The planar Cartesian equations; counts its evaluations."""

    def __init__(self):
        self.evals = 0

    def __call__(self, t, y):
        self.evals += 1
        x, z, vx, vz = y[0], y[1], y[2], y[3]
        r = math.hypot(x, z)
        rx, rz = x / r, z / r
        g = -MU / (r * r)
        ax, az = g * rx, g * rz
        v = math.hypot(vx, vz)
        rho = RHO0 * math.exp(-(r - RADIUS) / SCALE_H)
        kq = K_AERO * rho * v * v
        ux, uz = vx / v, vz / v
        # Lift perpendicular to the velocity, towards the local vertical (bank 0).
        d = rx * ux + rz * uz
        ex, ez = rx - d * ux, rz - d * uz
        en = math.hypot(ex, ez)
        ex, ez = ex / en, ez / en
        ax += kq * (CL * ex - CD * ux)
        az += kq * (CL * ez - CD * uz)
        q = Q_K * math.sqrt(rho) * (v / V_REF) ** M_EXP
        # Horizontal speed over r (flown range rate).
        hx, hz = vx - d * v * rx, vz - d * v * rz
        return [vx, vz, ax, az, q, math.hypot(hx, hz) / r]


def altitude_event(t, y):
    return math.hypot(y[0], y[1]) - RADIUS - H_END


altitude_event.terminal = True
altitude_event.direction = -1


def initial_state():
    e = SCENARIO["entry"]
    r = RADIUS + e["altitude_km"] * 1e3
    v, gam = e["speed_m_s"], math.radians(e["flight_path_angle_deg"])
    # x along the entry radius, z along the horizontal direction of flight (east).
    return [r, 0.0, v * math.sin(gam), v * math.cos(gam), 0.0, 0.0]


def scipy_clocked():
    rhs = Rhs()
    t, y = 0.0, initial_state()
    while True:
        sol = solve_ivp(rhs, (t, t + PERIOD), y, method="DOP853", rtol=RTOL, atol=ATOL,
                        events=altitude_event)
        if sol.status == 1:
            return sol.t_events[0][0], sol.y_events[0][0], rhs.evals
        t, y = sol.t[-1], sol.y[:, -1]


def scipy_one_call():
    rhs = Rhs()
    sol = solve_ivp(rhs, (0.0, 5000.0), initial_state(), method="DOP853", rtol=RTOL,
                    atol=ATOL, events=altitude_event)
    return sol.t_events[0][0], sol.y_events[0][0], rhs.evals


def cpu_per_call(f, repeats, rounds):
    f()
    means = []
    for _ in range(rounds):
        c0 = time.process_time()
        for _ in range(repeats):
            f()
        means.append((time.process_time() - c0) / repeats)
    return statistics.median(means), min(means)


def speed_of(y):
    return math.hypot(y[2], y[3])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=200)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--profile", action="store_true",
                    help="also time the native call alone and the Python layer's conversion")
    ap.add_argument("--write-scenario", metavar="FILE",
                    help="write the planar case as a scenario file (for host-sim) and exit")
    a = ap.parse_args()
    # TOML text once, so that the timed calls do not convert the dict each time.
    toml_text = reentry.flight._native.json_to_toml(json.dumps(SCENARIO))
    if a.write_scenario:
        with open(a.write_scenario, "w") as f:
            f.write(toml_text)
        return

    flight = reentry.fly(toml_text)
    s = flight.summary
    ticks, v_end = s["guidance_ticks"], s["final_state"]["speed_m_s"]
    heat = s["heat_load_mj_m2"] * 1e6
    t_sp, y_sp, ev_sp = scipy_clocked()
    t_1, y_1, ev_1 = scipy_one_call()
    print(f"load average {os.getloadavg()[0]:.2f} (1 min), {os.cpu_count()} CPUs")
    print(f"planar case: {s['termination']} after {s['flight_time_s']:.6f} s, "
          f"{ticks} ticks, {len(flight)} samples")
    print(f"  host-sim: V_end {v_end:.9f} m/s, heat load "
          f"{heat:.9e} J/m^2, {s['rhs_evals']} RHS evaluations "
          f"({s['rhs_evals'] / ticks:.2f} per tick), {s['accepted_steps']} steps")
    for name, (t_e, y_e, ev) in (("clocked", (t_sp, y_sp, ev_sp)), ("one call", (t_1, y_1, ev_1))):
        print(f"  SciPy {name}: t_end {t_e:.6f} s, V_end {speed_of(y_e):.9f} m/s, heat load "
              f"{y_e[4]:.9e} J/m^2, {ev} RHS evaluations; "
              f"dV = {speed_of(y_e) - v_end:+.2e} m/s, "
              f"dt = {t_e - s['flight_time_s']:+.2e} s, "
              f"heat load rel {(y_e[4] - heat) / heat:+.1e}")

    rows = [
        ("reentry.fly", lambda: reentry.fly(toml_text)),
        ("reentry.fly_summary", lambda: reentry.fly_summary(toml_text)),
        ("SciPy DOP853 clocked", scipy_clocked),
        ("SciPy DOP853 one call", scipy_one_call),
    ]
    if a.profile:
        nat = reentry.flight._native
        rows.insert(2, ("native fly_scenario", lambda: nat.fly_scenario(toml=toml_text)))
        rows.insert(3, ("native, summary_only",
                        lambda: nat.fly_scenario(toml=toml_text, summary_only=True)))
    times = {}
    for name, f in rows:
        times[name] = cpu_per_call(f, a.repeats if "SciPy" not in name else max(1, a.repeats // 20),
                                   a.rounds)
    print(f"CPU time per flight, median (min) of {a.rounds} rounds:")
    for name, (med, mn) in times.items():
        print(f"  {name:24s} {med * 1e3:8.3f} ms ({mn * 1e3:.3f})")
    for ours in ("reentry.fly", "reentry.fly_summary"):
        for peer in ("SciPy DOP853 clocked", "SciPy DOP853 one call"):
            print(f"  {peer} / {ours}: {times[peer][0] / times[ours][0]:.1f}x")
    fly_t, sum_t = times["reentry.fly"][0], times["reentry.fly_summary"][0]
    print(f"  trajectory conversion (fly - fly_summary): {(fly_t - sum_t) * 1e3:.3f} ms, "
          f"{(fly_t - sum_t) / fly_t * 100:.0f} % of fly")


if __name__ == "__main__":
    main()
