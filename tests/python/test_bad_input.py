"""Bad input to a module raises TypeError or ValueError (UnknownNameError is both a ValueError
and an AttributeError) with a message naming the function, the argument and what it expected;
nothing crashes."""
import math
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import cart_pole as m


def test_a_wrong_shape_is_a_value_error_that_says_the_expected_shapes():
    with pytest.raises(ValueError, match=r"mass_matrix\(\): q: expected shape \(2,\), or \(N, 2\) for N states, got \(3,\)"):
        m.mass_matrix(0.0, [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"forcing\(\): qd: expected shape \(2,\), or \(N, 2\) .* got \(2, 2, 1\)"):
        m.forcing(0.0, [0.0, 0.0], np.zeros((2, 2, 1)))
    with pytest.raises(ValueError, match=r"t: expected a number, or an array of shape \(N,\)"):
        m.mass_matrix(np.zeros((2, 2)), [0.0, 0.0])


def test_batches_of_different_sizes_are_a_value_error():
    with pytest.raises(ValueError, match=r"forcing\(\): q holds 3 states but qd holds 4"):
        m.forcing(0.0, np.zeros((3, 2)), np.zeros((4, 2)))


@pytest.mark.parametrize("value, dtype", [
    (np.array([1 + 2j, 0]), "complex128"),
    (["a", "b"], "<U1"),
    (np.array([True, False]), "bool"),
    ([object(), object()], "object"),
])
def test_arrays_that_are_not_real_numbers_are_a_type_error(value, dtype):
    with pytest.raises(TypeError, match=r"mass_matrix\(\): q: expected real numbers .* got " + dtype):
        m.mass_matrix(0.0, value)


def test_other_real_dtypes_are_converted():
    q = np.array([0, 1], dtype=np.int32)
    assert np.array_equal(m.mass_matrix(0, q), m.mass_matrix(0.0, q.astype(float)))


def test_a_missing_argument_and_a_wrong_parameter_set_are_type_errors():
    with pytest.raises(TypeError, match=r"mass_matrix\(\): q is required, got None"):
        m.mass_matrix(0.0)
    with pytest.raises(TypeError, match=r"p: expected cart_pole.Parameters or cart_pole.Constants .* got .* dict"):
        m.mass_matrix(0.0, [0.0, 0.0], {"l": 2.0})
    with pytest.raises(TypeError):
        m.mass_matrix(0.0, [0.0, 0.0], None, 1)  # one argument too many


def test_an_unknown_parameter_name_is_a_value_error_listing_the_models_parameters():
    with pytest.raises(ValueError, match="cart_pole has no parameter 'lenght'; its parameters: mc, mp, l, rp, g"):
        m.Parameters(lenght=2.0)
    p = m.Parameters()
    with pytest.raises(ValueError, match="no parameter 'lenght'"):
        p.lenght = 2.0
    with pytest.raises(AttributeError):
        p.lenght  # noqa: B018
    assert not hasattr(p, "lenght")
    assert issubclass(m.UnknownNameError, ValueError) and issubclass(m.UnknownNameError, AttributeError)


@pytest.mark.parametrize("value, error", [
    (math.nan, ValueError), (math.inf, ValueError), ("2", TypeError), (1j, TypeError), (None, TypeError),
    (True, TypeError),
])
def test_a_parameter_value_that_is_not_a_finite_real_number_is_refused(value, error):
    p = m.Parameters()
    with pytest.raises(error, match="parameter l: expected a"):
        p.l = value
    assert p.l == 1.0


def test_nan_where_the_runtime_refuses_it_is_a_value_error():
    with pytest.raises(ValueError, match=r"forward_dynamics\(\): M is not positive definite .* or the result is not finite"):
        m.forward_dynamics(0.0, [0.0, math.nan], [0.0, 0.0])
    with pytest.raises(ValueError, match=r"forward_dynamics\(\): at state 1: "):
        m.forward_dynamics(0.0, [[0.0, 0.0], [0.0, math.nan]], [0.0, 0.0])
    with pytest.raises(ValueError, match=r"linearization\(\): the terms of the equations are not finite"):
        m.linearization(0.0, [0.0, math.nan], [0.0, 0.0])
    with pytest.raises(ValueError, match=r"simulate\(\): x0: expected finite numbers"):
        m.simulate(1.0, [0.0, math.nan, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"simulate\(\): u: expected finite numbers"):
        m.simulate(1.0, [0.0, 0.1, 0.0, 0.0], u=[math.inf])


@pytest.mark.parametrize("options, message", [
    (dict(method="leapfrog"), r"method: expected one of euler, rk4, dp5, got 'leapfrog'"),
    (dict(method="dp5", dt=0.01), r"dt: dp5 chooses its own steps"),
    (dict(method="rk4"), r"rk4 takes fixed steps: give dt"),
    (dict(method="rk4", dt=0.01, rtol=1e-6), r"rtol/atol: rk4 takes fixed steps"),
    (dict(dt=-0.01), r"dt: expected a number above 0"),
    (dict(solver="null-space"), r"solver: the module runs the KKT system only"),
    (dict(stabilization="magic"), r"stabilization: expected 'projection', 'baumgarte' or 'none'"),
    (dict(t0=2.0), r"expected finite times with t_end >= t0"),
])
def test_simulation_options_are_checked_as_eomgen_simulate_checks_them(options, message):
    with pytest.raises(ValueError, match=message):
        m.simulate(1.0, [0.0, 0.1, 0.0, 0.0], **options)


def test_an_input_callable_that_raises_ends_the_simulation_with_its_exception():
    def u(t, x):
        if t > 0.1:
            raise RuntimeError("the controller failed")
        return [0.0]
    with pytest.raises(RuntimeError, match="the controller failed"):
        m.simulate(1.0, [0.0, 0.1, 0.0, 0.0], u=u)
    with pytest.raises(ValueError, match=r"simulate\(\): u\(t, x\): expected shape \(1,\)"):
        m.simulate(1.0, [0.0, 0.1, 0.0, 0.0], u=lambda t, x: [0.0, 1.0])


def test_a_simulation_that_blows_up_raises_with_the_samples_up_to_the_failure():
    import spring_mass_damper as s
    p = s.Parameters(k1=1e9)
    with pytest.raises(s.SimulationError) as failure:
        s.simulate(10.0, [1.0, 0.0], p, method="euler", dt=0.01)
    assert failure.value.status in ("non_finite_state", "singular_mass_matrix")  # NaN makes M fail first
    assert failure.value.t[0] == 0.0 and failure.value.x[0, 0] == 1.0
    assert len(failure.value.t) == len(failure.value.x) and failure.value.failure_time > 0


def test_unknown_names_given_to_assemble_are_refused():
    import four_bar as f
    with pytest.raises(ValueError, match=r"assemble\(\): given: four_bar has no coordinate or rate 'theta9'"):
        f.assemble(np.zeros(2 * f.nq), given=["theta9"])
    with pytest.raises(TypeError, match="expected a sequence of names, got a string"):
        f.assemble(np.zeros(2 * f.nq), given="theta1")


def test_garbage_in_every_argument_of_every_function_never_crashes():
    # in a child process, so that a crash fails this test instead of ending the run
    script = textwrap.dedent("""
        import itertools, math
        import numpy as np
        import cart_pole as m, four_bar as f
        garbage = [None, 1, -1.5, math.nan, "x", b"x", [], [[]], {}, object(), np.zeros(0), np.zeros((0, 2)),
                   np.zeros((3, 2, 2)), np.array([1 + 1j]), np.ones(10**6)[::500000], np.empty((2, 0)),
                   np.zeros((2, 2), dtype=np.float16), m.Parameters(), f.Parameters(), lambda: 0]
        calls = 0
        for mod in (m, f):
            for name, names in mod.functions.items():
                fn = getattr(mod, name)
                for position in range(len(names)):
                    for value in garbage:
                        args = [0.0 if a == "t" else None if a in ("u", "p") else np.zeros({"q": mod.nq, "qd": mod.nq,
                                "qdd": mod.nq, "lambda_": mod.nc}[a]) for a in names]
                        args[position] = value
                        try:
                            fn(*args)
                        except (TypeError, ValueError):
                            pass
                        calls += 1
            for value in garbage:
                for call in (lambda v: mod.simulate(0.01, v), lambda v: mod.simulate(v, np.zeros(mod.nx)),
                             lambda v: mod.assemble(v), lambda v: mod.linearization(0.0, v, v),
                             lambda v: mod.Parameters(**{mod.parameter_names[0]: v}), lambda v: mod.Constants(v)):
                    try:
                        call(value)
                    except (TypeError, ValueError):
                        pass
                    calls += 1
        print(calls)
    """)
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    assert int(run.stdout) > 1000
