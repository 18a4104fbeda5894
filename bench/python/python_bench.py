#!/usr/bin/python3
"""The benchmark of issue 32: a generated model's Python module against C++ and against SymPy.

Run from the repository root with Debian's Python (the one with NumPy and SymPy):

    /usr/bin/python3 bench/python/python_bench.py --eomgen build/generator/eomgen \
        [--quick] [--out FILE.md] [--cache-dir DIR] [--work-dir DIR]

It builds the modules it needs with `eomgen python` (cached in --cache-dir), writes each model's
header with `eomgen python --source-only`, compiles cpp_timing.cpp (beside this file) on that
header, and measures in one run, each timing repeated in interleaved rounds (median and minimum
over the rounds; the machine is shared):

  1. overhead per call: m.forward_dynamics(t, q, qd, u, c) and m.mass_matrix_and_forcing(...)
     for one state from Python against the same function called from C++ on the same header
     (overhead = Python ns/call - C++ ns/call; target: at most 1 us), for cart_pole and ur5;
  2. the batch call, m.forward_dynamics(t_array, Q, QD, U, c) of N = 10,000 states, per state
     against a C++ loop over the same states (target: within 1.5x);
  3. against SymPy (sympy.physics.mechanics, KanesMethod): M and F of cart_pole and the double
     pendulum lambdified (NumPy backend), one state per call, against the module's
     mass_matrix_and_forcing; and PyDy's right-hand side with its lambdify backend (what
     pydy.codegen's LambdifyODEFunctionGenerator builds: M, F and qdot from one lambdified
     function of DeferredVectors, numpy.linalg.solve) against the module's forward_dynamics
     (target: at least 100x faster). SymPy's M and F are checked equal to the module's at a
     random state first (1e-12 relative), so both sides compute the same function.

A fourth part takes cart_pole's one-state call apart (floor_module.cpp beside this file):
pybind11's dispatch alone, with a result array, and eompy's whole call path around a function
that does nothing. The C++ program runs beside the script and times one round of its own
between two of the script's, so that C++, Python and floor rounds alternate and load on the
shared machine falls on all of them alike.

--quick is a smoke run of every part, in seconds once the modules are cached: cart_pole only,
1,000 states, 3 short rounds. Prints the markdown report on stdout and writes it to --out.
Exit status: 0 the report was made (whether or not the targets were met), 1 a failure (a
build, or a cross-check that shows two sides computing different functions), 2 usage.
"""

import argparse
import importlib
import json
import math
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import sysconfig
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.dont_write_bytecode = True

try:
    import numpy as np
    import sympy as sm
    import sympy.physics.mechanics as me
except ImportError as error:  # the first python3 on PATH may lack them
    sys.exit(f"python_bench: {error}; run it with Debian's /usr/bin/python3 (python3-numpy, python3-sympy)")

# the models: (model file, compare with SymPy, in --quick)
MODELS = [
    ("models/cart_pole.eom", True, True),
    ("models/robots/ur5.urdf", False, False),
    ("models/double_pendulum.eom", True, False),
]
OVERHEAD_TARGET_NS = 1000.0
BATCH_TARGET = 1.5
SYMPY_TARGET = 100.0
CHECK_TOLERANCE = 1e-12


class Failure(Exception):
    """A step that leaves the comparison meaningless: a build, or a failed cross-check."""


# ---------------------------------------------------------------------------------------------
# building: the modules, the headers, the C++ timing programs


def run(cmd, what, **kwargs):
    done = subprocess.run(cmd, capture_output=True, text=True, **kwargs)
    if done.returncode != 0:
        raise Failure(f"{what} failed (exit {done.returncode}):\n$ {' '.join(cmd)}\n{done.stdout}{done.stderr}")
    return done.stdout


def build_module(eomgen, model, modules_dir, cache_dir):
    """`eomgen python MODEL` into modules_dir; returns the module's name."""
    out = run([eomgen, "python", model, "-o", modules_dir, "--cache-dir", cache_dir], f"eomgen python {model}")
    found = re.search(r"^module: (.+)$", out, re.M)
    if not found:
        raise Failure(f"eomgen python {model}: no 'module:' line in its output:\n{out}")
    return os.path.basename(found.group(1)).split(".")[0]


