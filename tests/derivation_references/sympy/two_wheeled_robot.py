"""Independent reference for the two-wheeled self-balancing robot
(tests/derivation_references/pending/two_wheeled_robot.eom, to become models/two_wheeled_robot.eom):
Lagrange's equations in SymPy with the four no-slip rows of the two wheels, written in
components of the inertial frame a and the heading frame h (no eomgen), in the model's
coordinates and with its parameter values; and the linearization of the balance at a forward
speed with an LQR gain.

Rerun from the repository root:

    python3 tests/derivation_references/sympy/two_wheeled_robot.py             # C++ literals
    python3 tests/derivation_references/sympy/two_wheeled_robot.py --lqr [V]   # A, B, K at speed V (1 m/s)

and paste the first's output into the marked block of two_wheeled_robot_test.cpp. (SymPy 1.14,
mpmath; no numpy or scipy: the Riccati equation is solved from the stable invariant subspace of
the Hamiltonian matrix with mpmath.)

Model: a.3 up, the ground the plane z = 0 through w, gravity -g a.3. Heading frame h:
C_ha = C3(psi), h.1 forward, h.2 along the axle to the left. Chassis frame c: C_ch = C2(theta),
theta the pitch (positive tilts the chassis forward, c.3 = sin(theta) h.1 + cos(theta) h.3), the
chassis mass centre d along c.3 from the axle's midpoint O = (x, y, r). Wheel k (l: +1 to the left,
r: -1) is centred at O + s_k track/2 h.2 and turns by phi_k relative to the chassis about h.2
(the motor angle), so its angular velocity is psi_dot a.3 + (theta_dot + phi_k_dot) h.2; it is a
disk with inertia J_a about the axle and J_d about a diameter, the same in h at every spin.
Motor k puts tau_k h.2 on wheel k and -tau_k h.2 on the chassis: generalized force tau_k on phi_k.

Constraints, as the `wheel` statement writes them with normal a.3 (t1 = a.2, t2 = -a.1): for the
material point of wheel k at its contact C_k = centre_k - r a.3,
    k_1: a.2 . v = 0,   k_2: -a.1 . v = 0,   v = v_centre + omega_k x (-r a.3).
The four rows have rank 3 (both wheels' contacts move alike along the axle); the reference
states satisfy all four, the accelerations are those of any 3 independent rows (unique), and
so is the generalized constraint force Xi^T lambda = M qdd - F, printed instead of lambda.
"""
import os
import sys

import mpmath
import sympy as sp

sys.dont_write_bytecode = True   # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference_common import (exact, kkt_solve, lagrange, matrix_value, rate_acceleration_term,  # noqa: E402
                              literal, to_double)

PARAMETERS = {'r': '0.1', 'track': '0.4', 'd': '0.3', 'm_c': '10', 'I_c1': '0.6', 'I_c2': '0.5',
              'I_c3': '0.2', 'm_w': '1', 'J_a': '0.005', 'J_d': '0.0025', 'g': '9.81'}
P = {k: sp.Symbol(k, positive=True) for k in PARAMETERS}
r, track, d, m_c, I_c1, I_c2, I_c3, m_w, J_a, J_d, g = (P[k] for k in PARAMETERS)

NAMES = ['x', 'y', 'psi', 'theta', 'phi_l', 'phi_r']
q = sp.symbols(' '.join(NAMES))
qd = sp.symbols(' '.join(n + '_dot' for n in NAMES))
x, y, psi, theta, phi_l, phi_r = q
xd, yd, psid, thetad, phild, phird = qd
tau_l, tau_r = sp.symbols('tau_l tau_r')
ROWS = ['left_1', 'left_2', 'right_1', 'right_2']

h1 = sp.Matrix([sp.cos(psi), sp.sin(psi), 0])
h2 = sp.Matrix([-sp.sin(psi), sp.cos(psi), 0])
a3 = sp.Matrix([0, 0, 1])
O = sp.Matrix([x, y, r])
G = O + d * (sp.sin(theta) * h1 + sp.cos(theta) * a3)


def velocity(p):
    return p.jacobian(q) * sp.Matrix(qd)


def sq(v):
    return (v.T * v)[0]


# kinetic energy: chassis (omega in c: [-psi_dot sin(theta), theta_dot, psi_dot cos(theta)]) and wheels
T = m_c * sq(velocity(G)) / 2 + (I_c1 * (psid * sp.sin(theta))**2 + I_c2 * thetad**2
                                   + I_c3 * (psid * sp.cos(theta))**2) / 2
V = m_c * g * G[2] + 2 * m_w * g * r
rows = []
for side, phik_dot in ((1, phild), (-1, phird)):
    centre = O + side * track / 2 * h2
    spin = thetad + phik_dot
    T += m_w * sq(velocity(centre)) / 2 + (J_a * spin**2 + J_d * psid**2) / 2
    omega = psid * a3 + spin * h2
    v = velocity(centre) + omega.cross(-r * a3)
    rows += [v[1], -v[0]]           # k_1: a.2 . v, k_2: -a.1 . v
