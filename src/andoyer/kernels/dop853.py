r"""Dormand-Prince 8(5,3) (Hairer's DOP853) in Numba, on the Euler-Poisson field (1).

An explicit Runge-Kutta method of order 8 with 12 stages (the 13th is the first
stage of the next step, FSAL), a 5th-order error estimate corrected by a 3rd-order
one, step-size control as in Hairer's ``dop853.f`` / :class:`scipy.integrate.DOP853`,
and a dense output of order 7 that costs 3 extra stages per step where it is needed
[1]_, [2]_. The method is written once, for any right-hand side: :func:`make_stepper`
builds it for a compiled ``field(t, y, p, out)`` of any dimension. The entry points
below use the generated Lie-Poisson field :func:`andoyer.kernels.numba.ep_field` of
Eq. (1) (:func:`ep_rhs`, the stepper :data:`EP`), on states ordered as
:data:`andoyer.charts.euler_poisson.STATE`; :mod:`andoyer.kernels.tangent` uses the
same stepper on the variational equations.

Everything here works on plain float arrays, ``y`` of shape ``(n_orbits, 6)`` and
``p`` = the 8 kernel parameters :data:`PARAMS`; there is no validation (the
friendly layer validates) and no Python callback per step or per crossing.

Entry points (compiled with ``cache=True`` into the folder
:func:`andoyer.kernels.cache.cache_folder`; each orbit independent):

* :func:`propagate` -- states at given output times, read off the dense output;
* :func:`locate_crossings` -- the first crossings of a section
  ``f(y) = 0`` (from :func:`andoyer.kernels.generated.section`), each root located
  on the dense output polynomial;
* both run blocks of orbits in threads (:func:`andoyer.kernels.threads.over_orbits`)
  through the compiled, nogil :func:`propagate_block` and
  :func:`locate_crossings_block`;
* :func:`integrate_fixed`, :func:`interpolate_step` -- fixed steps without control
  and the interpolant of one step, for measuring the orders of the method.

Each returns an ``info`` array of shape ``(n_orbits, 4)`` whose columns are
:data:`INFO`: the status (:data:`SUCCESS`, :data:`STEP_TOO_SMALL`,
:data:`MAX_STEPS`), accepted steps, rejected steps and evaluations of the field.

Notes
-----
Step control. With the stages :math:`k_i`, the error estimates
:math:`\mathrm{err}_5 = \sum_i e^{(5)}_i k_i` and
:math:`\mathrm{err}_3 = \sum_i (b_i - \hat b_i) k_i`, scaled componentwise by
:math:`sc_j = \mathrm{atol} + \mathrm{rtol}\max(|y_j|, |y_{1,j}|)`, are combined as

.. math::
   \mathrm{err} = |h|\,\frac{\|\mathrm{err}_5\|^2}
   {\sqrt{N\,(\|\mathrm{err}_5\|^2 + 0.01\,\|\mathrm{err}_3\|^2)}}

and a step is accepted when :math:`\mathrm{err} < 1`; the next step is
:math:`h \min(10, 0.9\,\mathrm{err}^{-1/8})` (at least :math:`h/5` after a
rejection, at most :math:`h` right after one).

Dense output. With :math:`\theta = (t - t_0)/h`,

.. math::
   y(t_0 + \theta h) = y_0 + \theta\,(r_1 + (1-\theta)\,(r_2 + \theta\,(r_3
   + (1-\theta)\,(r_4 + \theta\,(r_5 + (1-\theta)\,(r_6 + \theta r_7))))))

where :math:`r_1 = y_1 - y_0`, :math:`r_2 = h k_1 - r_1`,
:math:`r_3 = 2 r_1 - h (k_1 + k_{13})` and :math:`r_{4..7} = h \sum_i d_{\cdot i} k_i`
use the three extra stages 14-16 (``contd8`` of [2]_).

Section crossings. After each accepted step the section function ``f`` is evaluated
at the step end; a sign change in the requested direction is bracketed by the step and
the root is found by Brent's method on :math:`f(y(t_0 + \theta h))` to
:math:`|\Delta\theta| \approx 4\varepsilon` (so ``|f|`` is at its round-off level, far
below 1e-12 of its scale, at any t). The crossing is kept if the margin ``w`` of the
section is positive at the root (for an angle section this rejects the root where the
angle is ``value + pi``: no spurious crossings at the wrap). A pair of roots inside
one step (the orbit dips through the section and back) changes no sign; it can only
hide next to a discrete local minimum of ``|f|`` over the step ends, so the two steps
around each such minimum are searched on their dense output (golden section for the
closest approach, then Brent on each side). This costs a few dense outputs per
oscillation of ``f``, not per step.

Compilation cache. Numba's cache is keyed on the source of the file that defines a
function, not on the functions it calls, so a regenerated
:mod:`andoyer.kernels.generated` would otherwise be served stale machine code. The
cached entry points are therefore built by a factory closing over :data:`KERNEL_STAMP`
(a hash of the generated kernels and their Numba wrappers), which Numba hashes into
the cache key; the helpers they call are not cached themselves (their code is part
of each entry point's cached library). The stepper's pieces close over their field
(:func:`make_stepper`) instead of taking it as an argument: a compiled function
passed as a value is lowered as a run-time address, which Numba refuses to cache.

References
----------
.. [1] E. Hairer, S. P. Norsett, G. Wanner, *Solving Ordinary Differential Equations I:
   Nonstiff Problems*, 2nd ed., Springer (1993), Sec. II.5 (DOP853) and II.6
   (dense output).
.. [2] E. Hairer, ``dop853.f``, http://www.unige.ch/~hairer/software.html.
"""

from __future__ import annotations

import hashlib
import math
from pathlib import Path
from typing import Any, NamedTuple

import numba
import numpy as np

from andoyer.kernels import generated
from andoyer.kernels import numba as _kernels
from andoyer.kernels.cache import cached_njit
from andoyer.kernels.constants import T_START
from andoyer.kernels.numba import ep_field
from andoyer.kernels.threads import over_orbits

