"""The body in space: the trace of an axis on a shaded sphere, precession and nutation
against time, and the gyroscope drawn moving (a Matplotlib animation).

Datasets in (:func:`andoyer.integrate.attitude`,
:func:`andoyer.analysis.space.inertial.axis_trace`,
:func:`andoyer.analysis.space.inertial.heteroclinic_cycle`), figures out; nothing
computed here but the drawing (the sphere's shading, the wheel's rim).
"""

from __future__ import annotations

import logging
import os
import subprocess
from io import BytesIO
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
from matplotlib.animation import AbstractMovieWriter, FFMpegWriter, FuncAnimation, writers
from matplotlib.figure import Figure

from andoyer.atomic import atomic_path
from andoyer.errors import EncoderError
from andoyer.plot.style import COLOURS, new_figure, paper_style
from andoyer.plot.words import branch_words
from andoyer.progress import Progress
from andoyer.validation import integer

__all__ = ["plot_axis_trace", "plot_precession_nutation", "plot_heteroclinic_cycle",
           "gyroscope_animation", "gyroscope_plotly", "save_animation", "ANIMATION_FORMATS",
           "animation_writer_available", "MAX_PLOTLY_FRAMES"]

#: File suffix -> the encoder that writes it (Pillow ships with Matplotlib; MP4 needs
#: the ffmpeg program).
ANIMATION_FORMATS = {".gif": "pillow", ".mp4": "ffmpeg"}
#: Most frames of :func:`gyroscope_plotly` (each is sent to the browser as JSON).
MAX_PLOTLY_FRAMES = 2000

#: Direction of the light shading the sphere (space frame).
_LIGHT = np.array([-0.4, -0.6, 0.7]) / np.linalg.norm([-0.4, -0.6, 0.7])


def _sphere(ax: Any, n: int = 48) -> None:
    """A unit sphere shaded by :data:`_LIGHT` (Lambert), with the equator and Z axis."""
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, n), np.linspace(0, np.pi, n // 2))
    x, y, z = np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)
    shade = np.clip(x * _LIGHT[0] + y * _LIGHT[1] + z * _LIGHT[2], 0.0, 1.0)
    colours = np.empty((*x.shape, 4))
    colours[..., :3] = (0.55 + 0.4 * shade)[..., None] * np.array([0.86, 0.9, 0.97])
    colours[..., 3] = 0.35
    ax.plot_surface(x, y, z, facecolors=colours, linewidth=0, antialiased=False,
                    shade=False, rstride=1, cstride=1)
    t = np.linspace(0, 2 * np.pi, 181)
    ax.plot(np.cos(t), np.sin(t), 0 * t, color="0.6", lw=0.5)
    ax.plot([0, 0], [0, 0], [-1.15, 1.15], color="0.4", lw=0.6)
    ax.text(0, 0, 1.2, "Z", fontsize=8, ha="center")
    ax.set_box_aspect((1, 1, 1))
    for setter in (ax.set_xlim, ax.set_ylim, ax.set_zlim):
        setter(-1.05, 1.05)
    ax.set_axis_off()