Q = [0, 0, 0, 0, tau_l, tau_r]

M, F = lagrange(sp.expand(T), V, q, qd, Q)
rate = sp.Matrix(rows)
Xi = rate.jacobian(qd)
assert sp.simplify(rate - Xi * sp.Matrix(qd)) == sp.zeros(4, 1)
b = rate_acceleration_term(rate, q, qd)
numbers = {P[k]: exact(v) for k, v in PARAMETERS.items()}
R, TRACK = mpmath.mpf(PARAMETERS['r']), mpmath.mpf(PARAMETERS['track'])


def state(coords, theta_rate, wheel_rates, torques):
    """The rates of x, y, psi that roll without slip: psi_dot = r (phi_r_dot - phi_l_dot)/track,
    forward speed r (theta_dot + (phi_l_dot + phi_r_dot)/2) along h.1."""
    wl, wr = (mpmath.mpf(float(v)) for v in wheel_rates)
    th = mpmath.mpf(float(theta_rate))
    yaw = R * (wr - wl) / TRACK
    speed = R * (th + (wl + wr) / 2)
    heading = mpmath.mpf(float(coords[2]))
    rates = [to_double(speed * mpmath.cos(heading)), to_double(speed * mpmath.sin(heading)), to_double(yaw),
             float(theta_rate), float(wheel_rates[0]), float(wheel_rates[1])]
    at = dict(numbers)
    at.update({s: exact(float(v)) for s, v in zip(q, coords)})
    at.update({s: exact(v) for s, v in zip(qd, rates)})
    at.update({tau_l: exact(float(torques[0])), tau_r: exact(float(torques[1]))})
    names = [(n, float(v)) for n, v in zip(NAMES, coords)] + [(n + '_dot', v) for n, v in zip(NAMES, rates)] + \
        [('tau_l', float(torques[0])), ('tau_r', float(torques[1]))]
    return names, at


def cpp(values):
    return '{' + ', '.join(literal(v) for v in values) + '}'


def main():
    print('    // BEGIN two_wheeled_robot: generated by tests/derivation_references/sympy/two_wheeled_robot.py')
    for coords, th_rate, wheels, torques, comment in [
            ((0.3, -0.2, 0.4, 0.1, 0.5, -1.0), 0.2, (8.0, 10.0), (0.3, -0.1), 'pitched forward, turning left, driven'),
            ((-1.0, 2.0, -2.5, -0.25, 3.0, 2.0), -0.5, (-4.0, -6.0), (0.0, 0.0), 'pitched back, reversing, no torques'),
            ((0.0, 0.0, 1.2, 0.05, 0.0, 0.0), 0.0, (0.0, 0.0), (1.5, 1.5), 'at rest, nearly upright, driven')]:
        names, at = state(coords, th_rate, wheels, torques)
        Mn, Fn, Xin, bn = matrix_value(M, at), matrix_value(F, at), matrix_value(Xi, at), matrix_value(b, at)
        residual = max(abs(v) for v in Xin * mpmath.matrix([float(v) for _, v in names[6:12]]))
        assert residual < 1e-15, residual
        keep = [0, 1, 3]            # left_1, left_2, right_2: independent
        qdd, lam = kkt_solve(Mn, Fn, mpmath.matrix([[Xin[k, j] for j in range(6)] for k in keep]),
                             [bn[k] for k in keep])
        force = Mn * mpmath.matrix(qdd) - Fn
        print('    // ' + comment)
        print('    {{%s},' % ', '.join('{"%s", %s}' % (k, repr(float(v))) for k, v in names))
        print('     %s,  // M' % cpp([Mn[i, j] for i in range(6) for j in range(6)]))
        print('     %s,  // F' % cpp([Fn[i] for i in range(6)]))
        print('     {%s},  // Xi by row' % ', '.join('{"%s", %s}' % (ROWS[k], cpp([Xin[k, j] for j in range(6)]))
                                                    for k in range(4)))
        print('     {%s},  // b by row' % ', '.join('{"%s", %s}' % (ROWS[k], literal(bn[k])) for k in range(4)))
        print('     %s,  // qdd' % cpp(qdd))
        print('     %s,  // Xi^T lambda = M qdd - F' % cpp([force[i] for i in range(6)]))
        print('    },')
    print('    // END two_wheeled_robot')


# ---------------------------------------------------------------------------------------------
# Balance at a forward speed: generalized speeds u = (v, w, p): the forward speed of O along h.1,
# the yaw rate psi_dot and the pitch rate theta_dot. Then x_dot = v cos(psi), y_dot = v sin(psi),
# phi_l_dot = (v - track/2 w)/r - p, phi_r_dot = (v + track/2 w)/r - p satisfy all four rows:
# qd = Y(q) u. Kane's equations Y^T (M qdd - F) = 0 with qdd = Y u_dot + Y_dot u (Y^T Xi^T = 0).