__all__ = [
    "make_stepper",
    "Stepper",
    "EP",
    "ep_rhs",
    "source_stamp",
    "FASTMATH",
    "PARAMS",
    "INFO",
    "SUCCESS",
    "STEP_TOO_SMALL",
    "MAX_STEPS",
    "STATUS_MESSAGES",
    "KERNEL_STAMP",
    "propagate",
    "locate_crossings",
    "propagate_block",
    "locate_crossings_block",
    "ensemble_propagate",
    "ensemble_crossings",
    "integrate_fixed",
    "interpolate_step",
]

#: Names of the 8 kernel parameters ``p`` (the Engine's ``params``), in order.
PARAMS = ("a", "b", "c", "mu", "e1", "e2", "e3", "phi0")
#: Columns of the ``info`` arrays returned by every entry point.
INFO = ("status", "accepted", "rejected", "nfev")
#: Status codes (column ``"status"`` of ``info``).
SUCCESS, STEP_TOO_SMALL, MAX_STEPS = 0, 1, 2
STATUS_MESSAGES = {
    SUCCESS: "success",
    STEP_TOO_SMALL: "step size fell below 10 ulp of t (non-finite or too stiff state)",
    MAX_STEPS: "maximum number of steps reached",
}

# Dimension of the Euler-Poisson state (G1, G2, G3, gamma1, gamma2, gamma3).
N = 6

# ----------------------------------------------------------------------------------
# Coefficients of DOP853 in Hairer's notation: c_i, a_ij, b_i, the error weights
# er_i (5th order) and bhh_i (3rd order), the dense-output weights d_ij. A[i, j] is
# a_{i+1, j+1} of dop853.f (0-based here). The numbers are copied from SciPy's
# ``scipy/integrate/_ivp/dop853_coefficients.py`` (BSD-3-Clause, (c) SciPy
# developers), which transcribes dop853.f; tests/kernels/test_dop853.py checks they agree.
# ----------------------------------------------------------------------------------

#: Stages of a step (the 13th, FSAL, is the first of the next step).
N_STAGES = 12
#: Stages including the three extra ones of the dense output.
N_STAGES_EXTENDED = 16
#: Degree of the dense-output polynomial.
INTERPOLATOR_POWER = 7

#: Nodes c_i (stages 1-12, the FSAL stage 13, the extra stages 14-16).
C = np.array([0.0,
              0.526001519587677318785587544488e-01,
              0.789002279381515978178381316732e-01,
              0.118350341907227396726757197510,
              0.281649658092772603273242802490,
              0.333333333333333333333333333333,
              0.25,
              0.307692307692307692307692307692,
              0.651282051282051282051282051282,
              0.6,
              0.857142857142857142857142857142,
              1.0,
              1.0,
              0.1,
              0.2,
              0.777777777777777777777777777778])

#: Runge-Kutta matrix a_ij, row i for stage i + 1; row 12 (FSAL) holds the b_i.
A = np.zeros((N_STAGES_EXTENDED, N_STAGES_EXTENDED))
A[1, 0] = 5.26001519587677318785587544488e-2

A[2, 0] = 1.97250569845378994544595329183e-2
A[2, 1] = 5.91751709536136983633785987549e-2

A[3, 0] = 2.95875854768068491816892993775e-2
A[3, 2] = 8.87627564304205475450678981324e-2

A[4, 0] = 2.41365134159266685502369798665e-1
A[4, 2] = -8.84549479328286085344864962717e-1
A[4, 3] = 9.24834003261792003115737966543e-1

A[5, 0] = 3.7037037037037037037037037037e-2
A[5, 3] = 1.70828608729473871279604482173e-1
A[5, 4] = 1.25467687566822425016691814123e-1

A[6, 0] = 3.7109375e-2
A[6, 3] = 1.70252211019544039314978060272e-1
A[6, 4] = 6.02165389804559606850219397283e-2
A[6, 5] = -1.7578125e-2

A[7, 0] = 3.70920001185047927108779319836e-2
A[7, 3] = 1.70383925712239993810214054705e-1
A[7, 4] = 1.07262030446373284651809199168e-1
A[7, 5] = -1.53194377486244017527936158236e-2
A[7, 6] = 8.27378916381402288758473766002e-3

A[8, 0] = 6.24110958716075717114429577812e-1
A[8, 3] = -3.36089262944694129406857109825
A[8, 4] = -8.68219346841726006818189891453e-1
A[8, 5] = 2.75920996994467083049415600797e1
A[8, 6] = 2.01540675504778934086186788979e1
A[8, 7] = -4.34898841810699588477366255144e1

A[9, 0] = 4.77662536438264365890433908527e-1
A[9, 3] = -2.48811461997166764192642586468
A[9, 4] = -5.90290826836842996371446475743e-1
A[9, 5] = 2.12300514481811942347288949897e1
A[9, 6] = 1.52792336328824235832596922938e1
A[9, 7] = -3.32882109689848629194453265587e1
A[9, 8] = -2.03312017085086261358222928593e-2

A[10, 0] = -9.3714243008598732571704021658e-1
A[10, 3] = 5.18637242884406370830023853209
A[10, 4] = 1.09143734899672957818500254654
A[10, 5] = -8.14978701074692612513997267357
A[10, 6] = -1.85200656599969598641566180701e1
A[10, 7] = 2.27394870993505042818970056734e1
A[10, 8] = 2.49360555267965238987089396762
A[10, 9] = -3.0467644718982195003823669022

A[11, 0] = 2.27331014751653820792359768449
A[11, 3] = -1.05344954667372501984066689879e1
A[11, 4] = -2.00087205822486249909675718444
A[11, 5] = -1.79589318631187989172765950534e1
A[11, 6] = 2.79488845294199600508499808837e1
A[11, 7] = -2.85899827713502369474065508674
A[11, 8] = -8.87285693353062954433549289258
A[11, 9] = 1.23605671757943030647266201528e1
A[11, 10] = 6.43392746015763530355970484046e-1