def write_source(eomgen, model, source_dir):
    """`eomgen python --source-only`: model.hpp and module.cpp; returns the C++ namespace."""
    run([eomgen, "python", model, "-o", source_dir, "--source-only"], f"eomgen python --source-only {model}")
    with open(os.path.join(source_dir, "model.hpp")) as f:
        found = re.search(r"namespace eomgen_models \{\s*namespace (\w+) \{", f.read())
    if not found:
        raise Failure(f"{source_dir}/model.hpp: no namespace eomgen_models::NAME")
    return "eomgen_models::" + found.group(1)


CXX_FLAGS = ["-O2", "-DNDEBUG", "-std=c++17"]  # eomgen compiles the modules with -O2 -DNDEBUG


def compile_timing(source_dir, namespace, program):
    run(["g++", *CXX_FLAGS, "-I" + source_dir, "-I/usr/include/eigen3", "-DMODEL_NS=" + namespace,
         os.path.join(HERE, "cpp_timing.cpp"), "-o", program], "compiling cpp_timing.cpp")


def compile_floor(source_dir, namespace, out_dir):
    """floor_module.cpp on a model's header, as eomgen compiles a module; returns its directory.

    The model's namespace is renamed (-DNAME=NAME_bench_floor), so that its Parameters and
    Constants are other C++ types than the model module's: pybind11 registers a type once per
    process, and the floor is timed in the process that times the module."""
    inner = namespace.split("::")[-1]
    includes = [source_dir, os.path.join(ROOT, "python"), os.path.join(ROOT, "runtime", "include"),
                "/usr/include/eigen3", sysconfig.get_paths()["include"]]
    try:
        import pybind11
        includes.append(pybind11.get_include())
    except ImportError:
        pass  # Debian's python3-pybind11 puts the headers in /usr/include
    os.makedirs(out_dir, exist_ok=True)
    target = os.path.join(out_dir, "eomgen_bench_floor" + sysconfig.get_config_var("EXT_SUFFIX"))
    run(["c++", *CXX_FLAGS, "-shared", "-fPIC", "-fvisibility=hidden", *("-I" + d for d in includes),
         f"-D{inner}={inner}_bench_floor", f"-DMODEL_NS=eomgen_models::{inner}_bench_floor",
         os.path.join(HERE, "floor_module.cpp"), "-o", target],
        "compiling floor_module.cpp")
    return out_dir


# ---------------------------------------------------------------------------------------------
# timing


def timer(f, *args):
    """run(n) -> ns of n calls f(*args), the arguments as local names (no * call in the loop)."""
    names = ", ".join(f"a{i}" for i in range(len(args)))
    source = (f"def make(f, {names}):\n"
              f"    def run(n, clock=clock):\n"
              f"        it = range(n)\n"
              f"        start = clock()\n"
              f"        for _ in it:\n"
              f"            f({names})\n"
              f"        return clock() - start\n"
              f"    return run\n")
    scope = {"clock": time.perf_counter_ns}
    exec(source, scope)
    return scope["make"](f, *args)


def empty_loop():
    def run(n, clock=time.perf_counter_ns):
        it = range(n)
        start = clock()
        for _ in it:
            pass
        return clock() - start
    return run


def summary(values):
    return {"median": statistics.median(values), "min": min(values)}


def time_interleaved(ops, rounds, seconds, per=None, other=None):
    """ns per call (per unit: per[key] states a call) of each op, median and min over the rounds.

    ops: {key: run(n)}. Each op is calibrated to about `seconds` a round, then every round runs
    every op once, in turn, so that load on a shared machine falls on each alike. other(), when
    given, runs a round elsewhere (the C++ program) between two rounds here; its {key: ns} are
    summarized too, under its own keys."""
    per = per or {}
    counts = {}
    for key, op in ops.items():
        n = 1
        while True:
            took = op(n)
            if took > seconds * 1e9 / 4 or n > 1 << 26:
                took = min(took, op(n))  # once more: the first may have paid for warming up
                counts[key] = max(1, int(n * seconds * 1e9 / max(took, 1)))
                break
            n *= 2
    ns = {key: [] for key in ops}
    elsewhere = {}
    for _ in range(rounds):
        for key, op in ops.items():
            ns[key].append(op(counts[key]) / (counts[key] * per.get(key, 1)))
        if other is not None:
            for key, value in other().items():
                elsewhere.setdefault(key, []).append(value)
    return ({key: summary(v) for key, v in ns.items()}, {key: summary(v) for key, v in elsewhere.items()})


