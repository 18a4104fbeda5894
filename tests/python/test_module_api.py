"""Every shipped model's module: its names, sizes and units; Parameters and Constants; every
generated function on one state and on a batch (the batch equals the loop, bit for bit, whatever
the arrays' layout); the runtime's linearization and assembly."""
import copy
import pickle

import numpy as np
import pytest

from conftest import module  # noqa: F401  (the fixture)

N = 7  # states per batch


def random_arguments(m, names, rng, n=None):
    """A value for each argument name: one state (n None) or a batch of n."""
    sizes = {"q": m.nq, "qd": m.nq, "qdd": m.nq, "u": m.nu, "lambda_": m.nc}
    values = {}
    for name in names:
        if name == "p":
            continue
        if name == "t":
            values[name] = float(rng.uniform(0, 1)) if n is None else rng.uniform(0, 1, n)
        else:
            shape = (sizes[name],) if n is None else (n, sizes[name])
            values[name] = rng.uniform(-0.5, 0.5, shape)
    return values


def as_tuple(result):
    return result if isinstance(result, tuple) else (result,)


def test_names_sizes_and_units_describe_the_model(module):
    m = module
    assert m.nx == 2 * m.nq
    assert len(m.coordinate_names) == m.nq and len(m.state_names) == 2 * m.nq
    assert m.state_names[m.nq:] == tuple(c + "_dot" for c in m.coordinate_names)
    assert len(m.input_names) == m.nu and len(m.parameter_names) == m.np
    assert len(m.constraint_names) == m.nc and len(m.output_names) == m.ny
    assert set(m.state_units) == set(m.state_names)
    assert set(m.parameter_units) == set(m.parameter_names)
    assert set(m.input_units) == set(m.input_names)
    assert m.name == m.__name__ and m.description in m.__doc__
    assert "mass_matrix" in m.functions and "forcing" in m.functions


def test_parameters_default_to_the_models_values_and_read_back_their_repr(module):
    m = module
    p = m.Parameters()
    assert list(p.to_dict().values()) == list(m.parameter_defaults.values())
    assert eval(repr(p), {m.__name__: m}) == p
    assert pickle.loads(pickle.dumps(p)) == p and copy.deepcopy(p) == p
    c = m.Constants(p)
    assert c.parameters == p
    assert pickle.loads(pickle.dumps(c)).parameters == p


def test_every_function_gives_on_a_batch_what_it_gives_state_by_state(module):
    m = module
    rng = np.random.default_rng(7)
    for name, names in m.functions.items():
        if set(names) <= {"p"}:
            continue  # of the parameters alone (inertial_parameters): no batch
        f = getattr(m, name)
        batch = random_arguments(m, names, rng, N)
        try:
            together = as_tuple(f(**batch))
        except ValueError as e:  # a state where the function refuses: the loop must refuse it too
            k = int(str(e).split("at state ")[1].split(":")[0])
            with pytest.raises(ValueError):
                f(**{a: v[k] for a, v in batch.items()})
            continue
        for k in range(N):
            one = as_tuple(f(**{a: v[k] for a, v in batch.items()}))
            for whole, single in zip(together, one):
                assert np.array_equal(whole[k], single), f"{m.__name__}.{name} at state {k}"


def test_a_batch_may_mix_one_value_with_n_values(module):
    m = module
    rng = np.random.default_rng(11)
    names = m.functions["forcing"]
    batch = random_arguments(m, names, rng, N)
    one_t = dict(batch, t=0.25)
    together = m.forcing(**one_t)
    assert together.shape == (N, m.nq)
    for k in range(N):
        assert np.array_equal(together[k], m.forcing(0.25, batch["q"][k], batch["qd"][k], batch["u"][k]))


def test_views_of_any_layout_read_the_same_values(module):
    m = module
    rng = np.random.default_rng(3)
    x = rng.uniform(-0.5, 0.5, (N, 2 * m.nq))
    t = np.linspace(0, 1, N)
    u = rng.uniform(-0.5, 0.5, (N, m.nu))
    contiguous = m.forcing(t, np.ascontiguousarray(x[:, :m.nq]), np.ascontiguousarray(x[:, m.nq:]), u)
    assert np.array_equal(m.forcing(t, x[:, :m.nq], x[:, m.nq:], u), contiguous)  # column blocks
    fortran = np.asfortranarray(x)
    assert np.array_equal(m.forcing(t, fortran[:, :m.nq], fortran[:, m.nq:], np.asfortranarray(u)), contiguous)
    swapped = m.forcing(t, x[:, :m.nq].astype(">f8"), x[:, m.nq:].astype(">f8"), u.astype(">f8"))
    assert np.array_equal(swapped, contiguous)  # big-endian: converted
    reversed_x = x[::-1]  # negative strides: copied
    assert np.array_equal(m.forcing(t[::-1], reversed_x[:, :m.nq], reversed_x[:, m.nq:], u[::-1]), contiguous[::-1])
    as_lists = m.forcing(t.tolist(), x[:, :m.nq].tolist(), x[:, m.nq:].tolist(), u.tolist())
    assert np.array_equal(as_lists, contiguous)
    as_float32 = m.forcing(t, x[:, :m.nq].astype(np.float32), x[:, m.nq:], u)
    assert np.array_equal(as_float32, m.forcing(t, x[:, :m.nq].astype(np.float32).astype(float), x[:, m.nq:], u))