A[12, 0] = 5.42937341165687622380535766363e-2
A[12, 5] = 4.45031289275240888144113950566
A[12, 6] = 1.89151789931450038304281599044
A[12, 7] = -5.8012039600105847814672114227
A[12, 8] = 3.1116436695781989440891606237e-1
A[12, 9] = -1.52160949662516078556178806805e-1
A[12, 10] = 2.01365400804030348374776537501e-1
A[12, 11] = 4.47106157277725905176885569043e-2

A[13, 0] = 5.61675022830479523392909219681e-2
A[13, 6] = 2.53500210216624811088794765333e-1
A[13, 7] = -2.46239037470802489917441475441e-1
A[13, 8] = -1.24191423263816360469010140626e-1
A[13, 9] = 1.5329179827876569731206322685e-1
A[13, 10] = 8.20105229563468988491666602057e-3
A[13, 11] = 7.56789766054569976138603589584e-3
A[13, 12] = -8.298e-3

A[14, 0] = 3.18346481635021405060768473261e-2
A[14, 5] = 2.83009096723667755288322961402e-2
A[14, 6] = 5.35419883074385676223797384372e-2
A[14, 7] = -5.49237485713909884646569340306e-2
A[14, 10] = -1.08347328697249322858509316994e-4
A[14, 11] = 3.82571090835658412954920192323e-4
A[14, 12] = -3.40465008687404560802977114492e-4
A[14, 13] = 1.41312443674632500278074618366e-1

A[15, 0] = -4.28896301583791923408573538692e-1
A[15, 5] = -4.69762141536116384314449447206
A[15, 6] = 7.68342119606259904184240953878
A[15, 7] = 4.06898981839711007970213554331
A[15, 8] = 3.56727187455281109270669543021e-1
A[15, 12] = -1.39902416515901462129418009734e-3
A[15, 13] = 2.9475147891527723389556272149
A[15, 14] = -9.15095847217987001081870187138

#: Weights b_i of the 8th-order solution (row 12 of A: stage 13 is the FSAL stage).
B = A[N_STAGES, :N_STAGES]

#: Error weights er_i of dop853.f: the 5th-order error estimate is sum_i ER_i k_i.
ER = np.zeros(N_STAGES + 1)
ER[0] = 0.1312004499419488073250102996e-1
ER[5] = -0.1225156446376204440720569753e+1
ER[6] = -0.4957589496572501915214079952
ER[7] = 0.1664377182454986536961530415e+1
ER[8] = -0.3503288487499736816886487290
ER[9] = 0.3341791187130174790297318841
ER[10] = 0.8192320648511571246570742613e-1
ER[11] = -0.2235530786388629525884427845e-1

#: Weights bhh_i of the embedded 3rd-order solution (stages 1, 9, 12).
BHH = np.zeros(N_STAGES)
BHH[0] = 0.244094488188976377952755905512
BHH[8] = 0.733846688281611857341361741547
BHH[11] = 0.220588235294117647058823529412e-1

#: 3rd-order error weights b_i - bhh_i (the FSAL stage has weight 0).
E3 = np.zeros(N_STAGES + 1)
E3[:N_STAGES] = B - BHH

#: Dense-output weights d_ij of dop853.f: row r gives r_{r+4} = h sum_j D[r, j] k_j.
D = np.zeros((INTERPOLATOR_POWER - 3, N_STAGES_EXTENDED))
D[0, 0] = -0.84289382761090128651353491142e+1
D[0, 5] = 0.56671495351937776962531783590
D[0, 6] = -0.30689499459498916912797304727e+1
D[0, 7] = 0.23846676565120698287728149680e+1
D[0, 8] = 0.21170345824450282767155149946e+1
D[0, 9] = -0.87139158377797299206789907490
D[0, 10] = 0.22404374302607882758541771650e+1
D[0, 11] = 0.63157877876946881815570249290
D[0, 12] = -0.88990336451333310820698117400e-1
D[0, 13] = 0.18148505520854727256656404962e+2
D[0, 14] = -0.91946323924783554000451984436e+1
D[0, 15] = -0.44360363875948939664310572000e+1
D[1, 0] = 0.10427508642579134603413151009e+2
D[1, 5] = 0.24228349177525818288430175319e+3
D[1, 6] = 0.16520045171727028198505394887e+3
D[1, 7] = -0.37454675472269020279518312152e+3
D[1, 8] = -0.22113666853125306036270938578e+2
D[1, 9] = 0.77334326684722638389603898808e+1
D[1, 10] = -0.30674084731089398182061213626e+2
D[1, 11] = -0.93321305264302278729567221706e+1
D[1, 12] = 0.15697238121770843886131091075e+2
D[1, 13] = -0.31139403219565177677282850411e+2
D[1, 14] = -0.93529243588444783865713862664e+1
D[1, 15] = 0.35816841486394083752465898540e+2
D[2, 0] = 0.19985053242002433820987653617e+2
D[2, 5] = -0.38703730874935176555105901742e+3
D[2, 6] = -0.18917813819516756882830838328e+3
D[2, 7] = 0.52780815920542364900561016686e+3
D[2, 8] = -0.11573902539959630126141871134e+2
D[2, 9] = 0.68812326946963000169666922661e+1
D[2, 10] = -0.10006050966910838403183860980e+1
D[2, 11] = 0.77771377980534432092869265740
D[2, 12] = -0.27782057523535084065932004339e+1
D[2, 13] = -0.60196695231264120758267380846e+2
D[2, 14] = 0.84320405506677161018159903784e+2
D[2, 15] = 0.11992291136182789328035130030e+2
D[3, 0] = -0.25693933462703749003312586129e+2
D[3, 5] = -0.15418974869023643374053993627e+3
D[3, 6] = -0.23152937917604549567536039109e+3
D[3, 7] = 0.35763911791061412378285349910e+3
D[3, 8] = 0.93405324183624310003907691704e+2
D[3, 9] = -0.37458323136451633156875139351e+2
D[3, 10] = 0.10409964950896230045147246184e+3
D[3, 11] = 0.29840293426660503123344363579e+2
D[3, 12] = -0.43533456590011143754432175058e+2
D[3, 13] = 0.96324553959188282948394950600e+2
D[3, 14] = -0.39177261675615439165231486172e+2
D[3, 15] = -0.14972683625798562581422125276e+3