def relative_error(a, b):
    """max |a - b| / max |b| (max |a - b| where b is zero)."""
    a, b = np.asarray(a, dtype=float).ravel(), np.asarray(b, dtype=float).ravel()
    if a.shape != b.shape:
        return math.inf
    scale = np.max(np.abs(b)) if b.size else 0.0
    diff = np.max(np.abs(a - b)) if b.size else 0.0
    return diff / scale if scale > 0 else diff


# ---------------------------------------------------------------------------------------------
# the same systems in sympy.physics.mechanics (KanesMethod, speeds u_i = qdot_i, so that its
# mass_matrix and forcing are eomgen's M and F of M qdd = F)


def sympy_cart_pole():
    """models/cart_pole.eom: the cart a particle at the hinge, the pole a uniform rod (solid
    cylinder inertia) from the hinge along +b.2, b = rotate(a, 3, theta), gravity -g a.2, the
    force u a.1 at the hinge."""
    x, theta = me.dynamicsymbols("x theta")
    ux, utheta = me.dynamicsymbols("u_x u_theta")
    force = me.dynamicsymbols("u")
    mc, mp, l, rp, g = sm.symbols("mc mp l rp g")
    a = me.ReferenceFrame("a")
    b = a.orientnew("b", "Axis", [theta, a.z])
    b.set_ang_vel(a, utheta * a.z)
    w = me.Point("w")
    w.set_vel(a, 0)
    hinge = w.locatenew("hinge", x * a.x)
    hinge.set_vel(a, ux * a.x)
    centre = hinge.locatenew("pole_centre", l / 2 * b.y)
    centre.v2pt_theory(hinge, a, b)
    inertia = me.inertia(b, mp * (l**2 / 12 + rp**2 / 4), mp * rp**2 / 2, mp * (l**2 / 12 + rp**2 / 4))
    bodies = [me.Particle("cart", hinge, mc), me.RigidBody("pole", centre, b, mp, (inertia, centre))]
    loads = [(hinge, -mc * g * a.y + force * a.x), (centre, -mp * g * a.y)]
    kane = me.KanesMethod(a, q_ind=[x, theta], u_ind=[ux, utheta],
                          kd_eqs=[x.diff() - ux, theta.diff() - utheta])
    kane.kanes_equations(bodies, loads)
    return kane, [x, theta], [ux, utheta], [force], [mc, mp, l, rp, g]


def sympy_double_pendulum():
    """models/double_pendulum.eom: bobs m1 at -l1 b.2 and m2 at -l2 c.2 from it, b = rotate(a,
    3, theta1), c = rotate(b, 3, theta2), gravity -g a.2, no inputs."""
    theta1, theta2 = me.dynamicsymbols("theta1 theta2")
    u1, u2 = me.dynamicsymbols("u1 u2")
    m1, m2, l1, l2, g = sm.symbols("m1 m2 l1 l2 g")
    a = me.ReferenceFrame("a")
    b = a.orientnew("b", "Axis", [theta1, a.z])
    c = b.orientnew("c", "Axis", [theta2, b.z])
    b.set_ang_vel(a, u1 * a.z)
    c.set_ang_vel(b, u2 * b.z)
    w = me.Point("w")
    w.set_vel(a, 0)
    p1 = w.locatenew("p1", -l1 * b.y)
    p1.v2pt_theory(w, a, b)
    p2 = p1.locatenew("p2", -l2 * c.y)
    p2.v2pt_theory(p1, a, c)
    bodies = [me.Particle("bob1", p1, m1), me.Particle("bob2", p2, m2)]
    loads = [(p1, -m1 * g * a.y), (p2, -m2 * g * a.y)]
    kane = me.KanesMethod(a, q_ind=[theta1, theta2], u_ind=[u1, u2],
                          kd_eqs=[theta1.diff() - u1, theta2.diff() - u2])
    kane.kanes_equations(bodies, loads)
    return kane, [theta1, theta2], [u1, u2], [], [m1, m2, l1, l2, g]


