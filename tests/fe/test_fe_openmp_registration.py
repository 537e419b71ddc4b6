"""Intel OpenMP's /dev/shm registration: MKL_THREADING_LAYER=sequential avoids it, so a
killed process leaves no file (docs/fe.md, Linear solvers)."""

import os
import signal
import subprocess
import sys
import textwrap

import pytest

from skfem_dielectric.linalg import pardiso_available

SCRIPT = textwrap.dedent("""
    import os, signal
    import numpy as np
    from skfem_dielectric import get_linear_solver
    from skfem_dielectric.gallery import equibiaxial_problem
    pb = equibiaxial_problem()
    K, r = pb.assemble(pb.initial_state(), (0.5, 1.0))
    get_linear_solver("pardiso").solve(K, r)
    print(os.getpid(), flush=True)
    os.kill(os.getpid(), signal.SIGKILL)
""")


@pytest.mark.skipif(not pardiso_available() or not os.path.isdir("/dev/shm"),
                    reason="needs pypardiso and /dev/shm")
def test_sequential_mkl_leaves_no_registration_file_when_killed():
    env = dict(os.environ, MKL_THREADING_LAYER="sequential")
    out = subprocess.run([sys.executable, "-c", SCRIPT], env=env, capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == -signal.SIGKILL, out.stderr
    pid = int(out.stdout.split()[0])
    left = [f for f in os.listdir("/dev/shm") if f.startswith(f"__KMP_REGISTERED_LIB_{pid}_")]
    assert left == []
