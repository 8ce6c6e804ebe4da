"""Section portraits: drawn from datasets, written atomically as PNG (and PDF)."""

from __future__ import annotations

import matplotlib.image as mpimg
import numpy as np
import pytest
import xarray as xr

from andoyer import RigidBody
from andoyer.integrate.fill import fill_section
from andoyer.plot import plot_section, save_figure


def fake_section(coord: str = "g", n_orbits: int = 5, n_crossings: int = 200) -> xr.Dataset:
    """Hand-made Poincare-section dataset: ellipses around a centre, one per orbit."""
    t = np.linspace(0.0, 2 * np.pi, n_crossings, endpoint=False)
    r = np.linspace(0.1, 0.5, n_orbits)[:, None]
    x = np.pi + 2.0 * r * np.cos(t)
    y = r * np.sin(t) + (0.5 if coord == "theta2" else 0.0)
    x[-1, n_crossings // 2:] = np.nan  # padding of an orbit with fewer crossings
    y[-1, n_crossings // 2:] = np.nan
    names = {"g": ("l_angle", "L_action"), "theta2": ("theta1", "J1")}[coord]
    dims = ("orbit", "crossing")
    return xr.Dataset({names[0]: (dims, x), names[1]: (dims, y)},
                      coords={"orbit": np.arange(n_orbits), "crossing": np.arange(n_crossings)},
                      attrs={"section_coord": coord, "section_value": 0.0,
                             "section_direction": 1})


def _check_png(path) -> None:
    assert path.exists() and path.stat().st_size > 1024
    img = mpimg.imread(path)
    assert img.ndim == 3 and img.shape[0] > 100
    assert float(img[..., :3].std()) > 0.0  # not a uniform picture


@pytest.mark.parametrize("coord, labels", [("g", ("$l$", "$L$")),
                                           ("theta2", (r"$\theta_1$", "$J_1$"))])
def test_png_written_with_paper_symbols(tmp_path, coord, labels):
    ax = plot_section(fake_section(coord), title="test")
    assert (ax.get_xlabel(), ax.get_ylabel()) == labels
    assert ax.get_title() == "test"
    # One colour per orbit, NaN padding skipped.
    (points,) = ax.collections
    assert len(points.get_offsets()) == 5 * 200 - 100
    assert np.unique(points.get_array()).size == 5
    written = save_figure(ax.figure, tmp_path / "section.png")
    assert written == [tmp_path / "section.png"]
    _check_png(written[0])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["section.png"]


def test_pdf_on_request_and_default_title(tmp_path):
    ax = plot_section(fake_section("g"))
    assert "g = 0" in ax.get_title()
    written = save_figure(ax.figure, tmp_path / "out" / "portrait", pdf=True)
    assert [p.name for p in written] == ["portrait.png", "portrait.pdf"]
    _check_png(written[0])
    assert written[1].read_bytes().startswith(b"%PDF") and written[1].stat().st_size > 1024


def test_draws_into_given_axes():
    from matplotlib.figure import Figure

    fig = Figure()
    ax0, ax1 = fig.subplots(1, 2)
    out = plot_section(fake_section("theta2"), ax=ax1)
    assert out is ax1 and not ax0.collections


def test_boundary_from_a_fill_dataset(tmp_path):
    body = RigidBody.paper()
    fill = fill_section(body, 0.2, 0.0, ("g", 0.0), n_orbits=10, boundary_grid=40)
    ax = plot_section(fake_section("g"), boundary=fill)
    assert len(ax.lines) == 1
    np.testing.assert_allclose(ax.get_xlim(), (0.0, 2 * np.pi))
    np.testing.assert_allclose(ax.get_ylim(), (fill.attrs["plane_y_min"],
                                               fill.attrs["plane_y_max"]))
    _check_png(save_figure(ax.figure, tmp_path / "b.png")[0])
    # The fill dataset itself (initial states, dim orbit only) can be drawn too.
    ax = plot_section(fill, boundary=fill)
    assert len(ax.collections[0].get_offsets()) == fill.sizes["orbit"]
    with pytest.raises(ValueError, match="same section"):
        plot_section(fake_section("theta2"), boundary=fill)


def test_unknown_plane_is_an_error():
    ds = fake_section("g")
    ds.attrs["section_coord"] = "G3"
    with pytest.raises(ValueError, match="section_coord = 'G3'"):
        plot_section(ds)
    with pytest.raises(ValueError, match="lacks the plane variables"):
        plot_section(fake_section("g").drop_vars("L_action"))


def test_failed_write_leaves_old_file_and_no_temporary(tmp_path, monkeypatch):
    ax = plot_section(fake_section("g"))
    target = tmp_path / "s.png"
    target.write_bytes(b"old")

    def boom(*args, **kwargs):
        raise RuntimeError("disk full")

    monkeypatch.setattr(ax.figure, "savefig", boom)
    with pytest.raises(RuntimeError, match="disk full"):
        save_figure(ax.figure, target)
    assert target.read_bytes() == b"old"
    assert [p.name for p in tmp_path.iterdir()] == ["s.png"]


def test_pdf_has_the_pngs_layout_and_the_figure_keeps_its_engine(tmp_path, monkeypatch):
    # constrained layout: the PNG lays the figure out, the PDF takes that layout (one pass
    # fewer); a colorbar needs the engine back as it was
    from matplotlib.figure import Figure

    fig = Figure(layout="constrained")
    ax = fig.subplots()
    fig.colorbar(ax.imshow(np.arange(12.0).reshape(3, 4)), ax=ax, label="FLI")
    ax.set_title("a title long enough to move the axes")
    engine = fig.get_layout_engine()
    seen = []
    real = fig.savefig

    def savefig(tmp, **kwargs):
        real(tmp, **kwargs)
        seen.append((kwargs["format"], fig.get_layout_engine() is engine,
                     [a.get_position().bounds for a in fig.axes]))

    monkeypatch.setattr(fig, "savefig", savefig)
    written = save_figure(fig, tmp_path / "map", pdf=True)
    assert [p.name for p in written] == ["map.png", "map.pdf"]
    (png, png_engine, png_axes), (pdf, pdf_engine, pdf_axes) = seen
    assert (png, png_engine, pdf, pdf_engine) == ("png", True, "pdf", False)
    assert pdf_axes == png_axes
    assert fig.get_layout_engine() is engine