SYMPY_MODELS = {"cart_pole": sympy_cart_pole, "double_pendulum": sympy_double_pendulum}


class SympyModel:
    """SymPy's M and F of a model, lambdified two ways."""

    def __init__(self, name):
        start = time.perf_counter()
        kane, q, u, r, p = SYMPY_MODELS[name]()
        self.derive_s = time.perf_counter() - start
        self.nq, self.nr = len(q), len(r)
        self.parameter_names = [str(s) for s in p]
        M, F = kane.mass_matrix, kane.forcing
        qdot = sm.Matrix([kane.kindiffdict()[qi.diff()] for qi in q])

        # plain sympy.lambdify of M and F (NumPy backend), the dynamic symbols as plain ones
        qs, us, rs = sm.symbols(f"q0:{len(q)}"), sm.symbols(f"qd0:{len(u)}"), sm.symbols(f"r0:{len(r)}")
        plain = dict(zip(q, qs)) | dict(zip(u, us)) | dict(zip(r, rs))
        args = [list(qs), list(us)] + ([list(rs)] if r else []) + [list(p)]
        start = time.perf_counter()
        self.mass_matrix_and_forcing = sm.lambdify(args, [me.msubs(M, plain), me.msubs(F, plain)], "numpy")
        self.lambdify_s = time.perf_counter() - start

        # PyDy's LambdifyODEFunctionGenerator (pydy/codegen/ode_function_generators.py): one
        # function of DeferredVectors q, u, [r,] p returning M, F and qdot, modules
        # [{'ImmutableMatrix': np.array}, 'numpy'], each output squeezed; its rhs(x, t, [r,] p)
        # with constants and specifieds given as arrays (its fastest argument handling) slices
        # x, solves M udot = F with numpy.linalg.solve and fills a preallocated xdot
        subs, vectors = {}, []
        for symbols_, vector_name in zip([q, u] + ([r] if r else []) + [p], ["q", "u"] + (["r"] if r else []) + ["p"]):
            vector = sm.DeferredVector(vector_name)
            for i, s in enumerate(symbols_):
                subs[s] = vector[i]
            vectors.append(vector)
        outputs = [me.msubs(o, subs) for o in (M, F, qdot)]
        f = sm.lambdify(vectors, outputs, modules=[{"ImmutableMatrix": np.array}, "numpy"])
        n, squeeze, solve = self.nq, np.squeeze, np.linalg.solve
        xdot = np.empty(2 * n)

        def eval_arrays(*a):
            return tuple([squeeze(o) for o in f(*a)])

        if r:
            def rhs(x, t, r, p):
                M, F, qd = eval_arrays(x[:n], x[n:], r, p)
                xdot[:n] = qd
                xdot[n:] = solve(M, F)
                return xdot
        else:
            def rhs(x, t, p):
                M, F, qd = eval_arrays(x[:n], x[n:], p)
                xdot[:n] = qd
                xdot[n:] = solve(M, F)
                return xdot
        self.pydy_rhs = rhs


def peer_availability():
    found = {}
    for name in ("pydy", "Cython"):
        try:
            __import__(name)
            found[name] = True
        except ImportError:
            found[name] = False
    return found


# ---------------------------------------------------------------------------------------------
# one model


def random_states(m, n, rng):
    """t, Q, QD, U of n states (U None when the model has no inputs), C-contiguous float64."""
    t = rng.uniform(0.0, 1.0, n)
    Q = rng.uniform(-math.pi, math.pi, (n, m.nq))
    QD = rng.uniform(-2.0, 2.0, (n, m.nq))
    U = rng.uniform(-1.0, 1.0, (n, m.nu)) if m.nu > 0 else None
    return t, Q, QD, U