def reduced_dynamics():
    v, w_, p = sp.symbols('v w p')
    u = [v, w_, p]
    Y = sp.Matrix([[sp.cos(psi), 0, 0], [sp.sin(psi), 0, 0], [0, 1, 0], [0, 0, 1],
                   [1 / r, -track / (2 * r), -1], [1 / r, track / (2 * r), -1]])
    qd_u = Y * sp.Matrix(u)
    assert sp.simplify(Xi * Y) == sp.zeros(4, 3)
    sub = dict(zip(qd, qd_u))
    Yd = sp.zeros(6, 3)
    for i in range(6):
        for j in range(3):
            Yd[i, j] = sum(sp.diff(Y[i, j], q[k]) * qd_u[k] for k in range(6))
    Mr = sp.simplify(Y.T * M.subs(sub) * Y)
    rhs = sp.simplify(Y.T * (F.subs(sub) - M.subs(sub) * Yd * sp.Matrix(u)))
    return u, Mr, rhs


def lqr(speed):
    u, Mr, rhs = reduced_dynamics()
    v, w_, p = u
    # state (s, theta, psi, v, w, p) about s = speed t, theta = psi = 0, v = speed, w = p = 0
    state = [sp.Symbol('s'), theta, psi, v, w_, p]
    udot = Mr.LUsolve(rhs)
    f = sp.Matrix([v, p, w_, udot[0], udot[1], udot[2]])
    point = {theta: 0, psi: 0, v: speed, w_: 0, p: 0, tau_l: 0, tau_r: 0}
    point.update(numbers)
    assert all(abs(value(e, point)) < 1e-30 for e in udot), 'not an equilibrium'
    A = mpmath.matrix([[value(sp.diff(f[i], s), point) for s in state] for i in range(6)])
    B = mpmath.matrix([[value(sp.diff(f[i], s), point) for s in (tau_l, tau_r)] for i in range(6)])
    Qw = mpmath.eye(6)
    Rw = mpmath.eye(2)
    X = care(A, B, Qw, Rw)
    K = mpmath.inverse(Rw) * B.T * X
    return A, B, K, X


def value(e, point):
    return mpmath.mpf(str(sp.N(sp.sympify(e).subs(point), 40)))


def care(A, B, Qw, Rw):
    """The stabilizing solution X of A^T X + X A - X B R^-1 B^T X + Q = 0, from the stable
    invariant subspace of the Hamiltonian matrix."""
    n = A.rows
    G = B * mpmath.inverse(Rw) * B.T
    H = mpmath.zeros(2 * n, 2 * n)
    for i in range(n):
        for j in range(n):
            H[i, j], H[i, n + j] = A[i, j], -G[i, j]
            H[n + i, j], H[n + i, n + j] = -Qw[i, j], -A[j, i]
    E, ER = mpmath.eig(H)
    stable = [k for k in range(2 * n) if mpmath.re(E[k]) < 0]
    assert len(stable) == n, E
    U1 = mpmath.matrix(n, n)
    U2 = mpmath.matrix(n, n)
    for c, k in enumerate(stable):
        for i in range(n):
            U1[i, c], U2[i, c] = ER[i, k], ER[n + i, k]
    X = U2 * mpmath.inverse(U1)
    X = mpmath.matrix([[mpmath.re(X[i, j]) for j in range(n)] for i in range(n)])
    residual = A.T * X + X * A - X * G * X + Qw
    assert mpmath.mnorm(residual, 1) < mpmath.mpf(10)**-25, residual
    return X


def show(name, m):
    print(name + ' =')
    for i in range(m.rows):
        print('  [' + ', '.join(mpmath.nstr(m[i, j], 10, min_fixed=-3, max_fixed=4) for j in range(m.cols)) + ']')


def print_lqr(speed):
    A, B, K, X = lqr(sp.Rational(str(speed)))
    print('Balance at v = %s m/s, state (s - v t, theta, psi, v, psi_dot, theta_dot), input (tau_l, tau_r);' % speed)
    print('LQR with Q = I6, R = I2, u = -K x:')
    show('A', A)
    show('B', B)
    show('K', K)
    closed = A - B * K
    E, _ = mpmath.eig(closed)
    print('open-loop eigenvalues:', ', '.join(mpmath.nstr(e, 6) for e in mpmath.eig(A)[0]))
    print('closed-loop eigenvalues:', ', '.join(mpmath.nstr(e, 6) for e in E))
    print('pitch eigenvalues: +-%s' % literal(mpmath.sqrt(A[5, 1])))


if __name__ == '__main__':
    if '--lqr' in sys.argv:
        i = sys.argv.index('--lqr')
        print_lqr(sys.argv[i + 1] if i + 1 < len(sys.argv) else '1')
    else:
        main()
