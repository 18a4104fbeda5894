"""The example of examples/python/ runs as the README shows it, and its figures are right: the
gain against an LQR of the cart-pole's linearization derived here by hand, the closed loop
stable, the pole upright at the end, SciPy's run and the module's own in agreement."""
import re
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

import numpy as np
import pytest
import scipy.linalg

from conftest import SOURCE_DIR

EXAMPLE = SOURCE_DIR / "examples" / "python" / "cart_pole_lqr.py"

# The weights the example chooses (Bryson's rule: cart 1 m, pole 0.2 rad, force 10 N)
Q = np.diag([1.0, 25.0, 0.0, 0.0])
R = np.array([[0.01]])


def hand_linearization(mc=1.0, mp=0.1, l=1.0, rp=0.01, g=9.81):
    """A and B of the cart-pole about the upright pole at rest (models/cart_pole.eom): with h = l/2
    and J = mp (l^2/3 + rp^2/4) the rod's inertia about the hinge, T = (mc + mp) x_dot^2 / 2 -
    mp h cos(theta) x_dot theta_dot + J theta_dot^2 / 2 and V = mp g h cos(theta), so to first
    order M0 qdd = [u, mp g h theta] with M0 = [[mc + mp, -mp h], [-mp h, J]]."""
    h, J = l / 2, mp * (l**2 / 3 + rp**2 / 4)
    M0 = np.array([[mc + mp, -mp * h], [-mp * h, J]])
    stiffness = np.linalg.solve(M0, np.array([[0.0, 0.0], [0.0, mp * g * h]]))
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [stiffness, np.zeros((2, 2))]])
    B = np.concatenate([np.zeros(2), np.linalg.solve(M0, [1.0, 0.0])]).reshape(4, 1)
    return A, B


def hand_gain(l):
    A, B = hand_linearization(l=l)
    K = np.linalg.solve(R, B.T @ scipy.linalg.solve_continuous_are(A, B, Q, R))
    return A, B, K


def run_example(tmp_path, *options):
    plot = tmp_path / "lqr.svg"
    run = subprocess.run([sys.executable, str(EXAMPLE), "--plot", str(plot), *options], capture_output=True,
                         text=True, timeout=300, cwd=tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
    return run.stdout, plot


def figures(output, label):
    """The words after the colon of the output's one line that starts with label."""
    lines = [line for line in output.splitlines() if line.startswith(label)]
    assert len(lines) == 1, f"no single line '{label}...' in:\n{output}"
    return lines[0].split(":", 1)[1].split()


def named_figures(output, label):
    """The 'name = number' pairs after the colon of the line that starts with label, as a dict."""
    pairs = re.findall(r"(\w+) = ([-+.\deE]+)", " ".join(figures(output, label)))
    return {name: float(value) for name, value in pairs}


def test_the_hand_linearization_is_the_modules():
    import cart_pole as m
    for l in (1.0, 2.0):
        A, B = m.linearization(0.0, [0.0, 0.0], [0.0, 0.0], p=m.Parameters(l=l))
        A_hand, B_hand = hand_linearization(l=l)
        np.testing.assert_allclose(A, A_hand, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(B, B_hand, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("l", [1.0, 2.0])
def test_the_example_balances_the_pole_with_the_lqr_gain(tmp_path, l):
    options = [] if l == 1.0 else ["--pole-length", str(l), "--t-end", "15"]
    output, plot = run_example(tmp_path, *options)
    A, B, K = hand_gain(l)

    printed_K = np.array([float(v) for v in figures(output, "gain K")])
    np.testing.assert_allclose(printed_K, K.ravel(), rtol=1e-5, atol=1e-6)
    assert printed_K[1] > 0  # theta > 0 tips the pole to -x: the cart is pushed to -x to catch it

    printed = np.sort_complex([complex(v) for v in figures(output, "closed-loop eigenvalues")])
    expected = np.sort_complex(np.linalg.eigvals(A - B @ K))
    assert np.all(printed.real < 0)
    np.testing.assert_allclose(printed, expected, atol=1e-3)

    difference = float(figures(output, "solve_ivp")[-1])
    assert 0 <= difference < 1e-6  # two integrators, one set of equations

    final = named_figures(output, "final state")
    assert set(final) == {"x", "theta", "x_dot", "theta_dot"}
    assert all(abs(v) < 1e-3 for v in final.values()), final  # at rest, upright, near the origin

    svg = ElementTree.parse(plot).getroot()
    assert svg.tag == "{http://www.w3.org/2000/svg}svg"
    assert len(svg.findall(".//{http://www.w3.org/2000/svg}path")) > 10  # axes and curves were drawn