# Step-size control (Hairer; scipy.integrate._ivp.rk).
SAFETY = 0.9
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0
ERROR_EXPONENT = -1.0 / 8.0
# Brent's method on the dense output: tolerance on theta = (t - t0)/h and iterations.
ROOT_XTOL = 4.0 * np.finfo(np.float64).eps
ROOT_MAXITER = 100
# Golden-section search for a pair of roots inside one step: ratio and tolerance.
GOLDEN = 0.5 * (math.sqrt(5.0) - 1.0)
GRAZE_XTOL = 1e-9


def source_stamp(*files: str | Path) -> str:
    """SHA-256 of the bytes of ``files``: a cache key for compiled entry points whose
    helpers live in other modules (see the module notes)."""
    h = hashlib.sha256()
    for f in files:
        h.update(Path(f).read_bytes())
    return h.hexdigest()


#: Hash of the generated kernels and their Numba wrappers, part of the cache key.
KERNEL_STAMP = source_stamp(generated.__file__ or "", _kernels.__file__ or "")

# Helpers: compiled into the entry points that call them (not cached on their own,
# see the module notes).
#: LLVM fast-math flags of every kernel: reassociation and contraction (FMA) let LLVM
#: vectorise the stage sums and error norm; reciprocals replace divisions. Not
#: ``nnan``/``ninf``: the step control relies on NaN comparisons to stop a non-finite
#: orbit. Measured 1.3x faster steps at the same accuracy.
FASTMATH = {"reassoc", "contract", "arcp"}
_jit = numba.njit(nogil=True, fastmath=FASTMATH)
_section = _jit(generated.section)


@_jit
def ep_rhs(t, y, p, out):
    """The field (1) in the stepper's form ``field(t, y, p, out)``: ``out = f(y)``.

    ``y`` in the order of STATE = (G1, G2, G3, gamma1, gamma2, gamma3), ``p`` of
    :data:`PARAMS`; ``t`` is not used (the flow is autonomous).
    """
    out[0], out[1], out[2], out[3], out[4], out[5] = ep_field(
        y[0], y[1], y[2], y[3], y[4], y[5], p[0], p[1], p[2], p[3], p[4], p[5], p[6])


@_jit
def _section_fw(y, p, kind, value, cv, sv):
    # The section reads the Euler-Poisson state, the first six components of y.
    return _section(kind, y[0], y[1], y[2], y[3], y[4], y[5], p[7], value, cv, sv)


@_jit
def _error_norm(y, y1, K, h, rtol, atol):
    n = y.shape[0]
    e5 = 0.0
    e3 = 0.0
    for i in range(n):
        s5 = 0.0
        s3 = 0.0
        for j in range(N_STAGES):
            s5 += ER[j] * K[j, i]
            s3 += E3[j] * K[j, i]
        sc = atol + rtol * max(abs(y[i]), abs(y1[i]))
        e5 += (s5 / sc) ** 2
        e3 += (s3 / sc) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * n)


@_jit
def _dense_eval(F, y, x, out):
    """``y(t0 + x h)`` from the dense-output rows ``F`` of a step starting at ``y``."""
    x1 = 1.0 - x
    for i in range(y.shape[0]):
        v = F[6, i] * x
        v = (F[5, i] + v) * x1
        v = (F[4, i] + v) * x
        v = (F[3, i] + v) * x1
        v = (F[2, i] + v) * x
        v = (F[1, i] + v) * x1
        v = (F[0, i] + v) * x
        out[i] = y[i] + v


@_jit
def _f_at(F, y, x, p, kind, value, cv, sv, ytmp):
    _dense_eval(F, y, x, ytmp)
    return _section_fw(ytmp, p, kind, value, cv, sv)[0]


@_jit
def _root(F, y, p, kind, value, cv, sv, xa, xb, fa, fb, ytmp):
    """Root in ``[xa, xb]`` of ``f(y(t0 + theta h))`` with ``f(xa) = fa``, ``f(xb) = fb``
    of opposite signs: Brent's method as in scipy's ``brentq``, to ``ROOT_XTOL``."""
    xpre, xcur = xa, xb
    fpre, fcur = fa, fb
    xblk, fblk = xa, 0.0
    spre, scur = 0.0, 0.0
    if fpre == 0.0:
        return xpre
    if fcur == 0.0:
        return xcur
    for _ in range(ROOT_MAXITER):
        if fpre != 0.0 and fcur != 0.0 and (fpre < 0.0) != (fcur < 0.0):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = 0.5 * ROOT_XTOL * (1.0 + abs(xcur))
        sbis = 0.5 * (xblk - xcur)
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:  # secant
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:  # inverse quadratic interpolation
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
                spre, scur = scur, stry
            else:
                spre, scur = sbis, sbis
        else:
            spre, scur = sbis, sbis
        xpre, fpre = xcur, fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0.0 else -delta
        fcur = _f_at(F, y, xcur, p, kind, value, cv, sv, ytmp)
    return xcur


@_jit
def _closest_approach(F, y, p, kind, value, cv, sv, sign, ytmp):
    """``(theta, f)`` where ``sign * f`` is least on the step (golden-section search,
    assuming one minimum in the step)."""
    a, b = 0.0, 1.0
    x1 = b - GOLDEN * (b - a)
    x2 = a + GOLDEN * (b - a)
    f1 = sign * _f_at(F, y, x1, p, kind, value, cv, sv, ytmp)
    f2 = sign * _f_at(F, y, x2, p, kind, value, cv, sv, ytmp)
    while b - a > GRAZE_XTOL and f1 > 0.0 and f2 > 0.0:
        if f1 < f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - GOLDEN * (b - a)
            f1 = sign * _f_at(F, y, x1, p, kind, value, cv, sv, ytmp)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + GOLDEN * (b - a)
            f2 = sign * _f_at(F, y, x2, p, kind, value, cv, sv, ytmp)
    if f1 < f2:
        return x1, sign * f1
    return x2, sign * f2