def plot_axis_trace(trace: xr.Dataset, *, orbits: Any = None, ax: Any = None) -> Figure:
    """The trace of a body axis on the unit sphere of the space frame (shaded).

    Parameters
    ----------
    trace : xarray.Dataset
        :func:`andoyer.analysis.space.inertial.axis_trace` output (``trace`` with a
        ``space`` dimension; a leading ``orbit`` or ``branch`` dimension is drawn one
        line per entry).
    orbits : sequence, optional
        The entries of the leading dimension to draw (default all).
    ax : Axes3D, optional
        Axes to draw into (default a new figure).

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.analysis.space.inertial import axis_trace
    >>> from andoyer.integrate import attitude
    >>> ds = attitude(RigidBody.lagrange(1.0, 0.6, 1.0), [0.2, 0.1, 1.5, 0.0, 0.6, 0.8],
    ...               np.linspace(0.0, 2.0, 21), engine="scipy")
    >>> plot_axis_trace(axis_trace(ds, "z")).axes[0].name
    '3d'
    """
    with paper_style():
        if ax is None:
            fig = new_figure(1, 1, width=3.6, aspect=1.0, projection="3d")
            ax = fig.axes[0]
        else:
            fig = ax.get_figure(root=True)
        _sphere(ax)
        u = trace.trace
        lead = [d for d in u.dims if d not in ("time", "space")]
        lines = [u] if not lead else [u.isel({lead[0]: i}) for i in range(u.sizes[lead[0]])]
        labels: list[str | None] = ([None] if not lead
                                    else [branch_words(str(v)) for v in u[lead[0]].values])
        if orbits is not None and lead:
            keep = set(np.atleast_1d(orbits).tolist())
            pairs = [(line, lab) for line, lab in zip(lines, labels, strict=True)
                     if line[lead[0]].item() in keep]
            lines, labels = [p[0] for p in pairs], [p[1] for p in pairs]
        for line, label in zip(lines, labels, strict=True):
            xyz = line.transpose("time", "space").values
            p, = ax.plot(*xyz.T, lw=0.9, label=label)
            ax.scatter(*xyz[0], s=10, color=p.get_color(), depthshade=False)
        ax.view_init(elev=22, azim=-60)
        ax.set_title(f"trace of the axis {trace.attrs.get('axis', '')} in space")
        if lead and len(lines) > 1:
            ax.legend(loc="upper left", fontsize=6.5,
                      title="separatrix branch" if lead[0] == "branch" else lead[0])
    return fig


def plot_precession_nutation(ds: xr.Dataset, orbit: int = 0) -> Figure:
    """Precession ``psi`` (unwrapped) and nutation ``theta`` of one orbit against time.

    Parameters
    ----------
    ds : xarray.Dataset
        An attitude dataset (:func:`andoyer.integrate.attitude`).
    orbit : int
        Which orbit (position along ``orbit``).

    Returns
    -------
    matplotlib.figure.Figure
        Two panels; gaps where the Euler angles are undefined (``euler_singular``).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.integrate import attitude
    >>> ds = attitude(RigidBody.lagrange(1.0, 0.6, 1.0), [0.2, 0.1, 1.5, 0.0, 0.6, 0.8],
    ...               np.linspace(0.0, 2.0, 21), engine="scipy")
    >>> len(plot_precession_nutation(ds).axes)
    2
    """
    one = ds.isel(orbit=orbit)
    t = one.time.values
    psi = one.precession.values
    finite = np.isfinite(psi)
    unwrapped = np.full_like(psi, np.nan)
    if finite.any():
        unwrapped[finite] = np.unwrap(psi[finite])
    with paper_style():
        fig = new_figure(2, 1, width=5.0, aspect=0.32, sharex=True)
        ax_p, ax_n = fig.axes
        ax_p.plot(t, unwrapped, color=COLOURS["centre"])
        ax_p.set_ylabel(r"precession $\psi$ (rad)")
        ax_n.plot(t, np.degrees(one.nutation.values), color=COLOURS["separatrix"])
        ax_n.set_ylabel(r"nutation $\theta$ (deg)")
        ax_n.set_xlabel("time")
        if bool(one.euler_singular.any()):
            ax_p.set_title(r"gaps: $\theta = 0$ or $\pi$, where $\psi$ is undefined",
                           fontsize=7, color=COLOURS["singular"])
    return fig


