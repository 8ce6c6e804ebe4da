"""Certificates of the first-order transversal splitting: written, verified, tampered with."""

from __future__ import annotations

import copy
import json

import pytest
from flint import arb

from andoyer import RigidBody
from andoyer.analysis.splitting.certificate import (
    _digest,
    prove_certificate,
    read_certificate,
    verify_certificate,
    write_certificate,
)
from andoyer.errors import CertificateError
from andoyer.integrate.validated.arithmetic import BodySpec, working_precision


@pytest.fixture(scope="module")
def cert():
    return prove_certificate(RigidBody.paper(), branch="theta1=4phi0", digits=20)


def _resealed(c):
    c = copy.deepcopy(c)
    c["digest"] = _digest(c)
    return c


def test_verify_accepts_what_prove_wrote(cert, tmp_path):
    path = write_certificate(cert, tmp_path / "c.json")
    out = verify_certificate(path)
    assert out["zeros"] == 2 and out["digits"] > 20
    assert read_certificate(path) == cert
    assert cert["libraries"]["python-flint"] and cert["body"]["C"] == "2.2"
    assert cert["mu_interval"]["upper"] is None


def test_an_edit_without_a_new_digest_is_caught(cert):
    c = copy.deepcopy(cert)
    c["zeros"][0]["box"] = c["zeros"][0]["box"].replace("0.0910", "0.0911")
    with pytest.raises(CertificateError, match="altered"):
        verify_certificate(c)


def _shift_box(c, k, by):
    with working_precision(c["precision_bits"]):
        X = arb(c["zeros"][k]["box"])
        c["zeros"][k]["box"] = (X + by).str(60, radius=True, more=True)


@pytest.mark.parametrize("edit, match", [
    (lambda c: c["body"].update(A="2.6"), "line|coefficient"),
    (lambda c: c["body"].update(C="2.21"), "line|coefficient"),
    (lambda c: c["body"].update(epsilon="0.01"), "coefficient"),
    (lambda c: c["level"].update(J2="1.1"), "line"),
    (lambda c: c.update(sheet=-1), "line"),
    (lambda c: c.update(branch="theta1=0"), "line"),
    (lambda c: c["heteroclinic_line"].update(theta1="[0 +/- 1e-30]"), "line"),
    (lambda c: c["mu_interval"].update(upper="0.1"), "mu interval"),
    (lambda c: _shift_box(c, 0, 3 * arb(c["zeros"][0]["box"]).rad()), "Krawczyk|where"),
    (lambda c: _shift_box(c, 1, arb("0.5")), "Krawczyk"),
    (lambda c: c["zeros"].__setitem__(1, copy.deepcopy(c["zeros"][0])), "same zero"),
    (lambda c: c["coefficient"].update(real="[1.0 +/- 1e-30]"), "coefficient"),
    (lambda c: c["zeros"].pop(), "two zeros"),
])
def test_an_altered_parameter_or_box_is_rejected(cert, edit, match):
    """Even with its digest recomputed, an altered certificate does not verify."""
    c = copy.deepcopy(cert)
    edit(c)
    with pytest.raises(CertificateError, match=match):
        verify_certificate(_resealed(c))


def test_another_flint_version_is_named(cert):
    c = copy.deepcopy(cert)
    c["libraries"]["python-flint"] = "0.1.0"
    with pytest.raises(CertificateError, match="python-flint 0.1.0"):
        verify_certificate(_resealed(c))


@pytest.mark.parametrize("content, match", [
    ("[1, 2]", "not an object"), ("{not json", "not JSON"),
    ('{"format": "something"}', "not an andoyer certificate"),
    ('{"format": "andoyer-certificate"}', "lacks the field")])
def test_foreign_files_get_one_line_errors(tmp_path, content, match):
    path = tmp_path / "x.json"
    path.write_text(content)
    with pytest.raises(CertificateError, match=match) as info:
        verify_certificate(path)
    assert "\n" not in str(info.value)


def test_nothing_to_certify_on_the_hess_line_of_a_hess_body():
    with pytest.raises(ValueError, match="vanishes identically"):
        prove_certificate(BodySpec("2.5", "2.0", "2.2"), branch="theta1=0", digits=10)


def test_certificate_is_json_with_strings_for_balls(cert):
    text = json.dumps(cert)
    back = json.loads(text)
    assert all(isinstance(z["box"], str) for z in back["zeros"])
