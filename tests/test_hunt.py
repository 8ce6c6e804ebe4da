"""Tests that hunt: random bad types, NaN/inf, out-of-range and huge values at the public
entries and on the command line. Each call must end in a clear ``ValueError``/``TypeError``
(our ``CostLimitError`` and ``ArgumentTypeError`` included) or a correct result, quickly."""

import math
import time
import warnings

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from andoyer import RigidBody, energy, from_andoyer, to_hess, vector_field
from andoyer.analysis.chaos import chaos_map, indicators
from andoyer.cli import EXIT_CODES, main
from andoyer.integrate import fill_section, poincare, propagate, propagate_hess_manifold

B = RigidBody.paper()
Y0 = [0.0, 0.0, 1.0, 0.0, 0.6, 0.8]

BAD = st.one_of(
    st.none(), st.text(max_size=5), st.booleans(),
    st.sampled_from([math.nan, math.inf, -math.inf, -1.0, 0.0, 1e300, -1e300, 10**30]),
    st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=7),
    st.dictionaries(st.text(max_size=2), st.integers(), max_size=1),
)

CALLS = {
    "RigidBody(A)": lambda v: RigidBody(v, 2.0, 2.2, 0.01, (1, 0, 0)),
    "RigidBody(mu)": lambda v: RigidBody(2.5, 2.0, 2.2, v, (1, 0, 0)),
    "RigidBody(r)": lambda v: RigidBody(2.5, 2.0, 2.2, 0.01, v),
    "RigidBody.hess(mu)": lambda v: RigidBody.hess(2.5, 2.0, 2.2, v),
    "propagate(body)": lambda v: propagate(v, Y0, [0, 1]),
    "propagate(y0)": lambda v: propagate(B, v, [0, 1]),
    "propagate(t)": lambda v: propagate(B, Y0, v),
    "propagate(rtol)": lambda v: propagate(B, Y0, [0, 1], rtol=v),
    "propagate(engine)": lambda v: propagate(B, Y0, [0, 1], engine=v),
    "propagate(chart)": lambda v: propagate(B, Y0, [0, 1], chart=v),
    "poincare(n)": lambda v: poincare(B, Y0, "G3=0", v, engine="numba"),
    "poincare(section)": lambda v: poincare(B, Y0, v, 2, engine="numba"),
    "poincare(t_max)": lambda v: poincare(B, Y0, "G3=0", 2, t_max=v, engine="numba"),
    "fill_section(h)": lambda v: fill_section(B, h=v, M=0.0, section=("theta2", 0.0),
                                              n_orbits=4),
    "fill_section(M)": lambda v: fill_section(B, h=0.2466, M=v, section=("theta2", 0.0),
                                              n_orbits=4),
    "fill_section(n_orbits)": lambda v: fill_section(B, h=0.2466, M=0.0, section=("theta2", 0.0),
                                              n_orbits=v),
    "chaos_map(n)": lambda v: chaos_map(B, 0.2466, 0.0, "theta2=0", n=v, t_end=5.0),
    "chaos_map(t_end)": lambda v: chaos_map(B, 0.2466, 0.0, "theta2=0", n=3, t_end=v),
    "indicators(t_end)": lambda v: indicators(B, [0.3, 0, 0.3, 1, 0], v, chart="andoyer"),
    "indicators(w0)": lambda v: indicators(B, [0.3, 0, 0.3, 1, 0], 5.0, chart="andoyer",
                                           w0=v),
    "indicators(tol)": lambda v: indicators(B, [0.3, 0, 0.3, 1, 0], 5.0, chart="andoyer",
                                            tol=v),
    "propagate_hess_manifold(x0)": lambda v: propagate_hess_manifold(B, v, [0, 1]),
    "to_hess(y)": lambda v: to_hess(B, v),
    "from_andoyer(x)": lambda v: from_andoyer(v),
    "energy(body)": lambda v: energy(v, Y0),
    "vector_field(chart)": lambda v: vector_field(B, [0.3, 0, 0.3, 1, 0], v),
}


@pytest.mark.parametrize("name", sorted(CALLS))
@settings(max_examples=12, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(value=BAD)
def test_public_entries_reject_bad_values_clearly(name, value):
    if name.startswith(("indicators", "chaos_map")):
        pytest.importorskip("heyoka")
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            CALLS[name](value)
        except (ValueError, TypeError) as exc:
            assert str(exc), name  # a message, naming something
    assert time.perf_counter() - t0 < 20.0, name


ARGS = st.sampled_from(["nan", "inf", "-1", "0", "1e300", "x", "", "1,2", "-0"])
FLAGS = {
    "orbit": ["--t-end", "--n-out", "--rtol", "--andoyer", "--mu", "--body"],
    "section": ["--h", "--energy", "--M", "--area", "--orbits", "--crossings", "--section"],
    "chaos-map": ["--n", "--t-end", "--h", "--tol"],
}


@settings(max_examples=40, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow,
                                 HealthCheck.function_scoped_fixture])
@given(command=st.sampled_from(sorted(FLAGS)), data=st.data())
def test_command_line_never_shows_a_traceback(command, data, tmp_path_factory, capsys):
    flag = data.draw(st.sampled_from(FLAGS[command]))
    value = data.draw(ARGS)
    out = tmp_path_factory.mktemp("cli") / "out.nc"
    argv = [command, "--out", str(out), flag, value]
    if command == "orbit" and flag != "--andoyer":
        argv += ["--andoyer", "0.3,1,0.2,1,0", "--t-end" if flag != "--t-end" else "--n-out",
                 "1" if flag != "--t-end" else "3"]
    if command == "section":
        argv += ["--orbits", "2", "--crossings", "2"] if flag not in ("--orbits",
                                                                      "--crossings") else []
    if command == "chaos-map":
        argv += ["--n", "3", "--t-end", "2"] if flag not in ("--n", "--t-end") else []
    try:
        main(argv)
    except SystemExit as exc:
        assert exc.code in (0, *EXIT_CODES.values()), argv
    err = capsys.readouterr().err
    assert "Traceback" not in err, (argv, err)