def plot_heteroclinic_cycle(cycle: xr.Dataset, trace: xr.Dataset) -> Figure:
    """(a) ``L/G`` along the two branches of the cycle; (b) the trace of the symmetry axis.

    Parameters
    ----------
    cycle : xarray.Dataset
        :func:`andoyer.analysis.space.inertial.heteroclinic_cycle` output.
    trace : xarray.Dataset
        ``axis_trace(cycle, "z")``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.analysis.space.inertial import axis_trace, heteroclinic_cycle
    >>> cyc = heteroclinic_cycle(RigidBody.paper(), n_times=11, engine="scipy")
    >>> len(plot_heteroclinic_cycle(cyc, axis_trace(cyc, "z")).axes)
    2
    """
    with paper_style():
        fig = Figure(figsize=(6.6, 3.0), layout="constrained")
        ax_a = fig.add_subplot(1, 2, 1)
        ax_b = fig.add_subplot(1, 2, 2, projection="3d")
        for b in cycle.branch.values:
            ax_a.plot(cycle.time, cycle.L_over_G.sel(branch=b), label=branch_words(str(b)))
        ax_a.axhline(1.0, color="0.7", lw=0.5)
        ax_a.axhline(-1.0, color="0.7", lw=0.5)
        # the two equilibria named beside the axis, off the curves
        ax_a.set_yticks([-1.0, -0.5, 0.0, 0.5, 1.0],
                        [r"$P_-$: $-1$", "$-0.5$", "$0$", "$0.5$", r"$P_+$: $1$"])
        ax_a.set_xlabel("time from the middle of the branch")
        ax_a.set_ylabel("$L/G$")
        ax_a.set_title(rf"(a) $\mu = {float(cycle.attrs['body_mu']):g}$")
        ax_a.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), ncols=2, fontsize=6.5,
                    frameon=False, title="separatrix branch", title_fontsize=6.5)
        plot_axis_trace(trace, ax=ax_b)
        if ax_b.get_legend() is not None:  # (a)'s legend names the same colours
            ax_b.get_legend().remove()
        ax_b.set_box_aspect((1, 1, 1), zoom=1.15)
        ax_b.set_title("(b) the axis $z$ in space")
    return fig


def _wheel(n: int = 48) -> np.ndarray:
    """The gyroscope in the body frame: rim of the wheel at ``z = 0.75`` and its axle."""
    t = np.linspace(0, 2 * np.pi, n)
    rim = np.stack([0.45 * np.cos(t), 0.45 * np.sin(t), np.full(n, 0.75)], axis=-1)
    spoke = np.array([[0.45, 0.0, 0.75], [-0.45, 0.0, 0.75]])
    return np.concatenate([rim, [[np.nan] * 3], spoke])


def _attitude_orbit(ds: Any, orbit: Any) -> xr.Dataset:
    """One orbit of an attitude dataset, or ``ValueError`` naming ``ds`` or ``orbit``."""
    if not isinstance(ds, xr.Dataset):
        raise TypeError(f"ds must be an attitude dataset (andoyer.integrate.attitude), got "
                        f"{type(ds).__name__}")
    if "rotation" not in ds or "orbit" not in ds.dims or "time" not in ds.dims:
        raise ValueError("ds has no attitude (no variable rotation over (orbit, time)): "
                         "pass a dataset of andoyer.integrate.attitude, not of propagate")
    n = ds.sizes["orbit"]
    k = integer("orbit", orbit, 0, n - 1) if n else integer("orbit", orbit, 0)
    if n == 0:
        raise ValueError("ds holds no orbit")
    one = ds.isel(orbit=k)
    if not np.all(np.isfinite(one.rotation.values)):
        raise ValueError(f"ds: orbit {k} has non-finite rotations (a failed integration)")
    return one


#: Side of an animation's frame in pixels (at :func:`save_animation`'s 100 dpi).
ANIMATION_SIZE = 480