class CppTiming:
    """cpp_timing.cpp running beside the script: its cross-check values, then a round a call."""

    def __init__(self, program, states_file, n_states, seconds):
        self.process = subprocess.Popen([program, states_file, str(n_states), str(seconds)], stdin=subprocess.PIPE,
                                        stdout=subprocess.PIPE, text=True)
        self.first = self._line()

    def _line(self):
        line = self.process.stdout.readline()
        if not line:
            self.process.wait()
            raise Failure(f"{self.process.args[0]} ended (exit {self.process.returncode}) without its timings")
        return json.loads(line)

    def round(self):
        self.process.stdin.write("round\n")
        self.process.stdin.flush()
        return self._line()

    def close(self):
        try:
            self.process.stdin.close()  # its end of input: it exits
        except OSError:
            pass  # it has ended already
        self.process.wait()


def add_sympy(name, m, c, state, rng, ops, checks):
    """SymPy's M and F of the model and PyDy's rhs: checked against the module at a random state,
    then their timed calls at `state` (t, q, qd, u) added to ops; returns the SympyModel."""
    sym = SympyModel(name)
    if sorted(sym.parameter_names) != sorted(m.parameter_names):
        raise Failure(f"{name}: SymPy's parameters {sym.parameter_names} are not the module's {m.parameter_names}")
    p = np.array([m.parameter_defaults[s] for s in sym.parameter_names])

    def inputs(u):
        return [u] if sym.nr else []

    tc, Qc, QDc, Uc = random_states(m, 1, rng)
    tc, qc, qdc, uc = float(tc[0]), Qc[0], QDc[0], (Uc[0] if Uc is not None else None)
    Ms, Fs = sym.mass_matrix_and_forcing(qc, qdc, *inputs(uc), p)
    Mm, Fm = m.mass_matrix_and_forcing(tc, qc, qdc, uc, c)
    qdd_pydy = sym.pydy_rhs(np.concatenate([qc, qdc]), tc, *inputs(uc), p)[sym.nq:]
    found = {("M, SymPy vs module (random state)", CHECK_TOLERANCE): relative_error(Ms, Mm),
             ("F, SymPy vs module (random state)", CHECK_TOLERANCE): relative_error(Fs, Fm),
             # two solvers (LAPACK's LU, the module's LDL^T) round differently
             ("qdd, PyDy-style rhs vs module forward_dynamics", 1e-10):
                 relative_error(qdd_pydy, m.forward_dynamics(tc, qc, qdc, uc, c))}
    for (key, tolerance), value in found.items():
        checks[key] = value
        if not value <= tolerance:
            raise Failure(f"{name}: {key}: relative difference {value:.3g} (> {tolerance:g}); "
                          "SymPy's system is not the model's")

    t0, q0, qd0, u0 = state
    ops["sympy_mf"] = timer(sym.mass_matrix_and_forcing, q0, qd0, *inputs(u0), p)
    ops["pydy_rhs"] = timer(sym.pydy_rhs, np.concatenate([q0, qd0]), t0, *inputs(u0), p)
    return sym


