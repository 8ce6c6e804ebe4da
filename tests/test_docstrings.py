"""The API reference is complete: every parameter documented, summaries not cut short.

numpydoc's own validation (``numpydoc.validate``) checks each public function and class
of every public module (the ``__all__`` of ``andoyer`` and of every module and package
below it whose name has no part starting with ``_``: the analysis sub-packages, the
engines, the kernels, the report and the command line included) against its signature;
the summaries the API tables show are extracted as Sphinx's autosummary extracts them,
with the site's extension ``docs/_ext/summaries.py``.
"""

from __future__ import annotations

import dataclasses
import enum
import importlib
import inspect
import pkgutil
import re
import sys
from pathlib import Path

import pytest

pytest.importorskip("numpydoc")
from numpydoc.docscrape import NumpyDocString  # noqa: E402
from numpydoc.validate import validate  # noqa: E402

import andoyer  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
#: numpydoc's checks: a parameter not documented (PR01), a documented parameter not in
#: the signature (PR02), no docstring at all (GL08).
CHECKS = ("PR01", "PR02", "GL08")


def _public_modules() -> list[str]:
    names = [m.name for m in pkgutil.walk_packages(andoyer.__path__, "andoyer.")
             if not any(part.startswith("_") for part in m.name.split("."))]
    return ["andoyer", *names]


def _import(name: str) -> object:
    """The module ``name``."""
    return importlib.import_module(name)


def _api() -> dict[str, object]:
    """``dotted name -> object`` of every function and class in the ``__all__`` of every
    public module, under the name of the module that defines it (an object re-exported
    by a package is checked once)."""
    found: dict[str, object] = {}
    for module_name in _public_modules():
        module = _import(module_name)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if (inspect.isfunction(obj) or inspect.isclass(obj)) \
                    and obj.__module__.split(".")[0] == "andoyer":
                found[f"{obj.__module__}.{obj.__qualname__}"] = obj
                if inspect.isclass(obj):
                    found.update(_constructors(obj))
    return found


def _constructors(cls: type) -> dict[str, object]:
    """The public classmethods a class defines itself (its preset constructors:
    ``RigidBody.lagrange``, ``Section.parse``, ...), under their dotted names."""
    out: dict[str, object] = {}
    for attr, value in vars(cls).items():
        if isinstance(value, classmethod) and not attr.startswith("_"):
            fn = getattr(cls, attr)
            out[f"{cls.__module__}.{cls.__qualname__}.{attr}"] = fn
    return out


API = _api()


def _attributes(obj: object) -> set[str]:
    """Names in the "Attributes" section (a dataclass documents its fields there)."""
    doc = NumpyDocString(inspect.getdoc(obj) or "")
    return {n.strip() for item in doc["Attributes"] for n in item.name.split(",")}


@pytest.mark.parametrize("name", sorted(API))
def test_every_parameter_is_documented(name: str) -> None:
    obj = API[name]
    if inspect.isclass(obj) and issubclass(obj, enum.Enum):
        return  # the signature is Enum's own (Singular("g_undefined")), not the class's
    if getattr(obj, "_is_protocol", False):
        return  # a typing.Protocol: its signature is Protocol's own (*args, **kwargs)
    errors = [(code, message) for code, message in validate(name)["errors"]
              if code in CHECKS]
    if dataclasses.is_dataclass(obj) and _attributes(obj):
        # a dataclass's fields are its parameters: documented as its Attributes
        fields = {f.name for f in dataclasses.fields(obj)}
        assert fields <= _attributes(obj), f"{name}: fields not documented: " \
                                           f"{sorted(fields - _attributes(obj))}"
        errors = [(c, m) for c, m in errors if c != "PR01"]
    assert not errors, f"{name}: {errors}"


def test_api_list_covers_every_public_module() -> None:
    """The checked objects come from every corner of the package (issue 29: ~90 objects
    of andoyer.analysis were outside the checked packages)."""
    assert len(API) > 400
    for name in ("andoyer.integrate.api.poincare",
                 "andoyer.analysis.chaos.frequency.orbit_frequencies",
                 "andoyer.analysis.hess.pendulum.pendulum_period",
                 "andoyer.analysis.splitting.section_map.SectionReturn",
                 "andoyer.kernels.taylor.flow.order_for", "andoyer.report.base.Item",
                 "andoyer.cli.main", "andoyer.plot.frequency.plot_orbit_frequencies",
                 "andoyer.body.RigidBody.lagrange", "andoyer.body.RigidBody.hess"):
        assert name in API, name


@pytest.mark.parametrize("module", _public_modules())
def test_every_public_module_has_a_summary(module: str) -> None:
    doc = inspect.getdoc(_import(module)) or ""
    assert doc.strip(), f"{module} has no docstring (its API page would have no summary)"


def _summaries(settings: object, autosummary: object) -> list[tuple[object, str]]:
    """``(object, summary)`` of every public module and of the functions and classes of
    its ``__all__``, extracted as autosummary extracts them."""
    out = []
    for module_name in _public_modules():
        module = _import(module_name)
        objects = [module] + [getattr(module, n) for n in getattr(module, "__all__", [])
                              if inspect.isfunction(getattr(module, n, None))
                              or inspect.isclass(getattr(module, n, None))]
        for obj in objects:
            doc = inspect.getdoc(obj)
            if doc:
                out.append((obj, autosummary.extract_summary(  # type: ignore[attr-defined]
                    doc.splitlines(), settings)))
    return out