def test_parameters_and_their_constants_give_the_same_values_and_a_change_takes_effect(module):
    m = module
    if m.np == 0:
        pytest.skip("no parameters")
    rng = np.random.default_rng(5)
    t, q, qd = 0.5, rng.uniform(-0.5, 0.5, m.nq), rng.uniform(-0.5, 0.5, m.nq)
    p = m.Parameters()
    before = m.kinetic_energy(t, q, qd, p) + m.potential_energy(t, q, p)
    assert before == m.kinetic_energy(t, q, qd, m.Constants(p)) + m.potential_energy(t, q, m.Constants(p))
    assert before == m.kinetic_energy(t, q, qd) + m.potential_energy(t, q)  # p=None: the defaults
    changed = False
    for name in p.to_dict():
        setattr(p, name, getattr(p, name) * 1.5 + 0.25)
        changed = changed or m.kinetic_energy(t, q, qd, p) + m.potential_energy(t, q, p) != before
    assert changed, "no parameter changes T + V: the Parameters' cached Constants went stale"


def test_linearization_of_a_batch_equals_the_loop_and_finite_differences(module):
    m = module
    rng = np.random.default_rng(13)
    q = rng.uniform(-0.3, 0.3, (3, m.nq))
    qd = rng.uniform(-0.3, 0.3, (3, m.nq))
    u = rng.uniform(-0.3, 0.3, (3, m.nu))
    try:
        A, B = m.linearization(0.0, q, qd, u)
    except ValueError as e:
        pytest.skip(f"not regular at random states: {e}")
    assert A.shape == (3, 2 * m.nq, 2 * m.nq) and B.shape == (3, 2 * m.nq, m.nu)
    for k in range(3):
        Ak, Bk = m.linearization(0.0, q[k], qd[k], u[k])
        assert np.array_equal(A[k], Ak) and np.array_equal(B[k], Bk)
    assert np.array_equal(A[0][:m.nq], np.hstack([np.zeros((m.nq, m.nq)), np.eye(m.nq)]))
    if "forward_dynamics" in m.functions and m.nc == 0:
        h = 1e-6
        for j in range(m.nq):  # dqdd/dq by central differences of the generated forward dynamics
            dq = np.zeros(m.nq)
            dq[j] = h
            column = (m.forward_dynamics(0.0, q[0] + dq, qd[0], u[0]) -
                      m.forward_dynamics(0.0, q[0] - dq, qd[0], u[0])) / (2 * h)
            np.testing.assert_allclose(A[0][m.nq:, j], column, rtol=1e-5, atol=1e-6)


def test_forward_dynamics_derivatives_are_the_bottom_rows_of_the_linearization(module):
    m = module
    if m.nc > 0:
        assert "forward_dynamics_derivatives" not in m.functions  # composed in the header, not bound
        return
    assert "forward_dynamics_derivatives" in m.functions
    rng = np.random.default_rng(19)
    q = rng.uniform(-0.3, 0.3, (3, m.nq))
    qd = rng.uniform(-0.3, 0.3, (3, m.nq))
    u = rng.uniform(-0.3, 0.3, (3, m.nu))
    try:
        by_q, by_qd, by_u = m.forward_dynamics_derivatives(0.0, q, qd, u)
        A, B = m.linearization(0.0, q, qd, u)
    except ValueError as e:
        pytest.skip(f"not regular at random states: {e}")
    assert by_q.shape == (3, m.nq, m.nq) and by_qd.shape == (3, m.nq, m.nq) and by_u.shape == (3, m.nq, m.nu)
    for k in range(3):
        np.testing.assert_array_equal(by_q[k], A[k][m.nq:, :m.nq])
        np.testing.assert_array_equal(by_qd[k], A[k][m.nq:, m.nq:])
        np.testing.assert_array_equal(by_u[k], B[k][m.nq:])


def test_assemble_returns_a_state_on_the_constraints(module):
    m = module
    rng = np.random.default_rng(17)
    x = rng.uniform(-0.2, 0.2, 2 * m.nq)
    if m.nc == 0:
        assert np.array_equal(m.assemble(x), x)
        return
    try:
        y = m.assemble(x)
    except ValueError as e:
        pytest.skip(f"no assembly near a random state: {e}")
    q, qd = y[:m.nq], y[m.nq:]
    Xi = m.constraint_jacobian(0.0, q)
    assert np.allclose(Xi @ qd + m.constraint_rate_term(0.0, q), 0, atol=1e-9)
    assert np.allclose(m.holonomic_residuals(0.0, q), 0, atol=1e-9)
