"""The problem contract: layouts, the stability count of the layout, load vectors."""

from __future__ import annotations

import inspect

import numpy as np
import pytest

from skfem_dielectric import (CrossSection, Layout, MembranePlate, NeoHookeanDielectric,
                              PlateProblem, Problem, membrane_mesh, plate_mesh, ramp,
                              section_mesh)


def _plate(**options):
    return PlateProblem(plate_mesh(4.0, 1.0, 4.0, 2, 1, 1, symmetry="quarter"),
                        NeoHookeanDielectric(1.0, 1.0), **options)


def _blocks_partition(layout: Layout) -> bool:
    allidx = np.concatenate(list(layout.blocks.values()))
    return np.array_equal(np.sort(allidx), np.arange(layout.n))


@pytest.mark.parametrize("make", [
    lambda: _plate(),
    lambda: _plate(control="voltage"),
    lambda: _plate(coupling="maxwell", field="local"),
    lambda: CrossSection(section_mesh(20.0, 1.0, 2, 1), NeoHookeanDielectric()),
    lambda: MembranePlate(membrane_mesh(100.0, 1.0, 50.0, 2, 1), NeoHookeanDielectric(),
                          loading="uniaxial"),
], ids=["plate", "plate-voltage", "plate-maxwell-local", "cross-section", "membrane"])
def test_layout_blocks_partition_the_unknowns(make):
    pb = make()
    assert isinstance(pb, Problem)
    assert pb.layout.n == pb.initial_state().size == pb.ndofs
    assert _blocks_partition(pb.layout)


def test_layout_multipliers_count_the_negative_eigenvalues_of_the_unloaded_tangent():
    # Haynsworth: the saddle-point tangent of a stable state has exactly as many negative
    # eigenvalues as multiplier (p) and potential (phi) unknowns; the unloaded plate is
    # stable, so a dense eigenvalue count must equal the layout's count (an independent
    # check that the layout names the right blocks)
    for pb in (_plate(), CrossSection(section_mesh(20.0, 1.0, 2, 1), NeoHookeanDielectric())):
        K, _ = pb.assemble(pb.initial_state(), np.zeros(len(pb.load_names)))
        ev = np.linalg.eigvalsh(K.toarray())
        tol = 1e-10 * np.abs(ev).max()      # round-off of the dense eigensolver
        assert np.all(np.abs(ev) > tol)
        n_neg = int(np.sum(ev < 0))
        assert n_neg == pb.layout.n_multipliers > 0
        assert pb.stability((ev.size - n_neg, n_neg, 0)) is True
        assert pb.stability((ev.size - n_neg - 1, n_neg + 1, 0)) is False


def test_plate_load_vector_closed_form_matches_central_differences():
    pb = _plate()
    rng = np.random.default_rng(3)
    x = 0.01 * rng.standard_normal(pb.ndofs)
    load = np.array([0.7, 1.3])
    exact = pb.load_vector(x, load)
    fd = Problem.load_vector(pb, x, load)
    assert exact.shape == (pb.ndofs, 2)
    # the loads enter linearly: central differences are exact up to round-off
    # (~1e-16 |r| / h with h = 1e-6, i.e. ~1e-10 of the largest entry)
    assert np.abs(fd - exact).max() <= 1e-7 * np.abs(exact).max()


def test_non_symmetric_problem_has_no_stability_verdict():
    pb = _plate(coupling="maxwell")
    assert pb.symmetric is False
    assert pb.stability((10, 0, 0)) is None


def test_ramp_rejects_an_object_outside_the_contract():
    class Duck:
        def initial_state(self):
            return np.zeros(1)

    with pytest.raises(ValueError, match="problem must be a skfem_dielectric.Problem"):
        ramp(Duck(), [1.0])


def test_layout_rejects_unknown_multiplier_blocks():
    with pytest.raises(ValueError, match="multipliers"):
        Layout(2, {"u": np.arange(2)}, ("p",))


# one construction convention: mesh, material, keyword-only options (docs/fe.md)
MODELS = {
    "plate": (PlateProblem, plate_mesh(4.0, 1.0, 4.0, 1, 1, 1, symmetry="eighth")),
    "membrane": (MembranePlate, membrane_mesh(4.0, 1.0, 4.0, 1, 1)),
    "section": (CrossSection, section_mesh(4.0, 1.0, 1, 1)),
}


@pytest.mark.parametrize("name, value", [
    ("mesh", plate_mesh(4.0, 1.0, 4.0, 1, 1, 1).mesh), ("mesh", None),
    ("material", "rubber"), ("material", None),
    ("loading", "clamped"), ("control", "current"), ("coupling", "both"),
    ("field", "remote"), ("phi_element", 2), ("intorder", 0), ("intorder", 2.5),
    ("grad_div", -1.0), ("grad_div", "x"),
])
def test_models_reject_the_same_bad_input_alike(name, value):
    """Every model that has the parameter rejects the value with a ValueError whose
    message starts with the parameter's name and names the value; all but ``mesh`` (whose
    message names each model's own mesh type) give the same message word for word."""
    mat = NeoHookeanDielectric(1.0, 1.0)
    messages = {}
    for label, (model, mesh) in MODELS.items():
        if name not in inspect.signature(model).parameters:
            continue
        args = {"mesh": mesh, "material": mat, name: value}
        with pytest.raises(ValueError, match=rf"^{name} must ") as err:
            model(args.pop("mesh"), args.pop("material"), **args)
        messages[label] = str(err.value)
        shown = type(value).__name__ if name == "mesh" else repr(value)
        assert shown in messages[label]
    assert len(messages) >= 2                 # a parameter the models share
    if name != "mesh":
        assert len(set(messages.values())) == 1, messages


def test_models_take_options_by_keyword_only():
    """After the mesh and the material every parameter is keyword-only."""
    for model, _ in MODELS.values():
        params = list(inspect.signature(model).parameters.values())
        assert [p.name for p in params[:2]] == ["mesh", "material"]
        assert all(p.kind is p.KEYWORD_ONLY for p in params[2:])
