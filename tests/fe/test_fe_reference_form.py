"""The fast mixed u-p-phi assembly equals the weak form written as scikit-fem integrands.

``skfem_dielectric.forms.reference.ReferenceForm`` is the readable statement of the form
(plain ``BilinearForm``/``LinearForm`` over the strain energy ``W(I1)``);
``MixedUPPhiForm`` is the batched, threaded assembly the models use.  They share no code
beyond the material's ``energy_derivatives``.
"""

import numpy as np
import pytest
import scipy.sparse as sp
from skfem import MeshHex

from skfem_dielectric.fem.assembly import DofReduction
from skfem_dielectric.forms.mixed_upphi import MixedUPPhiForm
from skfem_dielectric.forms.reference import ReferenceForm
from skfem_dielectric.materials import GentDielectric, NeoHookeanDielectric

MATERIALS = [NeoHookeanDielectric(mu=1.0, eps=1.0), GentDielectric(mu=1.3, eps=0.7, Jm=20.0)]


def _state(fast, seed):
    """A generic state: displacements ~5 % of the mesh size, pressure and potential O(1)
    (no symmetry the two assemblies could share by accident)."""
    rng = np.random.default_rng(seed)
    xf = 0.05 * rng.standard_normal(fast.n_full)
    xf[fast.fields["p"]] = 0.3 * rng.standard_normal(fast.n_p)
    xf[fast.fields["phi"]] = 0.8 * rng.standard_normal(fast.n_phi)
    return xf


@pytest.fixture(scope="module")
def mesh():
    # 2 x 1 x 2 elements of unequal sides: every block and face orientation is exercised
    return MeshHex.init_tensor(np.linspace(0, 1, 3), np.linspace(0, 0.5, 2),
                               np.linspace(0, 0.7, 3))


@pytest.mark.parametrize("material", MATERIALS, ids=lambda m: type(m).__name__)
@pytest.mark.parametrize("threads", [1, 2])
def test_fast_assembly_equals_the_reference_form(mesh, material, threads):
    fast = MixedUPPhiForm(mesh, material, threads=threads, chunk=1)
    fast.bind(DofReduction(fast.n_full))
    ref = ReferenceForm(mesh, material)
    perm = ref.from_mixed_upphi(fast)
    assert np.array_equal(np.sort(perm), np.arange(fast.n_full))     # a permutation
    xf = _state(fast, seed=threads)
    data, r = fast.assemble(xf)
    sc = fast.scatter
    K = sp.csr_matrix((data, sc.indices, sc.indptr), shape=(sc.n, sc.n))[perm][:, perm]
    Kr, rr = ref.tangent(xf[perm]), ref.residual(xf[perm])
    # the same quadrature and the same algebra in another order: round-off only (measured
    # 6e-13 relative to the largest entry; 1e-12 leaves room for the summation order)
    assert np.abs(rr - r[perm]).max() <= 1e-12 * np.abs(r).max()
    assert abs(Kr - K).max() <= 1e-12 * abs(K).max()


@pytest.mark.parametrize("material", MATERIALS, ids=lambda m: type(m).__name__)
def test_reference_tangent_is_the_derivative_of_its_residual(mesh, material):
    """The reference tangent against central differences of the reference residual."""
    fast = MixedUPPhiForm(mesh, material)
    ref = ReferenceForm(mesh, material)
    x = _state(fast, seed=7)[ref.from_mixed_upphi(fast)]
    # a direction of the state's own size (an O(1) displacement direction on elements of
    # size 0.5 makes the third derivatives, hence the truncation error, large)
    d = _state(fast, seed=8)[ref.from_mixed_upphi(fast)]
    h = 1e-5
    fd = (ref.residual(x + h * d) - ref.residual(x - h * d)) / (2 * h)
    Kd = ref.tangent(x) @ d
    # central differences: truncation O(h^2) and round-off O(1e-16/h) relative, both far
    # below 1e-7; a 0.1 % error in one block of the tangent gives 1.6e-5 (checked)
    err = np.abs(fd - Kd).max() / np.abs(Kd).max()
    assert err <= 1e-7, err