def test_summaries_are_not_cut_at_abbreviations(monkeypatch: pytest.MonkeyPatch) -> None:
    """autosummary ends the first sentence at "Eq." unless told it is an abbreviation:
    "H of Eq. (1) expressed in chart" was listed as "H of Eq."."""
    from docutils.frontend import get_default_settings
    from docutils.parsers.rst import Parser
    from sphinx.ext import autosummary

    monkeypatch.syspath_prepend(str(ROOT / "docs" / "_ext"))
    monkeypatch.setattr(autosummary, "WELL_KNOWN_ABBREVIATIONS",
                        autosummary.WELL_KNOWN_ABBREVIATIONS)  # restored afterwards
    monkeypatch.delitem(sys.modules, "summaries", raising=False)
    summaries = importlib.import_module("summaries")
    summaries.setup(None)
    settings = get_default_settings(Parser)
    cut = [f"{getattr(obj, '__name__', obj)}: {summary!r}"
           for obj, summary in _summaries(settings, autosummary)
           if summary.endswith(summaries.ABBREVIATIONS)]
    assert not cut, cut
    # A summary stands alone in a table of another page: a class's or function's
    # citation ([1]_, renamed by numpydoc) resolves nowhere there (a module's is
    # suppressed with ref.citation), an inline literal cut by the sentence's end
    # (``q0^2 .. q3^2``) is left open; under -W both failed the docs build.
    broken = [f"{getattr(obj, '__name__', obj)}: {summary!r}"
              for obj, summary in _summaries(settings, autosummary)
              if ("]_" in summary and not inspect.ismodule(obj))
              or summary.count("``") % 2]
    assert not broken, broken
    hamiltonian = inspect.getdoc(andoyer.hamiltonian) or ""
    assert autosummary.extract_summary(hamiltonian.splitlines(), settings) == (
        "H of Eq. (1) expressed in ``chart`` (Eq. (7) in Andoyer-Deprit variables).")


#: Functions whose ``engine`` parameter states its default, and the capability with which
#: the function resolves ``engine=None`` (the default is the registry's for it), with the
#: workloads it names to the registry (:data:`~andoyer.integrate.engines.WORKLOADS`).
ENGINE_DEFAULTS = {
    "andoyer.integrate.api.propagate": ("propagate", "orbit"),
    "andoyer.integrate.api.poincare": ("crossings", "component_section", "angle_section"),
    "andoyer.integrate.orientation.attitude": ("attitude",),
    "andoyer.integrate.variational.propagate_variational": ("tangent",),
    "andoyer.analysis.splitting.section_map.flow_engine": ("tangent_crossings",),
    "andoyer.analysis.splitting.section_map.flow_to_section": ("tangent_crossings",),
    "andoyer.analysis.splitting.periodic.rotation_orbit": ("tangent_crossings",),
    "andoyer.analysis.splitting.manifolds.manifold_branch": ("tangent_crossings",),
    "andoyer.analysis.paper.trajectories.fig3_section": ("crossings", "angle_section"),
    "andoyer.analysis.chaos.alignment.alignment_indices": ("tangent",),
    "andoyer.analysis.chaos.lyapunov.indicators": ("tangent",),
    "andoyer.analysis.hess.floquet.monodromy": ("tangent",),
}


@pytest.mark.parametrize("name", sorted(ENGINE_DEFAULTS))
def test_a_stated_default_engine_is_the_registrys(name: str) -> None:
    """Where a docstring says which engine runs without heyoka ("heyoka where installed,
    else X"), X is the first of ``FALLBACK_DEFAULTS`` with the capability the function
    asks for (:func:`~andoyer.integrate.engines.default_engine_name`; several said numba
    after taylor became the default of orbits and sections)."""
    import re

    from andoyer.integrate.engines import FALLBACK_DEFAULTS, MEASURED_DEFAULTS, engine_class
    from andoyer.integrate.engines.base import Capability

    module, _, function = name.rpartition(".")
    doc = NumpyDocString(inspect.getdoc(getattr(_import(module), function)) or "")
    text = " ".join(" ".join(p.desc) for p in doc["Parameters"] if p.name == "engine")
    need, *workloads = ENGINE_DEFAULTS[name]
    measured = {MEASURED_DEFAULTS[w] for w in workloads if w in MEASURED_DEFAULTS}
    if measured:
        # a workload measured off heyoka: the text names the engine and the registry
        assert "MEASURED_DEFAULTS" in text and all(e in text for e in measured), \
            f"{name}: the default of its workloads ({', '.join(sorted(measured))}, " \
            f"MEASURED_DEFAULTS) is not stated: {text!r}"
        return
    stated = re.search(r"heyoka\s+where\s+installed,\s+else\s+(?:the\s+first\s+of\s+)?(\w+)",
                       text)
    assert stated, f"{name}: the engine parameter does not state its default: {text!r}"
    capability = Capability(need)
    fallback = next(n for n in FALLBACK_DEFAULTS if capability in engine_class(n).capabilities)
    assert stated.group(1) == fallback, f"{name}: says {stated.group(1)}, is {fallback}"


def test_attribute_comments_hold_no_rst_substitution() -> None:
    """A ``#:`` comment is the docs' text of a module attribute: a bare ``|G|`` in it is
    an undefined reStructuredText substitution, an error of the docs build under -W
    (CLOSED_FORM's comment in eleven modules broke the CI docs job). Literals
    (````|G|````) and roles (``:math:`|G|```) are fine."""
    literal = re.compile(r"``.*?``|:\w+:`[^`]*`")
    substitution = re.compile(r"(?<![\w|])\|[^|\s][^|]*?\|(?![\w|])")
    found = []
    for path in sorted((ROOT / "src" / "andoyer").rglob("*.py")):
        for number, line in enumerate(path.read_text().splitlines(), 1):
            text = line.strip()
            if text.startswith("#:") and substitution.search(literal.sub("", text)):
                found.append(f"{path.relative_to(ROOT)}:{number}: {text}")
    assert not found, found
