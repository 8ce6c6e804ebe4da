r"""The Lie-Deprit series to order ``N`` for a periodically forced action-angle system.

The reduced system of :mod:`~andoyer.analysis.resonance.predict` (R2) is a Hamiltonian
``K(J, phi, t) = K0(J) + sum_{n >= 1} mu^n / n! K_n(J, phi, t)`` in one action ``J``, its
angle ``phi`` and the time ``t`` (``phi2`` of the top, period ``2 pi``). About a chosen
action ``J*`` every function is held as a *jet*: a Taylor polynomial in ``x = J - J*`` of
degree ``D`` whose coefficients are Fourier series in ``(phi, t)``,

(D1) ``f = sum_{m <= D} sum_k f[m, k] x^m exp(i (k1 phi + k2 t))``, an array
     ``(D + 1, n1, n2)`` in the layout of :func:`numpy.fft.fft2`; products are taken on the
     grid (inverse FFT, product, FFT) and truncated at degree ``D``; the Poisson bracket is
     ``{f, g} = f_phi g_J - f_J g_phi`` (``t`` and its momentum ``T`` enter only through
     ``H0 = K0(J) + T``).

(D2) Deprit's triangle (A. Deprit, Celest. Mech. 1, 12 (1969)): with
     ``H = sum mu^n / n! H_n`` and the generator ``W = sum mu^n / n! W_{n+1}``,
     ``H_n^(i) = H_{n+1}^(i-1) + sum_{j=0}^{n} C(n, j) {H_{n-j}^(i-1), W_{j+1}}``; the new
     Hamiltonian is ``Ht_n = H_0^(n)``. At order ``n`` the one unknown term is
     ``{H0, W_n} = -omega(J) W_n,phi - W_n,t`` (``omega = K0'``), added unchanged along the
     diagonal.

(D3) The homological equation ``(omega(J) d_phi + d_t) W_n = Psi_n - Ht_n`` is solved away
     from the resonance ``k1 p + k2 q = 0`` (``omega(J*) = p/q``; ``p = 0``: no resonance
     but ``k = 0``), degree by degree in ``x``:
     ``i (k1 omega* + k2) W_n[m] = Psi_n[m] - sum_{j >= 1} omega_j i k1 W_n[m - j]``
     (``omega(J*+x) = sum omega_j x^j``); the resonant harmonics (and ``k = 0``) stay in
     ``Ht_n``.

(D4) Any function ``f`` of the old variables in the new: the same triangle with
     ``f_0^(0) = f``, ``f_n^(0) = 0`` (:func:`transform`), ``f(old) = sum mu^n/n! ft_n(new)``.

Truncated at order ``N`` the normal form errs by ``O(mu^(N+1))``; the jets lose one degree
of ``x`` per bracket, so ``D`` must exceed the degree wanted by ``N``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from andoyer.errors import ArgumentTypeError
from andoyer.validation import finite_array, integer

__all__ = ["JetSpace", "lie_deprit", "transform"]

Jet = NDArray[np.complex128]


class JetSpace:
    """Jets of degree ``D`` in ``x`` on an ``(n1, n2)`` Fourier grid in ``(phi, t)`` (D1).

    Parameters
    ----------
    degree : int
        ``D``, the largest power of ``x = J - J*`` kept.
    n1, n2 : int
        Fourier grid in ``phi`` and ``t`` (products alias beyond ``|k| >= n/2``).
    """

    def __init__(self, degree: int, n1: int, n2: int) -> None:
        self.D, self.n1, self.n2 = int(degree), int(n1), int(n2)
        self.k1 = np.fft.fftfreq(self.n1, 1.0 / self.n1)[None, :, None]
        self.k2 = np.fft.fftfreq(self.n2, 1.0 / self.n2)[None, None, :]

    def zeros(self) -> Jet:
        return np.zeros((self.D + 1, self.n1, self.n2), dtype=complex)

    def d_phi(self, f: Jet) -> Jet:
        return np.asarray(1j * self.k1 * f)

    def d_t(self, f: Jet) -> Jet:
        return np.asarray(1j * self.k2 * f)

    def d_x(self, f: Jet) -> Jet:
        out = np.zeros_like(f)
        out[:-1] = f[1:] * np.arange(1, self.D + 1)[:, None, None]
        return out

    def mul(self, f: Jet, g: Jet) -> Jet:
        n = self.n1 * self.n2
        F = np.fft.ifft2(f, axes=(1, 2)) * n
        Gg = np.fft.ifft2(g, axes=(1, 2)) * n
        out = np.zeros_like(F)
        for a in range(self.D + 1):
            for b in range(self.D + 1 - a):
                out[a + b] += F[a] * Gg[b]
        return np.asarray(np.fft.fft2(out, axes=(1, 2)) / n)

    def bracket(self, f: Jet, g: Jet) -> Jet:
        """``{f, g} = f_phi g_J - f_J g_phi`` (D1)."""
        return self.mul(self.d_phi(f), self.d_x(g)) - self.mul(self.d_x(f), self.d_phi(g))

    def evaluate(self, f: Jet, x: float, phi: float, t: float) -> complex:
        """``f`` at one point: :meth:`at` of :meth:`rows`."""
        return self.at(self.rows(f, phi, t), x)

    def rows(self, f: Jet, phi: float, t: float) -> NDArray[np.complex128]:
        """The Fourier sums of ``f`` at ``(phi, t)``, one per power of ``x``: what
        :meth:`evaluate` needs of ``f`` whatever ``x`` (a Newton search in ``x`` at one
        ``(phi, t)`` takes them once). ``f`` may be a stack of jets (leading axes): each
        jet's sums are those it has alone."""
        e = np.outer(np.exp(1j * phi * self.k1[0, :, 0]), np.exp(1j * t * self.k2[0, 0, :]))
        # elementwise, not a matrix product: BLAS threads cost more than these sums
        return np.sum(f.reshape(*f.shape[:-2], -1) * e.ravel(), axis=-1)

    def at(self, rows: NDArray[np.complex128], x: float) -> complex:
        """The jet of :meth:`rows` at ``x``."""
        xs = x ** np.arange(self.D + 1)
        return complex(np.sum(xs * rows))


