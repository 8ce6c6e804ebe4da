"""The first hour of a new user, through the public API (run by .ci/newcomer).

A PhD student's three tasks, each checked by an independent route:

(a) a Poincare section of the paper's body coloured by MEGNO (regular orbits: MEGNO
    near 2; every section point on the plane);
(b) the splitting of the Hess separatrix (the branch theta1 = 0) of a body turned off
    the Hess direction, ``RigidBody.near_hess(2.5, 2, 2.2, mu=0.01, epsilon=0.1)``,
    against its Melnikov prediction;
(c) a rotation number by NAFF, against the frequencies counted on the integrated orbit
    (zero crossings of L and the mean rate of the unwrapped angle g).

Writes ``section_megno.png`` and ``answers.json`` (the numbers the CLI steps are
compared with) into the current folder. Usage: ``python newcomer.py`` (any step that
fails raises).
"""

from __future__ import annotations

import json
import time

import numpy as np

START = time.perf_counter()
#: The orbit of tasks (a) and (c) on the command line too: (l, g, L, G, M).
ORBIT = [0.3, 1.0, 0.2, 1.0, 0.0]


def step(text: str) -> None:
    print(f"newcomer api [{time.perf_counter() - START:5.1f} s]: {text}", flush=True)


def section_coloured_by_megno() -> dict[str, float]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from andoyer import RigidBody, fill_section, indicators, poincare

    body = RigidBody.paper()
    fill = fill_section(body, h=0.2466, M=0.0, section=("theta2", 0.0), n_orbits=12)
    y0 = fill["y0"].values
    section = poincare(body, y0, "theta2=0", 200)
    assert float(abs(section.section_residual).max()) < 1e-10, "points off the plane"
    chaos = indicators(body, y0, 1000.0)
    megno = chaos.megno.isel(time=-1).values
    assert megno.shape == (y0.shape[0],) and np.all(np.isfinite(megno))
    # Near the Hess case at mu = 0.01 the paper's body is regular: <Y> -> 2.
    assert np.all((megno > 1.5) & (megno < 2.5)), megno
    fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
    colour = np.broadcast_to(megno[:, None], section.theta1.shape)
    points = ax.scatter(section.theta1.values % (2 * np.pi), section.J1.values,
                        c=colour, s=2, cmap="viridis", vmin=0.0, vmax=4.0)
    fig.colorbar(points, ax=ax, label="MEGNO <Y> at t = 1000")
    ax.set(xlabel="theta1", ylabel="J1", title="section theta2 = 0, coloured by MEGNO")
    fig.savefig("section_megno.png", dpi=80)
    step(f"(a) section of {y0.shape[0]} orbits x 200 crossings coloured by MEGNO "
         f"({megno.min():.3f} .. {megno.max():.3f}) -> section_megno.png")
    one = indicators(body, ORBIT, 1000.0, chart="andoyer")  # what the CLI step repeats
    return {"megno_min": float(megno.min()), "megno_max": float(megno.max()),
            "megno_orbit": float(one.megno.isel(orbit=0, time=-1))}


def hess_separatrix_splitting() -> dict[str, float]:
    from andoyer import RigidBody
    from andoyer.analysis.splitting.measure import separatrix_splitting

    body = RigidBody.near_hess(2.5, 2, 2.2, mu=0.01, epsilon=0.1)
    # The defaults: the Hess branch theta1 = 0 and the body's own mu.
    out = separatrix_splitting(body, progress=False)
    s = out["splitting"]
    assert s.attrs.get("branch", "theta1=0") == "theta1=0", s.attrs.get("branch")
    assert s.mu.values.tolist() == [0.01], s.mu.values
    amplitude = float(s.amplitude[0])
    predicted = float(s.amplitude_melnikov[0])
    error = float(s.relative_error[0])
    assert amplitude > 0 and np.isfinite(amplitude)
    assert error < 0.1, f"splitting {amplitude:.4e} vs Melnikov {predicted:.4e}"
    step(f"(b) Hess separatrix off the Hess direction: max |dG| = {amplitude:.6e}, "
         f"Melnikov {predicted:.6e}, relative error {error:.3f}")
    return {"splitting": amplitude, "splitting_melnikov": predicted}


def rotation_number_by_naff() -> dict[str, float]:
    from andoyer import RigidBody, propagate
    from andoyer.analysis.chaos.frequency import orbit_frequencies

    body = RigidBody.paper()
    y0 = ORBIT
    t_end, n = 4000.0, 16385
    ds = orbit_frequencies(body, y0, t_end, n_samples=n, chart="andoyer")
    omega_l, omega_g = float(ds.omega_l[0]), float(ds.omega_g[0])
    # Independently: the period of the (l, L) motion from the upward zero crossings of
    # L - <L>, and the rate of g from the slope of the unwrapped angle.
    orbit = propagate(body, y0, np.linspace(0.0, t_end, n), chart="andoyer").isel(orbit=0)
    t, L = orbit.time.values, orbit.L_action.values - orbit.L_action.values.mean()
    up = np.flatnonzero((L[:-1] < 0) & (L[1:] >= 0))
    crossings = t[up] - L[up] * (t[up + 1] - t[up]) / (L[up + 1] - L[up])
    counted_l = 2 * np.pi * (len(crossings) - 1) / (crossings[-1] - crossings[0])
    counted_g = float(np.polyfit(t, np.unwrap(orbit.g_angle.values), 1)[0])
    ratio, counted = omega_g / omega_l, counted_g / counted_l
    assert abs(omega_l / counted_l - 1) < 2e-3, (omega_l, counted_l)
    assert abs(ratio / counted - 1) < 5e-3, (ratio, counted)
    step(f"(c) NAFF: omega_l = {omega_l:.6f}, omega_g = {omega_g:.6f}, omega_g/omega_l = "
         f"{ratio:.5f} (counted on the orbit: {counted:.5f}; per turn of g the (l, L) "
         f"motion turns {1 / ratio:.5f} times)")
    return {"omega_l": omega_l, "omega_g": omega_g, "rotation_counted": 1 / counted}


if __name__ == "__main__":
    answers = {**section_coloured_by_megno(), **hess_separatrix_splitting(),
               **rotation_number_by_naff()}
    with open("answers.json", "w", encoding="utf-8") as f:
        json.dump(answers, f, indent=1)
    step("three tasks done through the API")
