"""What the Python modules' tests share: the modules ctest built (tests/python/CMakeLists.txt
puts their directory on PYTHONPATH and names them in EOMGEN_TEST_MODULES), the eomgen program,
and the states every test evaluates at."""
import importlib
import os
import pathlib

import numpy as np
import pytest

MODULES = [m for m in os.environ.get("EOMGEN_TEST_MODULES", "").split(",") if m]
EOMGEN = os.environ.get("EOMGEN_EXE", "eomgen")
SOURCE_DIR = pathlib.Path(os.environ.get("EOMGEN_SOURCE_DIR", pathlib.Path(__file__).parents[2]))


def entry(i, k, a, b, modulus):
    """Entry i of state k, as tests/python/reference_values.cpp computes it, bit for bit."""
    return ((i * a + k * b) % modulus) / (modulus / 2.0) - 1.0


def reference_state(m, k):
    """State k of reference_values.cpp: t, q, qd, qdd, u."""
    q = np.array([entry(i, k, 31, 17, 97) for i in range(m.nq)])
    qd = np.array([entry(i, k, 13, 29, 89) for i in range(m.nq)])
    qdd = np.array([entry(i, k, 5, 3, 79) for i in range(m.nq)])
    u = np.array([entry(i, k, 7, 11, 23) for i in range(m.nu)])
    return k / 4.0, q, qd, qdd, u


@pytest.fixture(params=MODULES)
def module(request):
    return importlib.import_module(request.param)