def gyroscope_animation(ds: xr.Dataset, orbit: int = 0, *, fps: int = 20,
                        tail: int | None = None, size: int = ANIMATION_SIZE) -> FuncAnimation:
    """The gyroscope moving: its axle (body axis ``z``), its wheel, and the trace of the
    axle's tip on the sphere, one frame per time of ``ds``.

    Parameters
    ----------
    ds : xarray.Dataset
        An attitude dataset (:func:`andoyer.integrate.attitude`).
    orbit : int
        Which orbit: an index in ``[0, n_orbits)``.
    fps : int
        Frames per second of the animation's clock, in ``[1, 60]``.
    tail : int, optional
        Frames of trace kept behind the tip (default: all).
    size : int, default 480
        Side of the square frame in pixels (written at 100 dpi); the sphere fills it.

    Raises
    ------
    ValueError
        Naming ``ds`` (no attitude: a dataset of ``propagate``, or a failed orbit) or
        ``orbit`` (out of range), ``fps``, ``tail``.

    Returns
    -------
    matplotlib.animation.FuncAnimation
        Write it with :func:`save_animation` (GIF or MP4, atomically).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.integrate import attitude
    >>> ds = attitude(RigidBody.lagrange(1.0, 0.6, 1.0), [0.2, 0.1, 1.5, 0.0, 0.6, 0.8],
    ...               np.linspace(0.0, 2.0, 5), engine="scipy")
    >>> anim = gyroscope_animation(ds)
    >>> len(list(anim.new_frame_seq()))
    5
    """
    one = _attitude_orbit(ds, orbit)
    fps = integer("fps", fps, 1, 60)
    tail = None if tail is None else integer("tail", tail, 0)
    R = one.rotation.transpose("time", "space", "body").values
    tip = R[:, :, 2]
    body = _wheel()
    t = one.time.values
    side = integer("size", size, 64, 4096) / 100.0
    with paper_style():
        # The whole frame is the 3D axes (constrained layout would leave a blank band
        # under a square 3D box), zoomed so that the sphere fills it.
        fig = Figure(figsize=(side, side), dpi=100)
        ax: Any = fig.add_axes((0.0, 0.0, 1.0, 1.0), projection="3d")
        _sphere(ax, n=32)
        ax.set_box_aspect((1, 1, 1), zoom=1.35)
        ax.view_init(elev=18, azim=-60)
        axle, = ax.plot([], [], [], color="0.15", lw=2.0)
        wheel, = ax.plot([], [], [], color=COLOURS["separatrix"], lw=1.4)
        trail, = ax.plot([], [], [], color=COLOURS["centre"], lw=0.9)
        label = ax.text2D(0.03, 0.95, "", transform=ax.transAxes,
                          fontsize=max(7.0, 7.0 * side / 3.4))

    def draw(k: int) -> tuple[Any, ...]:  # the lines are Line3D
        a = tip[k]
        axle.set_data_3d([0.0, a[0]], [0.0, a[1]], [0.0, a[2]])
        w = body @ R[k].T
        wheel.set_data_3d(w[:, 0], w[:, 1], w[:, 2])
        lo = 0 if tail is None else max(0, k - tail)
        trail.set_data_3d(tip[lo:k + 1, 0], tip[lo:k + 1, 1], tip[lo:k + 1, 2])
        label.set_text(f"t = {t[k]:.2f}")
        return axle, wheel, trail, label

    return FuncAnimation(fig, draw, frames=len(t), interval=1000.0 / fps, blit=False)


class _GifWriter(AbstractMovieWriter):
    """Matplotlib's movie-writer protocol (setup, grab_frame, finish) writing an animated
    GIF with Pillow in an explicit format, so that it can write a temporary file of any
    name (:func:`andoyer.atomic.atomic_path`)."""

    def setup(self, fig: Any, outfile: Any, dpi: float | None = None) -> None:
        super().setup(fig, outfile, dpi=dpi)
        self.images: list[Any] = []

    def grab_frame(self, **savefig_kwargs: Any) -> None:
        from PIL import Image

        buf = BytesIO()
        self.fig.savefig(buf, **{**savefig_kwargs, "format": "rgba", "dpi": self.dpi})
        im = Image.frombuffer("RGBA", self.frame_size, buf.getvalue(), "raw", "RGBA", 0, 1)
        self.images.append(im.convert("RGB"))

    def finish(self) -> None:
        self.images[0].save(self.outfile, format="GIF", save_all=True,
                            append_images=self.images[1:],
                            duration=int(1000 / self.fps), loop=0)


def animation_writer_available(suffix: str) -> bool:
    """Whether an animation of file suffix ``suffix`` (``.gif``, ``.mp4``) can be written
    here (``.mp4`` needs the ffmpeg program).

    Parameters
    ----------
    suffix : str
        File suffix of the animation (``".gif"``, ``".mp4"``).

    Examples
    --------
    >>> animation_writer_available(".gif")
    True
    """
    if suffix not in ANIMATION_FORMATS:
        raise ValueError(f"animations are written as {', '.join(ANIMATION_FORMATS)}, got "
                         f"{suffix!r}")
    return suffix == ".gif" or bool(writers.is_available("ffmpeg"))