def measure_model(name, m, program, work, args, rng, floor=None):
    """Every timing of one model: the module's, SymPy's, the floors (floor: the floor module, or
    None) and C++'s, in alternating rounds."""
    n_states = args.states
    t, Q, QD, U = random_states(m, n_states, rng)
    states_file = os.path.join(work, f"{name}_states.bin")
    U_file = U if U is not None else np.zeros((n_states, 0))
    np.concatenate([t, Q.ravel(), QD.ravel(), U_file.ravel()]).astype("<f8").tofile(states_file)
    c = m.Constants(m.Parameters())
    state = (float(t[0]), Q[0].copy(), QD[0].copy(), U[0].copy() if U is not None else None)

    cpp_timing = CppTiming(program, states_file, n_states, args.seconds)
    try:
        cpp = cpp_timing.first
        # the module and the C++ program compute the same at state 0 and over the batch
        checks = {}
        M0, F0 = m.mass_matrix_and_forcing(*state, c)
        checks["qdd one, module vs C++"] = relative_error(m.forward_dynamics(*state, c), cpp["qdd"])
        checks["M one, module vs C++"] = relative_error(M0, cpp["M"])
        checks["F one, module vs C++"] = relative_error(F0, cpp["F"])
        checks["qdd batch (last state), module vs C++"] = relative_error(m.forward_dynamics(t, Q, QD, U, c)[-1],
                                                                         cpp["batch_qdd_last"])
        for key, value in checks.items():
            if not value <= CHECK_TOLERANCE:
                raise Failure(f"{name}: {key}: relative difference {value:.3g}")

        ops = {
            "fd_one": timer(m.forward_dynamics, *state, c),
            "mf_one": timer(m.mass_matrix_and_forcing, *state, c),
            "fd_batch": timer(m.forward_dynamics, t, Q, QD, U, c),
            "mf_batch": timer(m.mass_matrix_and_forcing, t, Q, QD, U, c),
            "loop": empty_loop(),
        }
        sym = add_sympy(name, m, c, state, rng, ops, checks) if name in SYMPY_MODELS else None
        if floor is not None:
            fc = floor.Constants(floor.Parameters())
            ops["bare"] = timer(floor.bare, *state, fc)
            ops["bare_result"] = timer(floor.bare_result, *state, fc)
            ops["eompy_noop"] = timer(floor.eompy_noop, *state, fc)
        py, cpp_ns = time_interleaved(ops, args.rounds, args.seconds, {"fd_batch": n_states, "mf_batch": n_states},
                                      cpp_timing.round)
    finally:
        cpp_timing.close()
    cpp.update(cpp_ns)
    return {"cpp": cpp, "py": py, "checks": checks, "sympy": sym, "nq": m.nq, "nu": m.nu}


# ---------------------------------------------------------------------------------------------
# the report


def ns(x):
    return f"{x:,.0f}" if x >= 100 else f"{x:.1f}"


def pair(d):
    return f"{ns(d['median'])} / {ns(d['min'])}"


def verdict(ok_median, ok_min):
    text = "yes" if ok_median else "no"
    if ok_median != ok_min:
        text += f" (minima: {'yes' if ok_min else 'no'})"
    return text


def table(results, args):
    rows = []
    for name, r in results.items():
        py, cpp = r["py"], r["cpp"]
        for key, what in (("fd", "forward_dynamics"), ("mf", "mass_matrix_and_forcing")):
            ours, peer = py[f"{key}_one"], cpp[f"{key}_one"]
            over = {s: ours[s] - peer[s] for s in ("median", "min")}
            rows.append([f"{name} {what}, one state: ns/call from Python vs C++", pair(ours), pair(peer),
                         f"+{ns(over['median'])} / +{ns(over['min'])} ns", f"overhead <= {OVERHEAD_TARGET_NS:,.0f} ns",
                         verdict(over["median"] <= OVERHEAD_TARGET_NS, over["min"] <= OVERHEAD_TARGET_NS)])
        for key, what in (("fd", "forward_dynamics"), ("mf", "mass_matrix_and_forcing")):
            ours, peer = py[f"{key}_batch"], cpp[f"{key}_batch"]
            ratio = {s: ours[s] / peer[s] for s in ("median", "min")}
            rows.append([f"{name} {what}, batch of {args.states:,}: ns/state from Python vs C++ loop", pair(ours),
                         pair(peer), f"{ratio['median']:.2f}x / {ratio['min']:.2f}x", f"<= {BATCH_TARGET}x",
                         verdict(ratio["median"] <= BATCH_TARGET, ratio["min"] <= BATCH_TARGET)])
        if "sympy_mf" in py:
            for ours_key, peer_key, what in (
                    ("mf_one", "sympy_mf", "M and F, one state per call: module vs sympy.lambdify"),
                    ("fd_one", "pydy_rhs",
                     "qdd: module forward_dynamics vs PyDy-style rhs (lambdify + numpy.linalg.solve)")):
                ours, peer = py[ours_key], py[peer_key]
                ratio = {s: peer[s] / ours[s] for s in ("median", "min")}
                rows.append([f"{name} {what}", pair(ours), pair(peer),
                             f"{ratio['median']:.1f}x / {ratio['min']:.1f}x faster", f">= {SYMPY_TARGET:.0f}x faster",
                             verdict(ratio["median"] >= SYMPY_TARGET, ratio["min"] >= SYMPY_TARGET)])
    head = ["measure", "ours (ns, median / min)", "peer or C++ (ns, median / min)", "ratio (median / min)", "target",
            "met?"]
    lines = ["| " + " | ".join(head) + " |", "|" + "|".join(["---"] * len(head)) + "|"]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return lines


