"""simulate() runs the runtime as `eomgen simulate` does: the same samples, the same states."""
import csv
import os
import subprocess

import numpy as np
import pytest

from conftest import EOMGEN, SOURCE_DIR

CACHE = os.environ.get("EOMGEN_TEST_CACHE_DIR")


def eomgen_simulate(model, tmp_path, *options):
    out = tmp_path / "run.csv"
    command = [EOMGEN, "simulate", str(SOURCE_DIR / "models" / f"{model}.eom"), "-o", str(out), "--no-plot",
               *options]
    if CACHE:
        command += ["--cache-dir", CACHE]
    subprocess.run(command, check=True, capture_output=True, timeout=600)
    with open(out) as f:
        rows = list(csv.reader(f))
    header, data = rows[0], np.array([[float(v) for v in row] for row in rows[1:]])
    return header, data


@pytest.mark.parametrize("method, step", [("dp5", None), ("rk4", 0.002)])
def test_simulate_equals_the_csv_of_eomgen_simulate(tmp_path, method, step):
    import cart_pole as m
    options = ["--t-end", "2", "--init", "theta=0.3,x_dot=0.1", "--input", "u=0.5", "--method", method]
    if step:
        options += ["--dt", str(step)]
    header, data = eomgen_simulate("cart_pole", tmp_path, *options)
    t, x = m.simulate(2.0, [0.0, 0.3, 0.1, 0.0], u=[0.5], method=method, dt=step)
    assert header[:1 + m.nx] == ["t", *m.state_names]
    assert np.array_equal(t, data[:, 0])
    # the CSV's %.17g reads back every double exactly
    assert np.array_equal(x, data[:, 1:1 + m.nx])


def test_a_closed_loop_from_a_consistent_start_follows_eomgen_simulate(tmp_path):
    import four_bar as m
    _, assembled = eomgen_simulate("four_bar", tmp_path, "--t-end", "0.001", "--init", f"{m.coordinate_names[0]}=0.4")
    x0 = assembled[0, 1:1 + m.nx]  # the start eomgen assembled
    # given whole, to both: each keeps it (it is consistent) and projects it once, as the run starts
    given = ",".join(f"{name}={value!r}" for name, value in zip(m.state_names, x0))
    header, data = eomgen_simulate("four_bar", tmp_path, "--t-end", "1", "--init", given)
    t, x = m.simulate(1.0, x0)
    assert np.array_equal(t, data[:, 0])
    assert np.array_equal(x, data[:, 1:1 + m.nx])


def test_inputs_from_a_callable_equal_the_same_constant_inputs():
    import cart_pole as m
    _, constant = m.simulate(1.0, [0.0, 0.2, 0.0, 0.0], u=[0.3])
    _, called = m.simulate(1.0, [0.0, 0.2, 0.0, 0.0], u=lambda t, x: np.array([0.3]))
    assert np.array_equal(constant, called)


def test_a_state_feedback_sees_the_state_it_acts_on():
    import cart_pole as m
    seen = []

    def u(t, x):
        seen.append((t, x.copy()))
        return [-2.0 * x[2]]
    t, x = m.simulate(1.0, [0.0, 0.0, 1.0, 0.0], u=u, method="rk4", dt=0.01, sample=0.5)
    assert len(t) == 3 and x.shape == (3, 4)
    assert seen[0][0] == 0.0 and np.array_equal(seen[0][1], [0.0, 0.0, 1.0, 0.0])
    assert 0 < x[-1, 2] < 1.0  # the damping force slowed the cart