def _jets(space: JetSpace, name: str, jets: object, *, minimum: int = 1) -> list[Jet]:
    """``jets`` checked as a sequence of at least ``minimum`` finite jets of ``space``."""
    if isinstance(jets, np.ndarray) and jets.ndim == 3:
        jets = [jets]
    if not isinstance(jets, (list, tuple)) or len(jets) < minimum:
        raise ArgumentTypeError(f"{name} must be a list of at least {minimum} jets of "
                                f"shape {space.zeros().shape}, got {jets!r:.60}")
    return [_jet(space, f"{name}[{i}]", f) for i, f in enumerate(jets)]


def _jet(space: JetSpace, name: str, f: object) -> Jet:
    """``f`` checked as a finite jet of ``space`` (shape ``(D + 1, n1, n2)``)."""
    shape = space.zeros().shape
    a = np.asarray(f) if isinstance(f, np.ndarray) else None
    if a is None or a.shape != shape or not np.issubdtype(a.dtype, np.number) \
            or a.dtype == np.bool_:
        raise ArgumentTypeError(f"{name} must be a jet: an array of shape {shape}, got "
                                f"{f!r:.60}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite")
    return np.asarray(a, dtype=complex)


def _space(space: object) -> JetSpace:
    if not isinstance(space, JetSpace):
        raise ArgumentTypeError(f"space must be a JetSpace, got {space!r:.60}")
    return space


