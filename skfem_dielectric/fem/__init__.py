"""Discretisation machinery, without physics: the sparse assembly of element chunks into a
fixed pattern and the elimination of Dirichlet and tied dofs
(:mod:`~skfem_dielectric.fem.assembly`), where it runs: threads, BLAS threads, the heap
(:mod:`~skfem_dielectric.fem.runtime`), the structured hexahedral plate mesh with its
symmetry planes and boundary names (:mod:`~skfem_dielectric.fem.mesh`), and the
quadrilateral meshes and batched point gradients of the 2D models
(:mod:`~skfem_dielectric.fem.mesh2d`).
"""

from .assembly import BlockScatter, DofReduction, OrderedSum, ScatterMap, drop_spare_slots
from .runtime import blas_threads, blas_thread_limit, single_threaded_blas, trim_heap
from .mesh import PlateMesh, plate_mesh, SYMMETRIES
from .mesh2d import BatchedVectorForm, point_gradients, quarter_quad_mesh

__all__ = [
    "BlockScatter", "DofReduction", "OrderedSum", "ScatterMap", "blas_threads",
    "blas_thread_limit",
    "drop_spare_slots", "single_threaded_blas", "trim_heap", "PlateMesh", "plate_mesh",
    "SYMMETRIES", "BatchedVectorForm", "point_gradients", "quarter_quad_mesh",
]
