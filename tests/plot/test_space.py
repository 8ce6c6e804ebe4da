"""Figures of the body in space (issue 27, item 4): the axis trace on the shaded sphere,
precession and nutation against time (gaps where undefined), the heteroclinic cycle,
and the gyroscope's animation (one frame per time; the axle follows the symmetry axis)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from _figures import overlapping_texts
from andoyer import RigidBody
from andoyer.analysis.space.inertial import axis_trace, heteroclinic_cycle
from andoyer.integrate import attitude
from andoyer.plot.space import (
    gyroscope_animation,
    plot_axis_trace,
    plot_heteroclinic_cycle,
    plot_precession_nutation,
)

LAGRANGE = RigidBody.lagrange(1.0, 0.6, 1.0)


@pytest.fixture(scope="module")
def ds():
    y0 = [[0.2, 0.1, 1.5, 0.0, math.sin(0.8), math.cos(0.8)], [0.3, 0.0, 1.5, 0.0, 0.0, 1.0]]
    return attitude(LAGRANGE, y0, np.linspace(0, 5, 101), engine="numba")


def test_axis_trace_draws_one_line_per_orbit_on_the_sphere(ds):
    fig = plot_axis_trace(axis_trace(ds, "z"))
    ax = fig.axes[0]
    lines = [ln for ln in ax.get_lines() if len(ln.get_xdata()) == ds.sizes["time"]]
    assert len(lines) == 2
    x, y = lines[0].get_data_3d()[:2]
    assert np.allclose(x, ds.rotation.values[0, :, 0, 2])


def test_precession_nutation_leaves_gaps_where_undefined(ds):
    fig = plot_precession_nutation(ds, orbit=1)  # starts at theta = 0
    psi = fig.axes[0].get_lines()[0].get_ydata()
    assert np.isnan(psi[0]) and np.isfinite(psi[1:]).all()
    assert "undefined" in fig.axes[0].get_title()  # said above the panel, not over the data
    theta = fig.axes[1].get_lines()[0].get_ydata()
    assert np.allclose(theta, np.degrees(ds.nutation.values[1]))


def test_heteroclinic_cycle_figure():
    cyc = heteroclinic_cycle(RigidBody.paper(mu=0.01), engine="numba", n_times=201)
    fig = plot_heteroclinic_cycle(cyc, axis_trace(cyc, "z"))
    assert len(fig.axes[0].get_lines()) >= 2


def test_animation_has_one_frame_per_time_and_the_axle_follows_z(ds):
    anim = gyroscope_animation(ds.isel(time=slice(0, 10)))
    axle = anim._fig.axes[0].get_lines()[-3]
    anim._func(7)
    x, y, z = (np.asarray(v) for v in axle.get_data_3d())
    assert np.allclose([x[1], y[1], z[1]], ds.rotation.values[0, 7, :, 2])
    assert len(list(anim.new_frame_seq())) == 10


def test_plotly_gyroscope_frames_follow_the_attitude(ds):
    from andoyer.plot.space import gyroscope_plotly

    fig = gyroscope_plotly(ds, orbit=0, frames=11)
    assert [t.name for t in fig.data] == ["sphere", "axis trace", "axle", "wheel"]
    assert len(fig.frames) == 11 and fig.layout.meta == "andoyer-gyroscope"
    R = ds.rotation.values[0]
    last = fig.frames[-1].data[0]
    assert np.allclose([last.x[1], last.y[1], last.z[1]], R[-1, :, 2])
    assert np.allclose(fig.data[1].x, R[:, 0, 2])
    # the Play/Pause buttons and the slider sit under the scene, off its axis labels
    bottom = fig.layout.scene.domain.y[0]
    assert fig.layout.updatemenus[0].y < bottom and fig.layout.sliders[0].y < bottom


def test_space_figures_have_no_overlapping_labels(ds):
    cyc = heteroclinic_cycle(RigidBody.paper(mu=0.01), engine="numba", n_times=201)
    for fig in (plot_axis_trace(axis_trace(ds, "z")), plot_precession_nutation(ds, orbit=1),
                plot_heteroclinic_cycle(cyc, axis_trace(cyc, "z"))):
        assert overlapping_texts(fig) == []


def test_plotly_gyroscope_refuses_a_dataset_without_attitude_naming_ds():
    """Before: AttributeError from xarray ('Dataset' object has no attribute 'rotation')."""
    from andoyer.integrate import propagate
    from andoyer.plot.space import gyroscope_plotly

    plain = propagate(LAGRANGE, [0.2, 0.1, 1.5, 0.0, 0.6, 0.8], [0.0, 1.0], engine="numba")
    with pytest.raises(ValueError, match=r"^ds has no attitude"):
        gyroscope_plotly(plain)
    with pytest.raises(ValueError, match=r"^ds has no attitude"):
        gyroscope_animation(plain)
    with pytest.raises(TypeError, match=r"^ds must be an attitude dataset"):
        gyroscope_plotly(plain.to_array())


@pytest.mark.parametrize("orbit", [3, 2, -1, True, 1.5, "0", None])
def test_plotly_gyroscope_refuses_an_orbit_out_of_range_naming_orbit(ds, orbit):
    """Before: orbit=3 on a one-orbit dataset raised IndexError."""
    from andoyer.plot.space import gyroscope_plotly

    with pytest.raises(ValueError, match=r"^orbit must be an integer in \[0, 1\]"):
        gyroscope_plotly(ds, orbit=orbit)
    with pytest.raises(ValueError, match=r"^orbit must be"):
        gyroscope_animation(ds, orbit=orbit)


@pytest.mark.parametrize("frames", [1, 10**6, True, 2.5])
def test_plotly_gyroscope_refuses_bad_frames(ds, frames):
    from andoyer.plot.space import gyroscope_plotly

    with pytest.raises(ValueError, match=r"^frames must be"):
        gyroscope_plotly(ds, frames=frames)


def _failing_encoder(tmp_path, monkeypatch, status=3):
    """A fake ffmpeg first on PATH: it says two lines on stderr and exits ``status``."""
    fake = tmp_path / "bin"
    fake.mkdir()
    exe = fake / "ffmpeg"
    exe.write_text("#!/bin/sh\necho 'ffmpeg version fake' >&2\n"
                   "echo '[libx264 @ 0x1] no such codec' >&2\n"
                   f"exit {status}\n")
    exe.chmod(0o755)
    monkeypatch.setenv("PATH", f"{fake}:{__import__('os').environ['PATH']}")


def test_a_failing_encoder_is_named_with_its_status_and_last_line(ds, tmp_path, monkeypatch):
    """Before: the encoder's raw CalledProcessError (and matplotlib's log of its output)."""
    from andoyer.errors import EncoderError
    from andoyer.plot.space import save_animation

    _failing_encoder(tmp_path, monkeypatch)
    out = tmp_path / "top.mp4"
    anim = gyroscope_animation(ds.isel(time=slice(0, 4)))
    with pytest.raises(EncoderError) as info:
        save_animation(anim, out)
    said = str(info.value)
    assert said == (f"the encoder ffmpeg failed with exit status 3: [libx264 @ 0x1] no such "
                    f"codec; nothing was written to {str(out)!r}")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bin"]
