"""Section crossings of the Taylor kernel on an angle section: as accurate as heyoka's.

The error of a crossing is the integration's global error at the crossing (the root
and its polish add nothing measurable: the kernel's dense output at the reference
crossing times has the same transverse error). heyoka counts its event functions in
the step size; the Taylor kernel does too (:func:`andoyer.kernels.taylor.jets.section_step_size`).
Without it, the theta2 = 0 crossings of the benchmark's orbits were 4x less accurate
than heyoka's (see :mod:`andoyer.kernels.taylor.flow`'s notes).

Reference: the 10th upward crossing of theta2 = 0 of the first 20 W2 orbits of the
benchmarks (paper's body), by heyoka's Taylor integrator in extended precision (80-bit
long double, tol = 1.1e-19, a terminal event), the ``benchmarks.reference`` route; it
agrees with a second extended-precision route (non-terminal events, dense output) to
2e-18. Stored as hex floats, 12 per orbit: the initial state, then the state at the
10th crossing.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from andoyer import RigidBody
from andoyer.kernels import common
from andoyer.kernels.generated import equations
from andoyer.kernels.taylor import flow as T
from andoyer.kernels.taylor.jets import SECTION_STEP_FLOOR

K = 10  # the crossing of the reference
REFERENCE = """
  0x1.0a74c80d6cd9bp-4   0x1.b48b62f66a629p-4   0x1.05b8129dfbe33p+0
  0x1.ed90270d1fd86p-1  -0x1.0e1b041ef6c39p-2  -0x1.153ae87fd8ea1p-5
 -0x1.2797fe5c97bb7p-3   0x1.6ce76674f8f25p-3  -0x1.0402d5d0d33c7p+0
  0x1.514acf84686ccp-1  -0x1.70631465bb9e4p-1  -0x1.c239c70510a4dp-3
  0x1.520edadf808dfp-1   0x1.ce78b47e97cb6p-6  -0x1.ade744b0b1ddap-1
  0x1.12d757d77ddb3p-1  -0x1.7d25008361858p-1   0x1.969efb4934ef6p-2
  0x1.c2800c1c45c6bp-1   0x1.38278f25a2431p-1  -0x1.57c2bfffe5af4p-6
  0x1.22187c85895dep-1  -0x1.a050019b25efcp-1   0x1.116b717099ca5p-3
  0x1.dd48fcb066347p-1  -0x1.18f63d7f094b3p-1   0x1.5c85518e9e8a0p-5
 -0x1.743172bac9818p-3  -0x1.e0a46815c5eaap-3   0x1.e8ecbf8223466p-1
  0x1.c11b126c78e95p-1   0x1.9181651c74637p-2  -0x1.fbb137ccd23f0p-2
  0x1.09b1e5976402fp-1  -0x1.9dac04c027998p-1   0x1.1dd656b85f9bbp-2
 -0x1.ce5340a8ac8b9p-5   0x1.f4c28d78a34fdp-1  -0x1.a544ea83afb68p-4
  0x1.44b012c3b7a2ep-1  -0x1.6d33da61b0238p-5  -0x1.8b38f82a23c48p-1
  0x1.8b4ce3c7a490bp-4   0x1.f52d4e5f2dd81p-1  -0x1.5921b53f46c5dp-5
  0x1.795a2381e6ec3p-1  -0x1.9f6fcbba74b3cp-4  -0x1.562131b058c46p-1
 -0x1.9763cea4ea94cp-2   0x1.9bc1af8056f88p-1   0x1.dd1abc3963e94p-2
  0x1.a80475729ac04p-5   0x1.0a12c5780f470p-1  -0x1.b4a18cc867f0ap-1
 -0x1.f439f2cbdbafep-2   0x1.b9843b467245cp-1   0x1.b42cf37a30c3ep-3
  0x1.7bc27397b2d4cp-4   0x1.26d678a38650cp-2  -0x1.e803be889716dp-1
  0x1.0c23a302881d7p+0  -0x1.18dd0c907559bp-3  -0x1.59885a0da5e84p-2
  0x1.2ce0790b86becp-3  -0x1.56ca0da6209e8p-1   0x1.74cd66453a334p-1
  0x1.10a8fe700b9d4p+0  -0x1.076a8288977e4p-2   0x1.8e41c2d8bed56p-3
 -0x1.16b046b9604b5p-2  -0x1.051c386e6b94bp-1   0x1.a1ca47985faa8p-1
  0x1.bee3798704db0p-1   0x1.95f9f8ec99201p-2   0x1.055a3ebda25b8p-1
  0x1.0bb3f0e3da2eap-2  -0x1.da21f162ff898p-1   0x1.16c14309a1136p-2
  0x1.d6ae6ace5a63dp-1  -0x1.125a2dfc5cad3p-1  -0x1.82fb1060a4d88p-3
 -0x1.9501c8a79217ep-8  -0x1.5e2c960a59e49p-2   0x1.e11f43c7054eep-1
  0x1.07cc3635823e7p-3   0x1.8d5aae806b3d5p-1  -0x1.43ba2e7faa7c2p-1
  0x1.6c8c7253df85ap-1  -0x1.0580308650538p-1  -0x1.ed6b5b540e97dp-2
  0x1.b136cdc4e6770p-2   0x1.c420186070b3dp-1  -0x1.ed2eb3de3c1bbp-3
  0x1.984b5c817a651p-1  -0x1.ecd6cdb6b5026p-2  -0x1.74a68b303a56cp-2
  0x1.2a042ab6ce08bp-2   0x1.d9bc24c65ab9cp-1   0x1.b483cc9ebb30cp-3
  0x1.b6e75bcbec591p-1  -0x1.40caee7451b96p-3  -0x1.f64c38eb8c4d0p-2
 -0x1.c4fd54402fc58p-4   0x1.c5db9d9187a50p-1   0x1.b29ae0ef3bd66p-2
  0x1.0f3da307bac40p-1   0x1.ad2fd47d59108p-2  -0x1.798560abcb7d2p-1
  0x1.a74a3c0714159p-1   0x1.54195a1fedfefp-1  -0x1.c2d5bacf7c440p-6
  0x1.40b3b0b39b3f4p-1  -0x1.8dd00ac7be1aep-1   0x1.01e9def8f8331p-4
  0x1.7c7e6dd76cf68p-1   0x1.161233f9fb02cp-1   0x1.0fad01e641520p-1
  0x1.15e77be90c861p-1  -0x1.ab4f92c488c62p-1   0x1.8138d9ff303d2p-4
  0x1.608368c76edf1p-1  -0x1.0fe42aea80de3p-2   0x1.935892a48dc98p-1
 -0x1.8a3786684d442p-1  -0x1.73f2b4361728dp-3   0x1.3931a730191d9p-1
  0x1.a92762172055ep-1  -0x1.26f0c4e37cf95p-1  -0x1.620d44e563b0fp-2
  0x1.0f4364d24ceb8p-3  -0x1.736e14056ff46p-2   0x1.d8497504c6baap-1
 -0x1.175f633948d71p-2   0x1.8e71075e77a86p-2  -0x1.d8a95062c768cp-1
  0x1.38dd3426c8ec2p-1  -0x1.4c0887e4321eap-1  -0x1.d0d167e8d75e6p-2
 -0x1.dde4dab2342c3p-4   0x1.1e5ef3af10a12p-2   0x1.f5887bac61ee6p-1
 -0x1.19cc7f97e7244p-5   0x1.eb7acfde14cfbp-1  -0x1.1cd379a13a236p-2
 -0x1.116d280826d78p-3   0x1.41681c3c32cb1p-1   0x1.8d2bc5dba8a02p-1
  0x1.6d094d9b5d1a7p-2   0x1.82bba94bcc62cp-1  -0x1.198c0277d3c33p-1
 -0x1.084f4c7bb0365p-3   0x1.40d00ca0fd68cp-1   0x1.8df2a83ee6e6bp-1
  0x1.77c9a1868b409p-2   0x1.818db4ad88f6cp-1  -0x1.179f32497fb8dp-1
  0x1.46147f73329dfp-1  -0x1.3c437e03833fep-1  -0x1.1cd712e461cb3p-1
  0x1.5a7462b966f78p-2  -0x1.a6b3a6ab9cf87p-2   0x1.b0f986cca8f8fp-1
  0x1.d252276fa78c6p-2  -0x1.83ebc8e98b636p-2   0x1.bd00c376d0085p-1
 -0x1.6eef78012d67fp-1   0x1.ac86ae01a9611p-2   0x1.1da56c2525f90p-1
  0x1.0579d002d391ep+0   0x1.3bfe36b200829p-2   0x1.284b35da0f903p-2
  0x1.38b04d7b6604ap-3  -0x1.cacf4e574a563p-1   0x1.aabd5bd3d0552p-2
  0x1.f2b7ac4d13f71p-1  -0x1.ba5e9d85d0d4dp-9  -0x1.05e9c0884425ap-1
  0x1.3f98a42540111p-2  -0x1.797ea4520787ap-1   0x1.32c47c7688b2fp-1
  0x1.344edde3926e8p-1   0x1.77029a8f31c9bp-1  -0x1.a8a7395bd677ap-2
  0x1.74ed387bf1353p-1  -0x1.5866682df02d3p-1  -0x1.0b154d65dee0ep-3
 -0x1.5ebd06eab5408p-4   0x1.8374d9160e2a4p-2  -0x1.eafb3d8641773p-1
  0x1.52057b8406042p-1  -0x1.5a759c1562bdep-1  -0x1.4dc656a903e97p-2
  0x1.6d12a7215a91ap-1   0x1.51d90de99d9dap-1   0x1.9731473422660p-2
  0x1.5cb766c9f65fcp-1  -0x1.76dfba063f634p-1  -0x1.9cc376ac4e5c2p-8
  0x1.2f7710df5079bp-1   0x1.0537fc2f59028p-1  -0x1.6658f0b385158p-1
  0x1.556c0089668a4p-1  -0x1.7d6181e7876f5p-1   0x1.63ed96053556ap-6
  0x1.e2e673bfeb74ap-1   0x1.365675fb4411ap-3  -0x1.125b059462d05p-1
  0x1.972115f557eebp-2  -0x1.90e421dc1bf63p-1   0x1.e9dd3d5216494p-2
  0x1.fb02821257f82p-1  -0x1.8905a3348eb9cp-2   0x1.2546f95e85e50p-2
 -0x1.834e567ed55c9p-2  -0x1.5293538d849bap-2   0x1.bab3748de9261p-1
  0x1.1ced09695f5a8p-1  -0x1.a50de0ccc6269p-2   0x1.99efef866ba12p-1
 -0x1.6c82e689ac0e6p-1   0x1.247ff16193406p-2   0x1.4875f34f50c33p-1
  0x1.cb6a6dbdbe653p-2  -0x1.8f0387bddc580p-3   0x1.e4ebb35280f2ep-1
 -0x1.d02ed126942f9p-1  -0x1.aa827e9717aadp-5   0x1.accd2a95c16bcp-2
 -0x1.1e0da36d41769p-2   0x1.8cba7b4092175p-1  -0x1.2e96f6234b884p-1
  0x1.165205e616e29p-1  -0x1.814e30cb9f9f4p-2  -0x1.8024e34f67e7dp-1
 -0x1.09899a654c9c4p-5   0x1.6b75a1ba20fb5p-1  -0x1.726e489f08e1cp-1
  0x1.540bf788c8cd5p-1  -0x1.097db34f3f0e4p-1  -0x1.13babd544edfdp-1