def save_animation(anim: FuncAnimation, path: str | os.PathLike[str], *, fps: int = 20,
                   dpi: int = 100, progress: bool | None = None) -> Path:
    """Write ``anim`` as GIF (Pillow) or MP4 (ffmpeg, H.264) atomically: a temporary file
    in the same folder, renamed when complete (nothing left behind if interrupted).

    Parameters
    ----------
    anim : matplotlib.animation.FuncAnimation
        E.g. :func:`gyroscope_animation`.
    path : path-like
        Ends in ``.gif`` or ``.mp4``.
    fps : int
        Frames per second of the file, in ``[1, 60]``.
    dpi : int
        Resolution of the frames, in ``[10, 1000]``.
    progress : bool, optional
        A bar of the frames drawn (:class:`andoyer.progress.Progress`; default: on a
        terminal; plain lines where ``True`` and stderr is no terminal).

    Raises
    ------
    andoyer.errors.EncoderError
        The encoder (ffmpeg) failed: the message names it, its exit status and the last
        line of its error output; nothing was written.

    Returns
    -------
    Path

    Examples
    --------
    >>> import tempfile
    >>> from andoyer import RigidBody
    >>> from andoyer.integrate import attitude
    >>> ds = attitude(RigidBody.lagrange(1.0, 0.6, 1.0), [0.2, 0.1, 1.5, 0.0, 0.6, 0.8],
    ...               np.linspace(0.0, 2.0, 3), engine="scipy")
    >>> out = save_animation(gyroscope_animation(ds), Path(tempfile.mkdtemp()) / "top.gif")
    >>> out.name, out.read_bytes()[:6]
    ('top.gif', b'GIF89a')
    """
    final = Path(path)
    suffix = final.suffix.lower()
    if not animation_writer_available(suffix):
        raise ValueError(f"no MP4 encoder here (the ffmpeg program is not installed); write "
                         f"a .gif instead of {str(final)!r}")
    fps = integer("fps", fps, 1, 60)
    dpi = integer("dpi", dpi, 10, 1000)
    # Matplotlib logs the encoder's whole output as a warning when it fails; the error
    # below says what matters in one line.
    log = logging.getLogger("matplotlib.animation")
    level = log.level
    log.setLevel(logging.ERROR)
    try:
        with atomic_path(final) as tmp:
            if suffix == ".gif":
                writer: AbstractMovieWriter = _GifWriter(fps=fps)
            else:
                writer = FFMpegWriter(fps=fps, codec="h264", extra_args=["-f", "mp4"])
            bars: list[Progress] = []

            def drawn(k: int, n: int) -> None:
                if not bars:
                    bars.append(Progress(n, f"frames of {final.name}", progress))
                bars[0].update(1)

            try:
                anim.save(str(tmp), writer=writer, dpi=dpi, progress_callback=drawn)
            finally:
                for bar in bars:
                    bar.close()
    except subprocess.CalledProcessError as exc:
        raise _encoder_error(exc, final) from None
    finally:
        log.setLevel(level)
    return final


def _encoder_error(exc: subprocess.CalledProcessError, final: Path) -> EncoderError:
    """One line: the encoder, its exit status, the last line of its error output."""
    cmd = exc.cmd if isinstance(exc.cmd, list | tuple) else str(exc.cmd).split()
    encoder = os.path.basename(str(cmd[0])) if cmd else "the encoder"
    err = exc.stderr.decode(errors="replace") if isinstance(exc.stderr, bytes) else (
        exc.stderr or "")
    lines = [line.strip() for line in str(err).splitlines() if line.strip()]
    said = f": {lines[-1]}" if lines else " (no error output)"
    return EncoderError(f"the encoder {encoder} failed with exit status {exc.returncode}"
                        f"{said}; nothing was written to {str(final)!r}")


#: Where the 3D scene of :func:`gyroscope_plotly` starts (fraction of the height): its
#: controls sit under it.
SCENE_BOTTOM = 0.2


