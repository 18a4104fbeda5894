"""The modules' values are the C++ header's, bit for bit: reference_values.cpp, compiled from
the header each module was built from with the same flags, prints every value as a hexadecimal
float at the states conftest.reference_state gives, and the module must return the same bits."""
import importlib
import os
import subprocess

import numpy as np
import pytest

from conftest import reference_state

PROGRAMS = dict(entry.split("=", 1) for entry in os.environ.get("EOMGEN_TEST_REFERENCE_PROGRAMS", "").split(",")
                if entry)


def reference_values(program):
    """{(function, k): values} as the C++ program printed them."""
    out = subprocess.run([program], capture_output=True, text=True, check=True, timeout=120).stdout
    values = {}
    for line in out.splitlines():
        name, k, *numbers = line.split()
        values[(name, int(k))] = np.array([float.fromhex(v) for v in numbers])
    return values


def module_values(m, name, k):
    t, q, qd, qdd, u = reference_state(m, k)
    if name == "linearization.A":
        return m.linearization(t, q, qd, u)[0]
    if name == "linearization.B":
        return m.linearization(t, q, qd, u)[1]
    arguments = {"t": t, "q": q, "qd": qd, "qdd": qdd, "u": u}
    return getattr(m, name)(**{a: arguments[a] for a in m.functions[name] if a != "p"})


@pytest.mark.parametrize("stem", sorted(PROGRAMS))
def test_every_value_equals_the_headers_bit_for_bit(stem):
    m = importlib.import_module(stem)
    expected = reference_values(PROGRAMS[stem])
    functions = {name for name, _ in expected}
    assert {"mass_matrix", "forcing", "kinetic_energy", "linearization.A"} <= functions
    for (name, k), values in expected.items():
        actual = np.ravel(module_values(m, name, k))
        assert actual.tobytes() == values.tobytes(), f"{stem}.{name} at state {k}: {actual} != {values}"