def _homological(space: JetSpace, psi: Jet, omega: Sequence[float], p: int, q: int
                 ) -> tuple[Jet, Jet]:
    """(D3): ``W`` with ``(omega(J) d_phi + d_t) W = psi - resonant(psi)``; returns
    ``(W, resonant part of psi)``."""
    k1, k2 = space.k1[0], space.k2[0]
    resonant = (k1 * p + k2 * q == 0) if p != 0 else (k1 == 0) & (k2 == 0)
    div = 1j * (k1 * omega[0] + k2)
    W = space.zeros()
    kept = space.zeros()
    for m in range(space.D + 1):
        rhs = psi[m].copy()
        for j in range(1, min(m, len(omega) - 1) + 1):
            rhs -= omega[j] * 1j * k1 * W[m - j]
        kept[m] = np.where(resonant, psi[m], 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            W[m] = np.where(resonant, 0.0, rhs / div)
    return W, kept


def lie_deprit(space: JetSpace, H: Sequence[Jet], omega: Sequence[float],
               resonance: tuple[int, int]) -> tuple[list[Jet], list[Jet]]:
    """(D2)-(D3): the normal form to order ``N = len(H)``.

    Parameters
    ----------
    space : JetSpace
        The jets' degree and grid.
    H : sequence of jets
        ``H_1 .. H_N`` of ``H = K0(J) + sum mu^n / n! H_n`` (note the ``n!``).
    omega : sequence of float
        Taylor coefficients ``omega_j`` of ``K0'(J* + x) = sum omega_j x^j``;
        ``omega_0 = p/q`` at a resonance.
    resonance : (int, int)
        ``(p, q)``: the resonance ``p omega_t = q omega_phi`` kept (``k1 p + k2 q = 0``);
        ``p = 0``: none (only ``k = 0`` is kept).

    Returns
    -------
    (list of jets, list of jets)
        ``Ht_1 .. Ht_N`` (same ``n!`` convention) and the generators ``W_1 .. W_N``.
    """
    space = _space(space)
    H = _jets(space, "H", H)
    omega = [float(w) for w in finite_array("omega", omega, ndim=1)]
    if not omega:
        raise ValueError("omega must hold at least omega_0")
    if not isinstance(resonance, (tuple, list)) or len(resonance) != 2:
        raise ArgumentTypeError(f"resonance must be a pair of integers (p, q), got "
                                f"{resonance!r:.60}")
    p, q = (integer("resonance", r, -10**6, 10**6) for r in resonance)
    N = len(H)
    table: dict[tuple[int, int], Jet] = {(0, n): H[n - 1] for n in range(1, N + 1)}
    Ws: list[Jet] = []
    Ht: list[Jet] = []
    for n in range(1, N + 1):
        # the diagonal i + j = n with W_n = 0, from row i - 1
        for i in range(1, n + 1):
            j = n - i
            acc = table[(i - 1, j + 1)].copy() if (i - 1, j + 1) in table else space.zeros()
            for r in range(j + 1):
                if r + 1 > len(Ws):
                    continue      # W_n itself: added below
                if (i - 1, j - r) == (0, 0):
                    continue      # {H0, W}: the homological term, added below
                acc += math.comb(j, r) * space.bracket(table[(i - 1, j - r)], Ws[r])
            table[(i, j)] = acc
        W, _kept = _homological(space, table[(n, 0)], omega, p, q)
        hom = -_omega_dphi(space, W, omega) - space.d_t(W)               # {H0, W_n}
        for i in range(1, n + 1):
            table[(i, n - i)] = table[(i, n - i)] + hom
        Ws.append(W)
        Ht.append(table[(n, 0)])
    return Ht, Ws


def _omega_dphi(space: JetSpace, W: Jet, omega: Sequence[float]) -> Jet:
    """``omega(J* + x) W_phi`` as a jet."""
    dW = space.d_phi(W)
    out = space.zeros()
    for j, w in enumerate(omega):
        if j > space.D:
            break
        out[j:] += w * dW[: space.D + 1 - j]
    return out


def transform(space: JetSpace, f: Jet | None, Ws: Sequence[Jet]) -> list[Jet]:
    """(D4): a function of the old variables expanded in the new ones.

    Parameters
    ----------
    space : JetSpace
        The jets' degree and grid.
    f : jet or None
        The function; ``None``: the angle ``phi`` itself (not a jet: ``{phi, W} = W_J``),
        whose ``ft_0`` is then returned as zero (read ``phi`` for it).
    Ws : sequence of jets
        The generators ``W_1 .. W_N`` of :func:`lie_deprit`.

    Returns
    -------
    list of jets
        ``ft_0 .. ft_N`` with ``f(old) = sum mu^n / n! ft_n(new)``.
    """
    space = _space(space)
    f = None if f is None else _jet(space, "f", f)
    Ws = _jets(space, "Ws", Ws, minimum=0)
    N = len(Ws)
    base = space.zeros() if f is None else f
    table: dict[tuple[int, int], Jet] = {(0, 0): base}
    for n in range(1, N + 1):
        table[(0, n)] = space.zeros()
    out = [base]
    for n in range(1, N + 1):
        for i in range(1, n + 1):
            j = n - i
            acc = table[(i - 1, j + 1)].copy()
            for r in range(j + 1):
                if f is None and (i - 1, j - r) == (0, 0):
                    acc += math.comb(j, r) * space.d_x(Ws[r])            # {phi, W}
                else:
                    acc += math.comb(j, r) * space.bracket(table[(i - 1, j - r)], Ws[r])
            table[(i, j)] = acc
        out.append(table[(n, 0)])
    return out