@_jit
def _record(F, y, t, h, p, kind, value, cv, sv, direction, xa, xb, fa, fb, tc, yc,
            count, ytmp):
    """Locate the root bracketed by ``[xa, xb]`` of a step and append it to ``tc, yc``
    if its direction is wanted and the margin ``w`` is positive; returns the count."""
    up = fa < 0.0
    if count >= tc.shape[0] or (up and direction < 0) or (not up and direction > 0):
        return count
    theta = _root(F, y, p, kind, value, cv, sv, xa, xb, fa, fb, ytmp)
    _dense_eval(F, y, theta, ytmp)
    # The margin w > 0 tells the section from its antipode (angle = value + pi); a root
    # at t <= T_START is the initial state lying on the section to round-off.
    if _section_fw(ytmp, p, kind, value, cv, sv)[1] > 0.0 and t + theta * h > T_START:
        tc[count] = t + theta * h
        for i in range(ytmp.shape[0]):
            yc[count, i] = ytmp[i]
        count += 1
    return count



class Stepper(NamedTuple):
    """The DOP853 pieces of one right-hand side, built by :func:`make_stepper`."""

    stages: Any
    initial_step: Any
    step: Any
    dense_coefficients: Any
    propagate_orbit: Any
    crossings_orbit: Any


def make_stepper(field: Any) -> Stepper:
    """DOP853 with dense output and section crossings for ``dy/dt = field(t, y)``.

    ``field(t, y, p, out)`` is a Numba-compiled function writing the right-hand side at
    ``(t, y)`` with parameters ``p`` (an array) into ``out``; the dimension is
    ``len(y)`` (at least 6: sections read the Euler-Poisson state ``y[:6]``).

    The pieces close over ``field`` (a closure variable is bound at compile time, so the
    call is static and inlined; a function passed as an argument would be a dynamic
    address, which Numba cannot cache). They are not cached themselves: bind them to
    module globals and call them from cached entry points, whose cache key must then
    cover this module and the field's (see :func:`source_stamp`).

    Returns
    -------
    Stepper
        ``propagate_orbit(y0, t_out, p, rtol, atol, max_steps, out, info)`` (one orbit,
        ``out[j] = y(t_out[j])``) and ``crossings_orbit(y0, p, kind, value, direction,
        t_max, rtol, atol, max_steps, tc, yc, info)`` (the first ``len(tc)`` crossings,
        returns their number), with the stages, starting step, controlled step and dense
        output they use.
    """

    @_jit
    def stages(t, y, h, p, K, ytmp, first, last):
        """Stages ``first .. last-1`` into ``K`` (``K[:first]`` known); ``ytmp`` ends as the
        argument of the last stage (``y + h sum_j B_j k_j`` = y1 when ``last = 13``)."""
        n = y.shape[0]
        for s in range(first, last):
            if n == N:  # the field (1) alone: six accumulators in registers, 1.7x faster
                s0 = s1 = s2 = s3 = s4 = s5 = 0.0
                for j in range(s):
                    w = A[s, j]
                    if w != 0.0:
                        s0 += w * K[j, 0]
                        s1 += w * K[j, 1]
                        s2 += w * K[j, 2]
                        s3 += w * K[j, 3]
                        s4 += w * K[j, 4]
                        s5 += w * K[j, 5]
                ytmp[0] = y[0] + h * s0
                ytmp[1] = y[1] + h * s1
                ytmp[2] = y[2] + h * s2
                ytmp[3] = y[3] + h * s3
                ytmp[4] = y[4] + h * s4
                ytmp[5] = y[5] + h * s5
                field(t + C[s] * h, ytmp, p, K[s])
                continue
            for i in range(n):
                ytmp[i] = 0.0
            for j in range(s):
                w = A[s, j]
                if w != 0.0:
                    for i in range(n):
                        ytmp[i] += w * K[j, i]
            for i in range(n):
                ytmp[i] = y[i] + h * ytmp[i]
            field(t + C[s] * h, ytmp, p, K[s])

    @_jit
    def initial_step(t, y, f0, p, interval, rtol, atol, ytmp, f1):
        """Hairer's starting step (``hinit``; scipy's ``select_initial_step``, order 7)."""
        n = y.shape[0]
        d0 = 0.0
        d1 = 0.0
        for i in range(n):
            sc = atol + abs(y[i]) * rtol
            d0 += (y[i] / sc) ** 2
            d1 += (f0[i] / sc) ** 2
        d0 = math.sqrt(d0 / n)
        d1 = math.sqrt(d1 / n)
        h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
        h0 = min(h0, interval)
        for i in range(n):
            ytmp[i] = y[i] + h0 * f0[i]
        field(t + h0, ytmp, p, f1)
        d2 = 0.0
        for i in range(n):
            sc = atol + abs(y[i]) * rtol
            d2 += ((f1[i] - f0[i]) / sc) ** 2
        d2 = math.sqrt(d2 / n) / h0
        if d1 <= 1e-15 and d2 <= 1e-15:
            h1 = max(1e-6, h0 * 1e-3)
        else:
            h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
        return min(100.0 * h0, h1, interval)

    @_jit
    def step(t, y, h_abs, t_end, p, rtol, atol, K, ytmp, y1, info):
        """One accepted step from ``(t, y)`` with ``K[0] = f(t, y)``, at most to ``t_end``.

        Returns ``(status, t1, h, h_abs_next)``; on success ``y1`` holds the new state,
        ``K[:13]`` the stages (``K[12] = f(t1, y1)``).
        """
        n = y.shape[0]
        rejected = False
        while True:
            min_step = 10.0 * (np.nextafter(t, np.inf) - t)
            if not h_abs >= min_step:  # also catches h_abs = NaN (a non-finite state)
                return STEP_TOO_SMALL, t, 0.0, h_abs
            t1 = t + h_abs
            if t1 > t_end:
                t1 = t_end
            h = t1 - t
            stages(t, y, h, p, K, ytmp, 1, N_STAGES + 1)
            info[3] += N_STAGES
            err = _error_norm(y, ytmp, K, h, rtol, atol)
            if err < 1.0:
                if err == 0.0:
                    factor = MAX_FACTOR
                else:
                    factor = min(MAX_FACTOR, SAFETY * err ** ERROR_EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                for i in range(n):
                    y1[i] = ytmp[i]
                info[1] += 1
                return SUCCESS, t1, h, abs(h) * factor
            # Also for err = NaN (a non-finite state): shrink until min_step stops it.
            if err == err:
                h_abs = abs(h) * max(MIN_FACTOR, SAFETY * err ** ERROR_EXPONENT)
            else:
                h_abs = abs(h) * MIN_FACTOR
            rejected = True
            info[2] += 1

    @_jit
    def dense_coefficients(t, y, y1, h, p, K, ytmp, F):
        """The 7 rows ``r_1 .. r_7`` of the dense output of the step ``y -> y1`` (size h)."""
        n = y.shape[0]
        stages(t, y, h, p, K, ytmp, N_STAGES + 1, N_STAGES_EXTENDED)
        for i in range(n):
            dy = y1[i] - y[i]
            F[0, i] = dy
            F[1, i] = h * K[0, i] - dy
            F[2, i] = 2.0 * dy - h * (K[N_STAGES, i] + K[0, i])
            for r in range(INTERPOLATOR_POWER - 3):
                acc = 0.0
                for j in range(N_STAGES_EXTENDED):
                    acc += D[r, j] * K[j, i]
                F[3 + r, i] = h * acc

    @_jit
    def graze(y, y1, t, h, p, K, F, kind, value, cv, sv, direction, f0, tc, yc, count,
               ytmp, info):
        """Two roots inside one step (the orbit dips through the section and back): look
        for them where ``|f|`` has a discrete local minimum; returns the count."""
        sign = 1.0 if f0 > 0.0 else -1.0
        dense_coefficients(t, y, y1, h, p, K, ytmp, F)
        info[3] += N_STAGES_EXTENDED - N_STAGES - 1
        theta, fmin = _closest_approach(F, y, p, kind, value, cv, sv, sign, ytmp)
        if sign * fmin < 0.0:
            f1 = _f_at(F, y, 1.0, p, kind, value, cv, sv, ytmp)
            count = _record(F, y, t, h, p, kind, value, cv, sv, direction, 0.0, theta, f0,
                            fmin, tc, yc, count, ytmp)
            count = _record(F, y, t, h, p, kind, value, cv, sv, direction, theta, 1.0, fmin,
                            f1, tc, yc, count, ytmp)
        return count

    @_jit
    def propagate_orbit(y0, t_out, p, rtol, atol, max_steps, out, info):
        """One orbit of ``dy/dt = field(t, y)``: ``out[j] = y(t_out[j])`` (rows not reached
        stay as they are); ``info`` (4,) counts as the columns :data:`INFO`.

        ``field(t, y, p, out)`` writes the right-hand side into ``out``; the dimension is
        ``len(y0)``. Not cached itself: compiled into the caller's entry point.
        """
        dim = y0.shape[0]
        k = t_out.shape[0]
        for i in range(dim):
            out[0, i] = y0[i]
        if k == 1:
            return
        y = y0.copy()
        y1 = np.empty(dim)
        ytmp = np.empty(dim)
        f1 = np.empty(dim)
        K = np.empty((N_STAGES_EXTENDED, dim))
        F = np.empty((INTERPOLATOR_POWER, dim))
        t = t_out[0]
        t_end = t_out[k - 1]
        field(t, y, p, K[0])
        h_abs = initial_step(t, y, K[0], p, t_end - t, rtol, atol, ytmp, f1)
        info[3] += 2
        j = 1
        while j < k and t_out[j] <= t:  # repeated initial times
            for i in range(dim):
                out[j, i] = y0[i]
            j += 1
        while j < k:
            if info[1] >= max_steps:
                info[0] = MAX_STEPS
                return
            status, t1, h, h_abs = step(t, y, h_abs, t_end, p, rtol, atol, K, ytmp, y1,
                                         info)
            if status != SUCCESS:
                info[0] = status
                return
            dense = False
            while j < k and t_out[j] <= t1:
                if t_out[j] == t1:
                    for i in range(dim):
                        out[j, i] = y1[i]
                else:
                    if not dense:
                        dense_coefficients(t, y, y1, h, p, K, ytmp, F)
                        info[3] += N_STAGES_EXTENDED - N_STAGES - 1
                        dense = True
                    _dense_eval(F, y, (t_out[j] - t) / h, out[j])
                j += 1
            t = t1
            for i in range(dim):
                y[i] = y1[i]
                K[0, i] = K[N_STAGES, i]

    @_jit
    def crossings_orbit(y0, p, kind, value, direction, t_max, rtol, atol, max_steps,
                        tc, yc, info):
        """One orbit of ``dy/dt = field(t, y)``: the first ``len(tc)`` crossings in
        ``(0, t_max]`` of the section ``(kind, value)`` of the first six components (the
        Euler-Poisson state); returns their number. ``yc`` has rows of ``len(y0)``.

        A sign change of ``f`` over a step brackets one root. A pair of roots inside one
        step leaves no sign change; it can only hide next to a discrete local minimum of
        ``|f|`` over the step ends, so the two steps around each such minimum (same sign
        of ``f`` throughout) are searched on their dense output. The previous step's
        stages are kept for that (two stage buffers, swapped after each step).
        """
        dim = y0.shape[0]
        n_crossings = tc.shape[0]
        if n_crossings == 0 or t_max <= 0.0:
            return 0
        cv = math.cos(value)
        sv = math.sin(value)
        y = y0.copy()
        y1 = np.empty(dim)
        y_prev = np.empty(dim)
        ytmp = np.empty(dim)
        f1 = np.empty(dim)
        K = np.empty((N_STAGES_EXTENDED, dim))
        K_prev = np.empty((N_STAGES_EXTENDED, dim))
        F = np.empty((INTERPOLATOR_POWER, dim))
        t = 0.0
        t_prev = 0.0
        h_prev = 0.0
        field(t, y, p, K[0])
        h_abs = initial_step(t, y, K[0], p, t_max, rtol, atol, ytmp, f1)
        info[3] += 2
        f_prev = _section_fw(y, p, kind, value, cv, sv)[0]
        f_prev2 = np.nan  # f one step further back (none yet)
        count = 0
        while count < n_crossings and t < t_max:
            if info[1] >= max_steps:
                info[0] = MAX_STEPS
                return count
            status, t1, h, h_abs = step(t, y, h_abs, t_max, p, rtol, atol, K, ytmp, y1,
                                         info)
            if status != SUCCESS:
                info[0] = status
                return count
            f_new = _section_fw(y1, p, kind, value, cv, sv)[0]
            if (f_prev < 0.0 and f_new >= 0.0) or (f_prev > 0.0 and f_new <= 0.0):
                if f_new == 0.0:  # the root is the step end itself
                    if (f_prev < 0.0 and direction >= 0) or (f_prev > 0.0 and direction <= 0):
                        if _section_fw(y1, p, kind, value, cv, sv)[1] > 0.0:
                            tc[count] = t1
                            for i in range(dim):
                                yc[count, i] = y1[i]
                            count += 1
                else:
                    dense_coefficients(t, y, y1, h, p, K, ytmp, F)
                    info[3] += N_STAGES_EXTENDED - N_STAGES - 1
                    count = _record(F, y, t, h, p, kind, value, cv, sv, direction, 0.0, 1.0,
                                    f_prev, f_new, tc, yc, count, ytmp)
            elif f_prev != 0.0 and (f_prev > 0.0) == (f_new > 0.0) and f_new != 0.0:
                a_prev = abs(f_prev)
                if f_prev2 != f_prev2:  # first step: t = 0 counts as a minimum if |f| grows
                    if a_prev <= abs(f_new):
                        count = graze(y, y1, t, h, p, K, F, kind, value, cv, sv, direction,
                                       f_prev, tc, yc, count, ytmp, info)
                elif ((f_prev2 > 0.0) == (f_prev > 0.0) and f_prev2 != 0.0
                      and a_prev < abs(f_prev2) and a_prev <= abs(f_new)):
                    count = graze(y_prev, y, t_prev, h_prev, p, K_prev, F, kind, value,
                                   cv, sv, direction, f_prev2, tc, yc, count, ytmp, info)
                    count = graze(y, y1, t, h, p, K, F, kind, value, cv, sv, direction,
                                   f_prev, tc, yc, count, ytmp, info)
                if t1 >= t_max and abs(f_new) < abs(f_prev):  # the end is a minimum too
                    count = graze(y, y1, t, h, p, K, F, kind, value, cv, sv, direction,
                                   f_prev, tc, yc, count, ytmp, info)
            f_prev2 = f_prev
            f_prev = f_new
            t_prev = t
            h_prev = h
            t = t1
            K, K_prev = K_prev, K
            for i in range(dim):
                y_prev[i] = y[i]
                y[i] = y1[i]
                K[0, i] = K_prev[N_STAGES, i]
        return count

    return Stepper(stages, initial_step, step, dense_coefficients, propagate_orbit,
                   crossings_orbit)


#: The stepper of the Euler-Poisson field (1).
EP = make_stepper(ep_rhs)
_ep_propagate_orbit = EP.propagate_orbit
_ep_crossings_orbit = EP.crossings_orbit
_ep_stages = EP.stages
_ep_dense_coefficients = EP.dense_coefficients


def _build(stamp: str) -> tuple[Any, Any, Any, Any]:
    """The cached entry points. Each reads ``stamp`` (a no-op) so that it is a closure
    variable, which Numba hashes into the cache key; an ``assert`` would not do: pytest
    rewrites asserts in modules it imports, which Numba cannot compile."""

    @cached_njit(nogil=True, fastmath=FASTMATH)
    def propagate_block(y0, t, p, rtol, atol, max_steps, out, info):
        """:func:`propagate` of a block of orbits on the calling thread, into ``out``
        (n, k, 6) and ``info`` (n, 4)."""
        _ = len(stamp)  # keys the cache, see _build
        for i in range(y0.shape[0]):
            _ep_propagate_orbit(y0[i], t, p, rtol, atol, max_steps, out[i], info[i])

    @cached_njit(nogil=True, fastmath=FASTMATH)
    def locate_crossings_block(y0, p, kind, value, direction, t_max, rtol, atol, max_steps,
                               tc, yc, count, info):
        """:func:`locate_crossings` of a block of orbits on the calling thread, into
        ``tc`` (n, n_crossings), ``yc`` (n, n_crossings, 6), ``count`` (n,), ``info``."""
        _ = len(stamp)  # keys the cache, see _build
        for i in range(y0.shape[0]):
            count[i] = _ep_crossings_orbit(y0[i], p, kind, value, direction, t_max, rtol,
                                           atol, max_steps, tc[i], yc[i], info[i])

    @cached_njit(nogil=True, fastmath=FASTMATH)
    def integrate_fixed(y0, p, h, n_steps):
        """``n_steps`` steps of size ``h`` without error control: shape (n_steps + 1, 6)."""
        _ = len(stamp)  # keys the cache, see _build
        out = np.empty((n_steps + 1, N))
        K = np.empty((N_STAGES_EXTENDED, N))
        ytmp = np.empty(N)
        y = y0.copy()
        out[0] = y
        ep_rhs(0.0, y, p, K[0])
        for m in range(n_steps):
            _ep_stages(m * h, y, h, p, K, ytmp, 1, N_STAGES + 1)
            for i in range(N):
                y[i] = ytmp[i]
                K[0, i] = K[N_STAGES, i]
            out[m + 1] = y
        return out

    @cached_njit(nogil=True, fastmath=FASTMATH)
    def interpolate_step(y0, p, h, x):
        """One step of size ``h`` from ``y0``; its dense output at ``t = x h``,
        shape (len(x), 6)."""
        _ = len(stamp)  # keys the cache, see _build
        K = np.empty((N_STAGES_EXTENDED, N))
        F = np.empty((INTERPOLATOR_POWER, N))
        ytmp = np.empty(N)
        y1 = np.empty(N)
        ep_rhs(0.0, y0, p, K[0])
        _ep_stages(0.0, y0, h, p, K, ytmp, 1, N_STAGES + 1)
        for i in range(N):
            y1[i] = ytmp[i]
        _ep_dense_coefficients(0.0, y0, y1, h, p, K, ytmp, F)
        out = np.empty((x.shape[0], N))
        for m in range(x.shape[0]):
            _dense_eval(F, y0, x[m], out[m])
        return out

    return propagate_block, locate_crossings_block, integrate_fixed, interpolate_step


(propagate_block, locate_crossings_block, integrate_fixed,
 interpolate_step) = _build(KERNEL_STAMP)


def propagate(y0: np.ndarray, t: np.ndarray, p: np.ndarray, rtol: float, atol: float,
              max_steps: int, *, block: int = 1, threads: int | None = None
              ) -> tuple[np.ndarray, np.ndarray]:
    """States of many orbits at the output times ``t`` (dense output), orbits in threads.

    Parameters
    ----------
    y0 : ndarray, shape (n, 6)
        Initial Euler-Poisson states at time ``t[0]`` (C-contiguous floats).
    t : ndarray, shape (k,)
        Output times, non-decreasing, ``k >= 1``.
    p : ndarray, shape (8,)
        Kernel parameters :data:`PARAMS`.
    rtol, atol : float
        Tolerances of the local error (componentwise ``atol + rtol |y|``).
    max_steps : int
        Maximum accepted steps per orbit.
    block, threads :
        Orbits per block and threads (:func:`andoyer.kernels.threads.over_orbits`).

    Returns
    -------
    y : ndarray, shape (n, k, 6)
        ``y[i, j] = y_i(t[j])``; NaN after a failure (see ``info``).
    info : ndarray of int64, shape (n, 4)
        Columns :data:`INFO`.
    """
    return ensemble_propagate(propagate_block, y0, t, p, rtol, atol, max_steps, block=block,
                              threads=threads)


def locate_crossings(y0: np.ndarray, p: np.ndarray, kind: int, value: float,
                     direction: int, n_crossings: int, t_max: float, rtol: float,
                     atol: float, max_steps: int, *, block: int = 1,
                     threads: int | None = None
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The first crossings after t = 0 of a section, for many orbits, orbits in threads.

    Parameters
    ----------
    y0 : ndarray, shape (n, 6)
        Initial Euler-Poisson states at t = 0.
    p : ndarray, shape (8,)
        Kernel parameters :data:`PARAMS`.
    kind : int
        Index into :data:`andoyer.kernels.generated.SECTION_KINDS`.
    value : float
        The section is ``SECTION_KINDS[kind] = value`` (mod 2 pi for angles).
    direction : int
        +1: f increasing, -1: decreasing, 0: both.
    n_crossings : int
        Stop an orbit after this many crossings.
    t_max : float
        Stop an orbit at this time.
    rtol, atol : float
        Tolerances.
    max_steps : int
        Maximum accepted steps per orbit.
    block, threads :
        Orbits per block and threads (:func:`andoyer.kernels.threads.over_orbits`).

    Returns
    -------
    t : ndarray, shape (n, n_crossings)
        Crossing times, NaN-padded.
    y : ndarray, shape (n, n_crossings, 6)
        States on the section, NaN-padded.
    count : ndarray of int64, shape (n,)
        Crossings found per orbit.
    info : ndarray of int64, shape (n, 4)
        Columns :data:`INFO`.
    """
    return ensemble_crossings(locate_crossings_block, y0, p, kind, value, direction,
                              n_crossings, t_max, rtol, atol, max_steps, block=block,
                              threads=threads)


def ensemble_propagate(kernel: Any, y0: np.ndarray, t: np.ndarray, p: np.ndarray,
                       rtol: float, atol: float, max_steps: int, *, block: int = 1,
                       threads: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Allocate the outputs of :func:`propagate` for states of any width ``y0.shape[1]``
    and run a ``propagate_block`` kernel (this module's or :mod:`andoyer.kernels.tangent`'s)
    over blocks of orbits in threads."""
    n = y0.shape[0]
    out = np.full((n, t.shape[0], y0.shape[1]), np.nan)
    info = np.zeros((n, len(INFO)), dtype=np.int64)
    over_orbits(kernel, n, (y0,), (out, info),
                (t, p, float(rtol), float(atol), int(max_steps)), block=block,
                threads=threads)
    return out, info


def ensemble_crossings(kernel: Any, y0: np.ndarray, p: np.ndarray, kind: int, value: float,
                       direction: int, n_crossings: int, t_max: float, rtol: float,
                       atol: float, max_steps: int, *, block: int = 1,
                       threads: int | None = None
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """As :func:`ensemble_propagate`, for :func:`locate_crossings` and a
    ``locate_crossings_block`` kernel."""
    n = y0.shape[0]
    tc = np.full((n, int(n_crossings)), np.nan)
    yc = np.full((n, int(n_crossings), y0.shape[1]), np.nan)
    count = np.zeros(n, dtype=np.int64)
    info = np.zeros((n, len(INFO)), dtype=np.int64)
    over_orbits(kernel, n, (y0,), (tc, yc, count, info),
                (p, int(kind), float(value), int(direction), float(t_max), float(rtol),
                 float(atol), int(max_steps)), block=block, threads=threads)
    return tc, yc, count, info