"""


def _rows(i: int) -> NDArray[np.float64]:
    """The initial states (``i = 0``) or the reference states (``i = 1``), (20, 6)."""
    return np.array([float.fromhex(v) for v in REFERENCE.split()]).reshape(-1, 2, 6)[:, i]


def _params() -> NDArray[np.float64]:
    return np.asarray(RigidBody.paper().engine_params, dtype=float)


def _kind(name: str) -> int:
    return (equations.SECTION_KINDS + equations.EXTRA_SECTION_KINDS).index(name)


def test_theta2_crossings_are_as_accurate_as_heyokas() -> None:
    # Measured (max-norm error at crossing 10, median over the 20 orbits, tol 1e-12):
    # this kernel 5.7e-15, heyoka 4.8e-15 (numba's DOP853 4.2e-14); with the state's
    # step alone 2.2e-14, every orbit above 1.8e-14.
    y0, ref = _rows(0), _rows(1)
    tc, zc, count, info = T.locate_crossings(y0, _params(), _kind("theta2"), 0.0, 1, K,
                                             1e4, 1e-12, 10**7)
    assert (info[:, 0] == common.SUCCESS).all() and (count == K).all()
    err = np.abs(zc[:, K - 1] - ref).max(axis=1)
    assert np.median(err) <= 1e-14, err
    assert err.max() <= 5e-14, err


def test_the_section_shortens_the_steps_of_an_angle_never_of_a_coordinate() -> None:
    # Steps to t = 300 (about 20 crossings) of the crossing search against propagate.
    y0 = _rows(0)[:6]
    p = _params()
    t_max = 300.0
    _, prop = T.propagate(y0, np.array([0.0, t_max]), p, 1e-12, 10**7)
    for name, value in [("G3", 0.0), ("gamma1", 0.1), ("G1", -0.2), ("theta2", 0.0),
                        ("g", 1.0), ("l", 0.5), ("G", 1.0)]:
        _, _, count, info = T.locate_crossings(y0, p, _kind(name), value, 0, 200, t_max,
                                               1e-12, 10**7)
        assert (info[:, 0] == common.SUCCESS).all() and (count < 200).all(), name
        steps, ref = info[:, 1], prop[:, 1]
        assert (steps >= ref).all(), name  # never longer steps than the state's rule
        assert (steps <= ref / SECTION_STEP_FLOOR).all(), name
        if name in ("G3", "gamma1", "G1"):  # a state component: the same steps
            assert (steps == ref).all(), name
        if name in ("theta2", "g"):  # measured: 5-18 % more steps, 13 % in all
            assert (steps > ref).all() and steps.sum() >= 1.05 * ref.sum(), (name, steps / ref)


def test_the_step_sizes_roots_are_a_little_below_the_power() -> None:
    """:func:`andoyer.kernels.simd.root` (the radii without ``pow``) is below ``x ** (1/p)``
    by 1.4e-8 .. 3.1e-8 over the floats' range, subnormals included, for every order's
    exponents; :func:`andoyer.kernels.simd.roots` (lane vectors) gives the same floats."""
    import numba

    from andoyer.kernels import simd

    @numba.njit
    def both(x, inv_p, scalar, vector, buf, out):
        L = simd.LANES
        for j in range(0, x.shape[0], L):
            for lane in range(L):
                buf[lane] = x[j + lane]
                scalar[j + lane] = simd.root(x[j + lane], inv_p)
            simd.roots(buf, inv_p, out)
            for lane in range(L):
                vector[j + lane] = out[lane]

    rng = np.random.default_rng(3)
    L = simd.LANES
    x = np.concatenate([10.0 ** rng.uniform(-308, 308, 40 * L), [5e-324, 1e-310, 1.0, 2.0],
                        np.exp(rng.uniform(-5, 40, 40 * L)), [1e308, 3.0, 0.5, 7.0]])
    x = x[: x.size // L * L]
    for p in (2, 4, 14, 15, 19, 29, 30):
        scalar, vector = np.empty_like(x), np.empty_like(x)
        both(x, 1.0 / p, scalar, vector, np.empty(L), np.empty(L))
        shortfall = 1.0 - scalar / x ** (1.0 / p)
        assert (shortfall >= 1.4e-8).all() and (shortfall <= 3.1e-8).all(), p
        np.testing.assert_array_equal(vector, scalar)