def report(results, args, loads, peers, versions):
    out = ["# Python modules of generated models: the benchmark of issue 32", ""]
    out.append(f"- machine: {versions['cpu']}, {os.cpu_count()} cores; load average (1, 5, 15 min) "
               f"{loads[0][0]:.2f} {loads[0][1]:.2f} {loads[0][2]:.2f} at the start, "
               f"{loads[1][0]:.2f} {loads[1][1]:.2f} {loads[1][2]:.2f} at the end")
    out.append(f"- Python {platform.python_version()} ({sys.executable}), NumPy {np.__version__}, "
               f"SymPy {sm.__version__}; {versions['gxx']}; {versions['eomgen']}")
    out.append(f"- each timing: {args.rounds} interleaved rounds of about {args.seconds * 1e3:.0f} ms; "
               f"median / minimum over the rounds, in ns per call (per state for a batch)"
               + ("; **--quick: a smoke run, not a measurement**" if args.quick else ""))
    out.append(f"- C++: cpp_timing.cpp on the header `eomgen python --source-only` writes, "
               f"g++ {' '.join(CXX_FLAGS)} (the module's flags), Constants built once; one-state calls "
               f"through a noinline wrapper, the batch loop inlined")
    installed = {name: "is" if found else "is not" for name, found in peers.items()}
    out.append(f"- PyDy {installed['pydy']} installed and Cython {installed['Cython']}: "
               f"the PyDy row reproduces what pydy.codegen's LambdifyODEFunctionGenerator generates "
               f"(M, F, qdot from one lambdified function of DeferredVectors, squeezed, numpy.linalg.solve, "
               f"xdot filled), called as rhs(x, t, r, p) with array arguments; the module returns qdd alone")
    out.append("")
    out += table(results, args)
    out.append("")

    out.append("## Cross-checks (max |difference| / max |reference|)")
    out.append("")
    for name, r in results.items():
        for key, value in r["checks"].items():
            out.append(f"- {name}: {key}: {value:.2g}")
    out.append("")

    syms = {name: r["sympy"] for name, r in results.items() if r["sympy"] is not None}
    if syms:
        out.append("## SymPy")
        out.append("")
        for name, s in syms.items():
            py = results[name]["py"]
            out.append(f"- {name}: KanesMethod derivation {s.derive_s:.2f} s, lambdify of M and F "
                       f"{s.lambdify_s * 1e3:.0f} ms (SymPy's default printer, no cse)")
            mf = py["sympy_mf"]["median"] / py["mf_batch"]["median"]
            fd = py["pydy_rhs"]["median"] / py["fd_batch"]["median"]
            out.append(f"- {name}, for reference only (not the same use): the module's batch call per state against "
                       f"SymPy's one state per call: M and F {mf:,.0f}x, qdd {fd:,.0f}x faster (medians)")
        out.append("")

    floors = [name for name, r in results.items() if "eompy_noop" in r["py"]]
    if floors:
        first = floors[0]
        r = results[first]
        floor = r["py"]
        fd, cpp_fd = r["py"]["fd_one"], r["cpp"]["fd_one"]
        out.append(f"## Where a one-state call goes ({first}, forward_dynamics)")
        out.append("")
        out.append("Each row adds one thing to the one above (floor_module.cpp, its rounds alternating with the "
                   "module's; medians, then minima, in ns per call):")
        out.append("")
        out.append("| step | ns/call (median / min) | added by this step (median / min) |")
        out.append("|---|---|---|")
        steps = [("Python loop, empty", floor["loop"]),
                 ("pybind11 function of the five arguments (py::handle), returns None", floor["bare"]),
                 ("... and returns a new (nq,) float64 array", floor["bare_result"]),
                 ("eompy's call path (functions.hpp) around a function that does nothing", floor["eompy_noop"]),
                 ("the module's forward_dynamics", fd)]
        previous = None
        for label, d in steps:
            added = "" if previous is None else \
                f"{d['median'] - previous['median']:+,.0f} / {d['min'] - previous['min']:+,.0f}"
            out.append(f"| {label} | {pair(d)} | {added} |")
            previous = d
        out.append(f"| (forward_dynamics in C++, for reference) | {pair(cpp_fd)} | |")
        out.append("")
    return "\n".join(out)


