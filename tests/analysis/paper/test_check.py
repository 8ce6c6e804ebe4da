"""The paper check: its verdicts, its corrected forms, and the command line."""

import json

import numpy as np
import pytest

from andoyer import paper_check
from andoyer.analysis.paper import check as pc
from andoyer.cli import main


@pytest.fixture(scope="module")
def rows():
    return {(r.label, r.name): r for r in paper_check(n=100)}


def _row(rows, label, start):
    hits = [r for (lab, name), r in rows.items() if lab == label and name.startswith(start)]
    assert len(hits) == 1, (label, start, hits)
    return hits[0]


@pytest.mark.parametrize(("label", "start", "verdict"), [
    ("(5)", "G in", "holds"),
    ("(6)", "gamma", "holds"),
    ("(7)", "H0", "holds"),
    ("(7)", "H1, second", "holds"),
    ("(9)", "unperturbed dl/dt", "holds"),
    ("(9)", "unperturbed dL/dt", "misprint"),
    ("(12)", "H0", "misprint"),
    ("(13)", "H0", "holds"),
    ("(16)", "dtheta1", "holds"),
    ("(16)", "dtheta2", "holds"),
    ("(16)", "dJ1", "holds"),
    ("(16)", "dJ2", "holds"),
    ("after (15)", "H(theta, J), general M", "holds"),
    ("after (7)", "dm/dt", "misprint"),
    ("after (11)", "Pi = mu^-1", "misprint"),
    ("after Fig. 3", "the four fixed points", "omission"),
])
def test_verdicts(rows, label, start, verdict):
    assert _row(rows, label, start).verdict == verdict


def test_every_corrected_form_matches_the_derivation(rows):
    for r in rows.values():
        assert r.corrected_holds in (None, True), (r.label, r.name)


def test_misprints_carry_nature_and_correction(rows):
    for r in rows.values():
        if r.verdict == "misprint":
            assert r.nature and r.corrected, (r.label, r.name)


def test_sign_misprint_is_classified(rows):
    assert "sign" in _row(rows, "(9)", "unperturbed dL/dt").nature
    assert "mu-term has the wrong sign" in _row(rows, "after (7)", "dl/dt").nature


def test_check_detects_a_broken_derivation(monkeypatch):
    """If the derived kernels were wrong, formulas that hold would turn to misprints."""
    orig = pc.K.hess_field

    def broken(*args):
        out = list(orig(*args))
        out[2] = -np.asarray(out[2])  # flip dJ1/dt
        return tuple(out)

    monkeypatch.setattr(pc.K, "hess_field", broken)
    rows = {r.name: r for r in paper_check(n=20)}
    assert rows["dJ1/dt"].verdict == "misprint"


def test_cli_text_and_json(capsys):
    assert main(["paper-check", "--points", "20"]) == 0
    out = capsys.readouterr().out
    assert "(12)" in out and "misprint" in out and "c G3^2" in out
    assert main(["paper-check", "--points", "20", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {d["verdict"] for d in data} == {"holds", "misprint", "omission"}


def test_cli_bad_points():
    with pytest.raises(SystemExit):
        main(["paper-check", "--points", "0"])