def gyroscope_plotly(ds: xr.Dataset, orbit: int = 0, *, frames: int = 60) -> Any:
    """The gyroscope moving, as an interactive Plotly 3D figure (the explorer's 3D view).

    The unit sphere, the trace of the symmetry axis, and the axle and wheel at
    ``frames`` evenly spaced times, played in the browser (Play / Pause buttons and a
    time slider; nothing runs on the server while it plays).

    Parameters
    ----------
    ds : xarray.Dataset
        An attitude dataset (:func:`andoyer.integrate.attitude`).
    orbit : int
        Which orbit: an index in ``[0, n_orbits)``.
    frames : int
        Animation frames, in ``[2, MAX_PLOTLY_FRAMES]``.

    Raises
    ------
    ValueError
        Naming ``ds`` (no attitude: a dataset of ``propagate``, or a failed orbit),
        ``orbit`` (out of range) or ``frames``.

    Returns
    -------
    plotly.graph_objects.Figure
        ``layout.meta = "andoyer-gyroscope"``; traces ``sphere``, ``axis trace``,
        ``axle``, ``wheel``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.integrate import attitude
    >>> ds = attitude(RigidBody.lagrange(1.0, 0.6, 1.0), [0.2, 0.1, 1.5, 0.0, 0.6, 0.8],
    ...               np.linspace(0.0, 2.0, 21), engine="scipy")
    >>> fig = gyroscope_plotly(ds, frames=5)
    >>> [t.name for t in fig.data], len(fig.frames)
    (['sphere', 'axis trace', 'axle', 'wheel'], 5)
    """
    import plotly.graph_objects as go

    one = _attitude_orbit(ds, orbit)
    n = integer("frames", frames, 2, MAX_PLOTLY_FRAMES)
    R = one.rotation.transpose("time", "space", "body").values
    t = one.time.values
    tip = R[:, :, 2]
    keys = np.unique(np.linspace(0, len(t) - 1, n).round().astype(int))
    wheel = _wheel(24)
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 25), np.linspace(0, np.pi, 13))

    def moving(k: int) -> list[Any]:
        # Plain lists, not arrays: frames reach the browser as JSON (Panel's Plotly pane
        # sends the traces' arrays as columns, not the frames').
        rim = wheel @ R[k].T
        w = [[None if np.isnan(c) else float(c) for c in row] for row in rim]
        a = [float(c) for c in tip[k]]
        return [go.Scatter3d(x=[0.0, a[0]], y=[0.0, a[1]], z=[0.0, a[2]],
                             mode="lines", line={"color": "#262626", "width": 7},
                             name="axle"),
                go.Scatter3d(x=[p[0] for p in w], y=[p[1] for p in w], z=[p[2] for p in w],
                             mode="lines",
                             line={"color": COLOURS["separatrix"], "width": 5},
                             name="wheel")]

    sphere = go.Surface(x=np.cos(u) * np.sin(v), y=np.sin(u) * np.sin(v), z=np.cos(v),
                        opacity=0.25, showscale=False, colorscale="Blues", name="sphere",
                        hoverinfo="skip")
    trace = go.Scatter3d(x=tip[:, 0], y=tip[:, 1], z=tip[:, 2], mode="lines",
                         line={"color": COLOURS["centre"], "width": 3}, name="axis trace")
    fig = go.Figure(data=[sphere, trace, *moving(int(keys[0]))],
                    frames=[go.Frame(data=moving(int(k)), traces=[2, 3], name=f"{t[k]:.3g}")
                            for k in keys])
    steps = [{"args": [[f"{t[k]:.3g}"], {"frame": {"duration": 0, "redraw": True},
                                          "mode": "immediate"}],
              "label": f"{t[k]:.3g}", "method": "animate"} for k in keys]
    fig.update_layout(
        meta="andoyer-gyroscope", showlegend=False, margin={"l": 0, "r": 0, "t": 0, "b": 0},
        # the scene above the Play/Pause buttons and the slider (they covered its axes)
        scene={"domain": {"x": [0.0, 1.0], "y": [SCENE_BOTTOM, 1.0]},
               "aspectmode": "cube", "xaxis": {"range": [-1.1, 1.1], "title": "X"},
               "yaxis": {"range": [-1.1, 1.1], "title": "Y"},
               "zaxis": {"range": [-1.1, 1.1], "title": "Z"}},
        updatemenus=[{"type": "buttons", "showactive": False, "x": 0.02, "y": 0.02,
                      "xanchor": "left", "yanchor": "bottom",
                      "buttons": [{"label": "Play", "method": "animate",
                                   "args": [None, {"frame": {"duration": 60, "redraw": True},
                                                   "fromcurrent": True}]},
                                  {"label": "Pause", "method": "animate",
                                   "args": [[None], {"frame": {"duration": 0},
                                                     "mode": "immediate"}]}]}],
        sliders=[{"steps": steps, "currentvalue": {"prefix": "t = "}, "len": 0.75,
                  "x": 0.2, "y": 0.02}])
    return fig