def versions_of(eomgen):
    def first_line(cmd):
        try:
            return subprocess.run(cmd, capture_output=True, text=True).stdout.splitlines()[0]
        except (OSError, IndexError):
            return "?"
    cpu = "?"
    try:
        with open("/proc/cpuinfo") as f:
            found = re.search(r"^model name\s*:\s*(.+)$", f.read(), re.M)
            cpu = found.group(1) if found else "?"
    except OSError:
        pass
    return {"cpu": cpu, "gxx": first_line(["g++", "--version"]), "eomgen": first_line([eomgen, "--version"])}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--eomgen", default=os.path.join(ROOT, "build", "generator", "eomgen"),
                        help="the eomgen binary (default: build/generator/eomgen)")
    parser.add_argument("--quick", action="store_true", help="a smoke run of every part (seconds once cached)")
    parser.add_argument("--out", help="also write the report to this file")
    parser.add_argument("--cache-dir", help="eomgen's cache of compiled modules (default: one in the work directory)")
    parser.add_argument("--work-dir", help="keep the modules, headers and programs here (default: a temporary one)")
    args = parser.parse_args()
    args.rounds = 3 if args.quick else 15
    args.seconds = 0.002 if args.quick else 0.02
    args.states = 1000 if args.quick else 10000

    eomgen = os.path.abspath(args.eomgen)
    if not os.access(eomgen, os.X_OK):
        parser.error(f"--eomgen: {args.eomgen} is not an executable (build it, or pass its path)")
    work = os.path.abspath(args.work_dir) if args.work_dir else tempfile.mkdtemp(prefix="python_bench.")
    os.makedirs(work, exist_ok=True)
    cache = os.path.abspath(args.cache_dir) if args.cache_dir else os.path.join(work, "cache")
    modules_dir = os.path.join(work, "modules")
    os.makedirs(modules_dir, exist_ok=True)
    sys.path.insert(0, modules_dir)

    loads = [os.getloadavg()]
    peers = peer_availability()
    versions = versions_of(eomgen)
    rng = np.random.default_rng(32)
    results, floor = {}, None
    try:
        for model, _, in_quick in MODELS:
            if args.quick and not in_quick:
                continue
            path = os.path.join(ROOT, model)
            print(f"python_bench: {model}: building ...", file=sys.stderr, flush=True)
            module_name = build_module(eomgen, path, modules_dir, cache)
            source_dir = os.path.join(work, "src", module_name)
            namespace = write_source(eomgen, path, source_dir)
            program = os.path.join(work, f"cpp_timing_{module_name}")
            compile_timing(source_dir, namespace, program)
            with_floor = not results  # the first model's call is taken apart
            if with_floor:
                sys.path.insert(0, compile_floor(source_dir, namespace, os.path.join(work, "floor")))
                floor = importlib.import_module("eomgen_bench_floor")
            m = importlib.import_module(module_name)
            print(f"python_bench: {model}: timing ...", file=sys.stderr, flush=True)
            results[m.name] = measure_model(m.name, m, program, work, args, rng, floor if with_floor else None)
    except Failure as error:
        print(f"python_bench: {error}", file=sys.stderr)
        return 1
    finally:
        if not args.work_dir:
            shutil.rmtree(work, ignore_errors=True)
    loads.append(os.getloadavg())

    text = report(results, args, loads, peers, versions)
    print(text)
    if args.out:
        with open(args.out, "w") as f:
            f.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
