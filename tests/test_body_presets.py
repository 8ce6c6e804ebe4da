"""The body presets (:data:`andoyer.body.PRESETS`) are the one list of kinds of body: the
CLI's ``--body`` choices and flags, the scan configs' kinds and defaults, the explorer's
menu and the integrals each brings derive from it; a list that differs fails here."""

from __future__ import annotations

import argparse

import pytest

from andoyer.body import PAPER, PRESETS, RigidBody, make_body
from andoyer.charts.integrals import COMMON, integrals_of


def _body_choices() -> tuple[str, ...]:
    from andoyer.cli._common import add_body_args

    p = argparse.ArgumentParser()
    add_body_args(p)
    return tuple(next(a for a in p._actions if a.dest == "body").choices)


def derived() -> dict[str, object]:
    from andoyer.cli._common import BODY_FLAGS
    from andoyer.explore.base import BODIES
    from andoyer.scan.config import BODY_KINDS, HESS_DEFAULTS

    return {"--body choices": _body_choices(),
            "--body flags": BODY_FLAGS,
            "scan kinds within the presets": set(BODY_KINDS) <= set(PRESETS),
            "explorer menu within the presets": set(BODIES.values()) <= set(PRESETS),
            "scan defaults": {k: HESS_DEFAULTS[k] for k in PAPER},
            "paper body": {k: getattr(RigidBody.paper(), k) for k in PAPER}}


def expected() -> dict[str, object]:
    return {"--body choices": tuple(PRESETS),
            "--body flags": {k: p.flags for k, p in PRESETS.items()},
            "scan kinds within the presets": True,
            "explorer menu within the presets": True,
            "scan defaults": PAPER,
            "paper body": PAPER}


def test_every_list_of_bodies_is_the_presets():
    assert derived() == expected()
    assert "general" in PRESETS and "custom" not in _body_choices()


def test_the_check_catches_a_list_that_differs(monkeypatch):
    from andoyer.scan import config

    monkeypatch.setattr(config, "HESS_DEFAULTS", {**config.HESS_DEFAULTS, "A": 3.0})
    assert derived()["scan defaults"] != expected()["scan defaults"]


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_each_preset_makes_its_body_with_the_integrals_it_brings(name):
    preset = PRESETS[name]
    values = {"A": 2.5, "B": 1.0, "C": 1.6, "r": (0.6, 0.48, 0.64)}
    body = preset.make(**{k: v for k, v in values.items() if k in preset.required})
    assert integrals_of(body) == (*COMMON, *preset.integrals)


def test_a_flag_a_preset_does_not_take_is_refused():
    with pytest.raises(ValueError, match="does not take A"):
        make_body("kovalevskaya", A=2.0)
    with pytest.raises(ValueError, match="needs r"):
        make_body("general", A=2.5, B=1.0, C=1.6)
    with pytest.raises(ValueError, match="body kind must be one of"):
        make_body("custom")
    assert make_body("paper", epsilon=0.1).hess_epsilon == pytest.approx(0.1)
