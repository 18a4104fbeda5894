"""Shared by the SymPy reference derivations in this folder: Lagrange's equations in the
form eomgen uses (docs/conventions.md), the constraint terms, the KKT solve and the printing
of C++ literals. Nothing here reads eomgen's code or output.

    M(q) qdd = F(q, qd, t, u) + Xi^T lambda,     Xi qd + Xi_t = 0,
    Xi qdd + b = 0 with b = dXi/dt qd + dXi_t/dt,
    [[M, -Xi^T], [-Xi, 0]] [qdd; lambda] = [F; b].

Numbers are evaluated with mpmath at DIGITS significant digits from exact rationals (the
parameters as written in the model, the states as the doubles the C++ test passes).
"""
from fractions import Fraction

import mpmath
import sympy as sp

DIGITS = 40
mpmath.mp.dps = DIGITS


def lagrange(T, V, q, qd, Q, t=None):
    """M and F of Lagrange's equations for kinetic energy T(q, qd, t), potential V(q, t) and
    generalized forces Q (list): F_i = dT/dq_i - sum_j d2T/dqd_i dq_j qd_j - d2T/dqd_i dt
    - dV/dq_i + Q_i."""
    n = len(q)
    M = sp.Matrix(n, n, lambda i, j: sp.diff(T, qd[i], qd[j]))
    F = []
    for i in range(n):
        p = sp.diff(T, qd[i])
        f = sp.diff(T, q[i]) - sum(sp.diff(p, q[j]) * qd[j] for j in range(n)) - sp.diff(V, q[i]) + Q[i]
        if t is not None:
            f -= sp.diff(p, t)
        F.append(f)
    return M, sp.Matrix(F)


def holonomic_terms(phi, q, qd, t=None):
    """Xi = dphi/dq, Xi_t = dphi/dt and b = d(Xi qd + Xi_t)/dt at qdd = 0."""
    Xi = phi.jacobian(q)
    Xi_t = sp.diff(phi, t) if t is not None else sp.zeros(phi.rows, 1)
    return Xi, Xi_t, rate_acceleration_term(Xi * sp.Matrix(qd) + Xi_t, q, qd, t)


def rate_acceleration_term(rate, q, qd, t=None):
    """For a rate-level constraint c(q, qd, t) = Xi qd + Xi_t: b = dc/dt with qdd = 0."""
    b = sp.zeros(rate.rows, 1)
    for k in range(rate.rows):
        e = sum(sp.diff(rate[k], q[j]) * qd[j] for j in range(len(q)))
        if t is not None:
            e += sp.diff(rate[k], t)
        b[k] = e
    return b


def exact(x):
    """The exact rational of a decimal string or a double (a double's binary value)."""
    if isinstance(x, str):
        return sp.Rational(x)
    return sp.Rational(Fraction(x))


def to_double(x):
    return float(mpmath.mpf(x))


def value(expr, subs):
    """expr at the exact substitution subs, as an mpmath number of DIGITS digits."""
    v = sp.N(expr.subs(subs), DIGITS)
    return mpmath.mpf(str(v))


def matrix_value(m, subs):
    return mpmath.matrix([[value(m[i, j], subs) for j in range(m.cols)] for i in range(m.rows)])


def kkt_solve(M, F, Xi, b):
    n, c = M.rows, Xi.rows
    K = mpmath.zeros(n + c, n + c)
    rhs = mpmath.zeros(n + c, 1)
    for i in range(n):
        rhs[i] = F[i]
        for j in range(n):
            K[i, j] = M[i, j]
        for k in range(c):
            K[i, n + k] = -Xi[k, i]
            K[n + k, i] = -Xi[k, i]
    for k in range(c):
        rhs[n + k] = b[k]
    x = mpmath.lu_solve(K, rhs)
    return [x[i] for i in range(n)], [x[n + k] for k in range(c)]


def literal(x):
    """A C++ double literal of the double nearest x (the shortest that reads back as it); below
    1e-30, the round-off of the 40-digit arithmetic, 0."""
    x = mpmath.mpf(x)
    return '0.0' if abs(x) < mpmath.mpf('1e-30') else repr(float(x))


def flat(m):
    if isinstance(m, mpmath.matrix):
        return [m[i, j] for i in range(m.rows) for j in range(m.cols)]
    return list(m)


def cpp_vector(values):
    return '{' + ', '.join(literal(v) for v in values) + '}'


def print_reference(name, at, parts, comment=None):
    """One Reference aggregate of closed_loop_models_test.cpp: `at` the (name, double) pairs of
    the state, parts the matrices in the struct's order (M, F, Xi, Xi_t, phi, b, qdd, lambda)."""
    if comment:
        print('    // ' + comment)
    pairs = ', '.join('{"%s", %s}' % (k, repr(float(v))) for k, v in at)
    print('    {{%s},' % pairs)
    for key in ('M', 'F', 'Xi', 'Xi_t', 'phi', 'b', 'qdd', 'lambda'):
        print('     %s,  // %s' % (cpp_vector(flat(parts[key])), key))
    print('    },')
