"""Balancing the cart-pole with LQR, on the module eomgen builds from models/cart_pole.eom.

    eomgen python models/cart_pole.eom -o modules
    PYTHONPATH=modules python3 examples/python/cart_pole_lqr.py --plot cart_pole_lqr.svg

The module gives A and B about the upright pole (theta = 0 is upright in the model file), SciPy
the LQR gain K, and the closed loop u = -K x runs twice from a tilted pole: by SciPy's solve_ivp
calling the module's forward_dynamics, and by the module's own C++ integrator (simulate). The
two runs agree; the plot shows x, theta and u against time. Needs NumPy, SciPy and Matplotlib.
"""
import argparse

import numpy as np
import scipy.integrate
import scipy.linalg

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402 (after the backend)

import cart_pole  # noqa: E402 (the module: its directory on PYTHONPATH)

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("--plot", default="cart_pole_lqr.svg", help="the SVG written (default: %(default)s)")
parser.add_argument("--t-end", type=float, default=10.0, help="simulated time [s] (default: %(default)s)")
parser.add_argument("--pole-length", type=float, default=1.0, help="the parameter l [m] (default: %(default)s)")
args = parser.parse_args()

p = cart_pole.Parameters(l=args.pole_length)  # the model's defaults for mc, mp, rp, g
nq = cart_pole.nq  # q = [x, theta]; the state x = [q; qd] = [x, theta, x_dot, theta_dot]

# A and B of dx' = A dx + B du about the upright pole at rest, with no force (u=None: zero inputs)
A, B = cart_pole.linearization(0.0, np.zeros(nq), np.zeros(nq), None, p)

# The weights by Bryson's rule, each the inverse square of the largest value we accept: the cart
# within 1 m of the origin, the pole within 0.2 rad (about 11 degrees) of upright, the force
# within 10 N. The rates are left free (weight 0): what matters is where cart and pole are, and
# the LQR damps the rates to bring them there. (A, B) is controllable and Q sees both coordinates
# (their rates follow from them), so the loop A - B K is stable.
Q = np.diag([1 / 1.0**2, 1 / 0.2**2, 0.0, 0.0])
R = np.array([[1 / 10.0**2]])
P = scipy.linalg.solve_continuous_are(A, B, Q, R)
K = np.linalg.solve(R, B.T @ P)  # u = -K x, K of shape (nu, nx) = (1, 4)
eigenvalues = np.linalg.eigvals(A - B @ K)


def control(t, x):
    return -K @ x  # the force [N] on the cart, shape (nu,)


x0 = np.array([0.0, 0.3, 0.0, 0.0])  # the pole tilted 0.3 rad, at rest

# 1. The module's own integrator: classic Runge-Kutta with a fixed 1 ms step, control(t, x)
#    called at every evaluation of the dynamics; t and x at about 1000 samples
t, x = cart_pole.simulate(args.t_end, x0, p, control, method="rk4", dt=0.001)


# 2. SciPy's integrator on the same equations: x' = [qd; qdd], qdd from the module
def rhs(t, x):
    q, qd = x[:nq], x[nq:]
    return np.concatenate([qd, cart_pole.forward_dynamics(t, q, qd, control(t, x), p)])


run = scipy.integrate.solve_ivp(rhs, (0.0, args.t_end), x0, method="DOP853", t_eval=t, rtol=1e-10, atol=1e-12)
assert run.success, run.message
difference = np.max(np.abs(run.y.T - x))

u = -x @ K.T  # the force at every sample, shape (N, nu)

print(f"cart_pole: {p}")
print(f"gain K (u = -K x, x = [{', '.join(cart_pole.state_names)}]):", *(f"{k:.6f}" for k in K.ravel()))
print("closed-loop eigenvalues:", *(f"{z.real:.4f}{z.imag:+.4f}j" for z in eigenvalues))
print(f"solve_ivp (DOP853, rtol 1e-10) vs simulate (rk4, dt 1 ms): largest difference {difference:.2e}")
print(f"final state at t = {t[-1]:g} s:",
      ", ".join(f"{name} = {value:.3e}" for name, value in zip(cart_pole.state_names, x[-1])))

# The coordinates and the force against time: simulate solid, solve_ivp dashed on top
figure, axes = plt.subplots(3, 1, sharex=True, figsize=(7, 6))
series = [(x[:, 0], run.y[0], "x [m]"), (x[:, 1], run.y[1], "theta [rad]"), (u[:, 0], -(K @ run.y)[0], "u [N]")]
for ax, (own, scipy_run, label) in zip(axes, series):
    ax.plot(t, own, label="cart_pole.simulate (rk4)")
    ax.plot(t, scipy_run, "--", label="solve_ivp (DOP853)")
    ax.set_ylabel(label)
    ax.grid(True)
axes[0].set_title(f"Cart-pole balanced by LQR from theta = {x0[1]} rad")
axes[0].legend()
axes[-1].set_xlabel("t [s]")
figure.tight_layout()
figure.savefig(args.plot)
print(f"plot: {args.plot}")
