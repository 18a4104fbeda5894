#!/usr/bin/env python3
"""SymPy peer benchmark for eomgen (standard library + SymPy only; not part of the build).

The same two chains as models/planar_chain.eom and models/universal_chain.eom, built with
sympy.physics.mechanics and derived with KanesMethod (kinematic equations u_i = qdot_i, so
the generalized speeds ARE the coordinate rates and M, F compare one to one with eomgen's
M(q) qdd = F) or with LagrangesMethod (L = T - V, V the gravitational potential).

Subcommands
  derive  one (chain, n, method) in this process. Prints JSON lines on stdout as phases finish:
            {"phase": "derived", "setup_s", "eqs_s", "derive_s", ...}   derivation of M and F
            {"phase": "eval", "M", "F", ...}      M, F at the check state (--no-eval skips it)
            {"phase": "emitted", "cse", "cse_s", "ops", ...}  one per cse variant tried
            {"phase": "done", ...}                everything above merged
          --emit-c OUT.hpp writes SymPy's cse() + ccode() of [upper triangle of M, F] as a C++
          header with eomgen's signature (namespace sympy_models::CHAIN_METHOD, struct Model,
          mass_matrix_and_forcing(t, q, qd, u, p, M, F)), the variant with the fewest operations
          (count_ops.py) among --cse none / basic (default: both, in that order).
  run     the same in a child process with a wall-clock cap per phase (--cap, default 120 s):
          prints ONE JSON line; "derive_s": null and "timeout": "derive" when the derivation
          hit the cap ("> cap"); a cse variant that hits the cap is skipped (the other one kept).
  bench   the whole comparison (eomgen generate timings, SymPy Kane/Lagrange derivations,
          cross-check, op counts, compiled timing programs), printing markdown tables; see
          bench --help.
  state   print the check state (JSON) for a chain and n.

Examples
  python3 bench/peers/sympy_chains.py derive --chain planar --n 4 --method kane --emit-c /tmp/k4.hpp
  python3 bench/peers/sympy_chains.py run --chain universal --n 2 --method lagrange --cap 60
  python3 bench/peers/sympy_chains.py bench --eomgen /tmp/sympy-bench/eomgen --cap 120

Exit status: 0 success, 1 failure (message on stderr), 2 usage error, 3 (run only) the
derivation hit the cap (the JSON line is still printed).
"""

import argparse
import json
import math
import os
import random
import select
import signal
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
sys.dont_write_bytecode = True
import count_ops  # noqa: E402

CHAINS = {
    # name: (model file, coordinates per body, parameter defaults in the order m, l, rd, g)
    "planar": ("planar_chain.eom", 1, {"m": 0.5, "l": 0.3, "rd": 0.01, "g": 9.81}),
    "universal": ("universal_chain.eom", 2, {"m": 1.0, "l": 0.4, "rd": 0.02, "g": 9.81}),
}
PARAM_ORDER = ("m", "l", "rd", "g")
CHECK_SEED = 20240607


class Failure(Exception):
    pass


def emit(obj):
    sys.stdout.write(json.dumps(obj) + "\n")
    sys.stdout.flush()


def coordinate_names(chain, n):
    if chain == "planar":
        return ["q%d" % i for i in range(1, n + 1)]
    names = []
    for i in range(1, n + 1):
        names += ["alpha%d" % i, "beta%d" % i]
    return names


def check_state(chain, n, seed=CHECK_SEED):
    """A random state, the same for every method: q in [-pi, pi], qd in [-2, 2]."""
    rng = random.Random("%s-%d-%d" % (chain, n, seed))
    names = coordinate_names(chain, n)
    q = [rng.uniform(-math.pi, math.pi) for _ in names]
    qd = [rng.uniform(-2.0, 2.0) for _ in names]
    return {"names": names, "q": q, "qd": qd}


# ----------------------------------------------------------------------------------------------
# The models in sympy.physics.mechanics


def build_system(chain, n, method):
    """Frames, points, bodies and loads. Returns a dict with q, u (None for Lagrange), bodies,
    loads, kd, inertial frame, params."""
    import sympy as sp
    from sympy.physics.mechanics import (Point, ReferenceFrame, RigidBody, dynamicsymbols,
                                         inertia)

    m, l, rd, g = sp.symbols("m l rd g", positive=True)
    names = coordinate_names(chain, n)
    q = dynamicsymbols(names)
    if not isinstance(q, list):
        q = [q]
    kane = method == "kane"
    if kane:
        u = dynamicsymbols(["u_" + s for s in names])
        if not isinstance(u, list):
            u = [u]
        rates = u
    else:
        u = None
        rates = [qi.diff(dynamicsymbols._t) for qi in q]

    A = ReferenceFrame("a")
    w = Point("w")
    w.set_vel(A, 0)
    bodies, loads, potential = [], [], 0
    prev_frame, prev_point = A, w
    Ilat = m * (l**2 / 12 + rd**2 / 4)  # about the two axes across the rod
    Iax = m * rd**2 / 2                 # about the rod's axis
    for i in range(1, n + 1):
        if chain == "planar":
            # C_{b_i, b_{i-1}} = C3(q_i): b_i is b_{i-1} turned by +q_i about b_{i-1}.3
            qi, ri = q[i - 1], rates[i - 1]
            B = ReferenceFrame("b%d" % i)
            B.orient_axis(prev_frame, prev_frame.z, qi)
            B.set_ang_vel(prev_frame, ri * prev_frame.z)
            down = -B.y
            I = inertia(B, Ilat, Iax, Ilat)
            up = A.y
        else:
            # C_{j_i, b_{i-1}} = C1(alpha_i), C_{b_i, j_i} = C2(beta_i)
            qa, qb = q[2 * i - 2], q[2 * i - 1]
            ra, rb = rates[2 * i - 2], rates[2 * i - 1]
            J = ReferenceFrame("j%d" % i)
            J.orient_axis(prev_frame, prev_frame.x, qa)
            J.set_ang_vel(prev_frame, ra * prev_frame.x)
            B = ReferenceFrame("b%d" % i)
            B.orient_axis(J, J.y, qb)
            B.set_ang_vel(J, rb * J.y)
            down = B.z * -1
            I = inertia(B, Ilat, Ilat, Iax)
            up = A.z
        c = prev_point.locatenew("c%d" % i, l / 2 * down)
        o = prev_point.locatenew("o%d" % i, l * down)
        c.v2pt_theory(prev_point, A, B)
        o.v2pt_theory(prev_point, A, B)
        body = RigidBody("rod%d" % i, c, B, m, (I, c))
        if kane:
            loads.append((c, -m * g * up))
        else:
            # V = m g (height of c_i above w)
            body.potential_energy = m * g * c.pos_from(w).dot(up)
        bodies.append(body)
        prev_frame, prev_point = B, o
    kd = [u[k] - q[k].diff(dynamicsymbols._t) for k in range(len(q))] if kane else None
    return {"q": q, "u": u, "kd": kd, "bodies": bodies, "loads": loads, "A": A,
            "params": {"m": m, "l": l, "rd": rd, "g": g}}


def derive(chain, n, method):
    """Times the derivation of M and F. Returns (M, F, sys, timings)."""
    from sympy.physics.mechanics import KanesMethod, LagrangesMethod, Lagrangian

    t0 = time.perf_counter()
    s = build_system(chain, n, method)
    t1 = time.perf_counter()
    if method == "kane":
        km = KanesMethod(s["A"], q_ind=s["q"], u_ind=s["u"], kd_eqs=s["kd"])
        km.kanes_equations(s["bodies"], s["loads"])
        M, F = km.mass_matrix, km.forcing
    else:
        L = Lagrangian(s["A"], *s["bodies"])
        lm = LagrangesMethod(L, s["q"], frame=s["A"])
        lm.form_lagranges_equations()
        M, F = lm.mass_matrix, lm.forcing
    t2 = time.perf_counter()
    return M, F, s, {"setup_s": t1 - t0, "eqs_s": t2 - t1, "derive_s": t2 - t0}


def plain_symbols(M, F, s):
    """M, F with q_k(t) -> q_k, u_k(t) and q_k'(t) -> qd_k (plain symbols, 0-based k), and the
    list of plain symbols [q..., qd..., m, l, rd, g]."""
    import sympy as sp
    from sympy.physics.mechanics import dynamicsymbols

    nq = len(s["q"])
    qs = sp.symbols(["q_%d" % k for k in range(nq)], real=True)
    qds = sp.symbols(["qd_%d" % k for k in range(nq)], real=True)
    sub = {}
    for k in range(nq):
        sub[s["q"][k].diff(dynamicsymbols._t)] = qds[k]
        if s["u"] is not None:
            sub[s["u"][k]] = qds[k]
    sub2 = {s["q"][k]: qs[k] for k in range(nq)}
    Mp = M.xreplace(sub).xreplace(sub2)
    Fp = F.xreplace(sub).xreplace(sub2)
    left = (Mp.free_symbols | Fp.free_symbols) - set(qs) - set(qds) - set(s["params"].values())
    if left or Mp.atoms(sp.Derivative) or Fp.atoms(sp.Derivative) \
            or Mp.atoms(sp.core.function.AppliedUndef) or Fp.atoms(sp.core.function.AppliedUndef):
        raise Failure("unexpected symbols left in M, F after substitution: %s" % left)
    return Mp, Fp, list(qs), list(qds)


def numeric(exprs, env):
    """Evaluates SymPy expressions in double precision, each distinct subexpression once
    (memoized on the expression DAG), with the math module."""
    import sympy as sp

    memo = {}
    funcs = {sp.sin: math.sin, sp.cos: math.cos, sp.tan: math.tan, sp.sqrt: math.sqrt,
             sp.exp: math.exp, sp.log: math.log}

    def ev(e):
        r = memo.get(e)
        if r is not None:
            return r
        if e.is_Symbol:
            r = env[e]
        elif e.is_Number:
            r = float(e)
        elif e.is_Add:
            r = math.fsum(ev(a) for a in e.args)
        elif e.is_Mul:
            r = 1.0
            for a in e.args:
                r *= ev(a)
        elif e.is_Pow:
            b, x = e.args
            if x.is_Integer:
                r = ev(b) ** int(x)
            else:
                r = ev(b) ** ev(x)
        elif e.func in funcs:
            r = funcs[e.func](ev(e.args[0]))
        else:
            raise Failure("numeric: unsupported %s" % e.func)
        memo[e] = r
        return r

    old = sys.getrecursionlimit()
    sys.setrecursionlimit(max(old, 200000))
    try:
        return [ev(e) for e in exprs]
    finally:
        sys.setrecursionlimit(old)


# ----------------------------------------------------------------------------------------------
# C++ emission


def emit_header(chain, n, method, Mp, Fp, qs, qds, params, optimizations, path):
    import sympy as sp

    nq = len(qs)
    upper = [(i, j) for i in range(nq) for j in range(i, nq)]
    exprs = [Mp[i, j] for (i, j) in upper] + [Fp[k] for k in range(nq)]
    t0 = time.perf_counter()
    repl, red = sp.cse(exprs, symbols=sp.numbered_symbols("x"), optimizations=optimizations)
    t1 = time.perf_counter()
    ns = "%s_%s" % (chain, method)
    lines = []
    add = lines.append
    add("// Generated by bench/peers/sympy_chains.py (peer benchmark, not part of the build).")
    add("// SymPy %s %s of %s_chain, n = %d; sympy.cse(optimizations=%r) of [upper triangle of M, F],"
        % (sp.__version__, "KanesMethod (u = qdot)" if method == "kane" else "LagrangesMethod",
           chain, n, optimizations))
    add("// every statement printed with sympy.ccode. M qdd = F, same signature as eomgen's.")
    add("#pragma once")
    add("#include <Eigen/Core>")
    add("#include <cmath>")
    add("namespace sympy_models {")
    add("namespace %s {" % ns)
    add("struct Model {")
    add("  static constexpr int nq = %d;" % nq)
    add("  static constexpr int nu = 0;")
    add("  template <class Scalar> using Vector = Eigen::Matrix<Scalar, nq, 1>;")
    add("  template <class Scalar> using Inputs = Eigen::Matrix<Scalar, nu, 1>;")
    add("  template <class Scalar> using MassMatrix = Eigen::Matrix<Scalar, nq, nq>;")
    add("  template <class Scalar>")
    add("  struct Parameters {")
    for name in PARAM_ORDER:
        add("    Scalar %s = Scalar(%r);" % (name, CHAINS[chain][2][name]))
    add("  };")
    add("  template <class Scalar>")
    add("  static void mass_matrix_and_forcing([[maybe_unused]] const Scalar& t, "
        "const Vector<Scalar>& q, const Vector<Scalar>& qd, [[maybe_unused]] const "
        "Inputs<Scalar>& u, const Parameters<Scalar>& p, MassMatrix<Scalar>& M, "
        "Vector<Scalar>& F) noexcept {")
    add("    using std::sin; using std::cos; using std::tan; using std::sqrt; using std::pow;")
    used = set()
    for e in exprs:
        used |= e.free_symbols
    for name in PARAM_ORDER:
        add("    [[maybe_unused]] const Scalar %s = p.%s;" % (name, name))
    for k in range(nq):
        add("    [[maybe_unused]] const Scalar %s = q(%d);" % (qs[k], k))
        add("    [[maybe_unused]] const Scalar %s = qd(%d);" % (qds[k], k))
    for sym, e in repl:
        add("    const Scalar %s = %s;" % (sym, sp.ccode(e)))
    for idx, (i, j) in enumerate(upper):
        add("    M(%d, %d) = %s;" % (i, j, sp.ccode(red[idx])))
    for k in range(nq):
        add("    F(%d) = %s;" % (k, sp.ccode(red[len(upper) + k])))
    for (i, j) in upper:
        if i != j:
            add("    M(%d, %d) = M(%d, %d);" % (j, i, i, j))
    add("  }")
    add("};")
    add("}  // namespace %s" % ns)
    add("}  // namespace sympy_models")
    text = "\n".join(lines) + "\n"
    tmp = path + ".tmp%d" % os.getpid()
    with open(tmp, "w") as f:
        f.write(text)
    ops = count_ops.count_file(tmp)
    t2 = time.perf_counter()
    return tmp, ops, {"cse_s": t1 - t0, "print_s": t2 - t1, "temporaries": len(repl)}


def cmd_derive(a):
    import sympy as sp

    M, F, s, tm = derive(a.chain, a.n, a.method)
    info = {"chain": a.chain, "n": a.n, "method": a.method, "nq": len(s["q"]),
            "sympy": sp.__version__}
    info.update(tm)
    emit(dict(info, phase="derived"))
    done = dict(info)
    Mp = Fp = None
    if not a.no_eval or a.emit_c:
        t0 = time.perf_counter()
        Mp, Fp, qs, qds = plain_symbols(M, F, s)
        done["to_plain_s"] = time.perf_counter() - t0
    if not a.no_eval:
        st = check_state(a.chain, a.n, a.seed)
        env = {}
        for k in range(len(qs)):
            env[qs[k]] = st["q"][k]
            env[qds[k]] = st["qd"][k]
        for name, sym in s["params"].items():
            env[sym] = CHAINS[a.chain][2][name]
        t0 = time.perf_counter()
        nq = len(qs)
        vals = numeric(list(Mp) + list(Fp), env)
        ev = {"M": [vals[i * nq:(i + 1) * nq] for i in range(nq)], "F": vals[nq * nq:],
              "state": st, "eval_s": time.perf_counter() - t0}
        emit(dict(ev, phase="eval"))
        done.update(ev)
    if a.emit_c:
        best = None
        variants = {"none": None, "basic": "basic"}
        for v in a.cse.split(","):
            if v not in variants:
                raise Failure("unknown --cse variant %r (none, basic)" % v)
            tmp, ops, tm2 = emit_header(a.chain, a.n, a.method, Mp, Fp, qs, qds, s["params"],
                                        variants[v], a.emit_c)
            rec = dict(tm2, cse=v, ops=ops)
            if best is None or ops["total"] < best["ops"]["total"]:
                os.replace(tmp, a.emit_c)
                best = rec
                rec["kept"] = True
            else:
                os.unlink(tmp)
                rec["kept"] = False
            emit(dict(rec, phase="emitted"))
            done.setdefault("cse_variants", []).append(rec)
        done["best_cse"] = best["cse"]
        done["ops"] = best["ops"]
        done["header"] = a.emit_c
    emit(dict(done, phase="done"))
    return 0


def cmd_run(a):
    """The derive subcommand in a child process, with a wall-clock cap per phase."""
    cmd = [sys.executable, os.path.abspath(__file__), "derive", "--chain", a.chain, "--n",
           str(a.n), "--method", a.method, "--seed", str(a.seed), "--cse", a.cse]
    if a.emit_c:
        cmd += ["--emit-c", a.emit_c]
    if a.no_eval:
        cmd += ["--no-eval"]
    res = run_capped(cmd, a.cap)
    emit(res)
    if res.get("ok"):
        return 0
    return 3 if res.get("timeout") == "derive" and not res.get("error") else 1


def run_capped(cmd, cap):
    """Runs a 'derive' child; every phase (derivation, evaluation, each cse variant) gets `cap`
    seconds of wall clock. Returns the merged record."""
    t_start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            start_new_session=True)
    out = {"cap_s": cap, "ok": False, "timeout": None}
    phases = []
    buf = b""
    deadline = time.perf_counter() + cap
    stderr_chunks = []
    fds = [proc.stdout, proc.stderr]
    while fds:
        left = deadline - time.perf_counter()
        if left <= 0:
            nxt = {0: "derive", 1: "eval" if "--no-eval" not in cmd else "cse"}.get(len(phases), "cse")
            if phases and phases[-1]["phase"] == "eval" and "--emit-c" not in cmd:
                nxt = "done"
            out["timeout"] = nxt
            os.killpg(proc.pid, signal.SIGKILL)
            break
        r, _, _ = select.select(fds, [], [], min(left, 1.0))
        for f in r:
            chunk = os.read(f.fileno(), 1 << 16)
            if not chunk:
                fds.remove(f)
                continue
            if f is proc.stderr:
                stderr_chunks.append(chunk)
                continue
            buf += chunk
            while b"\n" in buf:
                line, buf = buf.split(b"\n", 1)
                rec = json.loads(line)
                phases.append(rec)
                deadline = time.perf_counter() + cap
    proc.wait()
    out["wall_s"] = time.perf_counter() - t_start
    for rec in phases:
        if rec["phase"] == "emitted":
            out.setdefault("cse_variants", []).append(rec)
        elif rec["phase"] != "done":
            out.update({k: v for k, v in rec.items() if k != "phase"})
        else:
            out.update({k: v for k, v in rec.items() if k != "phase"})
    if any(r["phase"] == "done" for r in phases):
        out["ok"] = True
    elif out["timeout"] in ("cse", "done") and any(r["phase"] == "derived" for r in phases):
        out["ok"] = True  # derivation (and evaluation) done, a cse variant hit the cap
        kept = [r for r in out.get("cse_variants", []) if r.get("kept")]
        if kept:
            out["ops"] = kept[-1]["ops"]
            out["best_cse"] = kept[-1]["cse"]
            out["header"] = cmd[cmd.index("--emit-c") + 1]
    if "derive_s" not in out:
        out["derive_s"] = None
    err = b"".join(stderr_chunks).decode(errors="replace").strip()
    if proc.returncode not in (0, -signal.SIGKILL) or (not out["ok"] and not out["timeout"]):
        out["error"] = err[-2000:] or ("exit status %s" % proc.returncode)
    return out


# ----------------------------------------------------------------------------------------------
# The whole benchmark


def sh(cmd, **kw):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)
    if r.returncode != 0:
        raise Failure("command failed (%d): %s\n%s" % (r.returncode, " ".join(cmd), r.stderr[-3000:]))
    return r.stdout


def eomgen_eval(eomgen, chain, n, state):
    at = ",".join("%s=%r,%s_dot=%r" % (nm, q, nm, qd)
                  for nm, q, qd in zip(state["names"], state["q"], state["qd"]))
    model = os.path.join(ROOT, "models", CHAINS[chain][0])
    return json.loads(sh([eomgen, "eval", model, "-D", "n=%d" % n, "--at", at, "-f", "json"]))


def rel_err(A, B):
    """max |A - B| / max |B| over all entries (A, B nested lists)."""
    fa = [x for row in A for x in (row if isinstance(row, list) else [row])]
    fb = [x for row in B for x in (row if isinstance(row, list) else [row])]
    scale = max(abs(x) for x in fb) or 1.0
    return max(abs(x - y) for x, y in zip(fa, fb)) / scale


def fmt_s(x):
    if x is None:
        return "–"
    return "%.3g" % x if x < 100 else "%.0f" % x


def cmd_bench(a):
    eomgen = os.path.abspath(a.eomgen)
    if not os.access(eomgen, os.X_OK):
        raise Failure("eomgen not executable: %s" % eomgen)
    work = a.work_dir or tempfile.mkdtemp(prefix="sympy-bench-")
    os.makedirs(work, exist_ok=True)
    log = open(os.path.join(work, "results.jsonl"), "a")
    print("# work dir: %s" % work, file=sys.stderr)
    plan = [("planar", int(x)) for x in a.planar.split(",") if x] + \
           [("universal", int(x)) for x in a.universal.split(",") if x]
    methods = [m for m in a.methods.split(",") if m]
    rows = []
    capped = {}
    for chain, n in plan:
        model = os.path.join(ROOT, "models", CHAINS[chain][0])
        row = {"chain": chain, "n": n}
        # ours: eomgen generate, wall clock (process included), median of a.gen_reps runs
        ours_hpp = os.path.join(work, "%s_%d_eomgen.hpp" % (chain, n))
        times, inside = [], []
        for _ in range(a.gen_reps):
            t0 = time.perf_counter()
            row["ours_stats"] = sh([eomgen, "generate", model, "-D", "n=%d" % n, "--stats", "-o", ours_hpp])
            times.append(time.perf_counter() - t0)
            inside.append(in_process_seconds(row["ours_stats"]))
        row["ours_generate_s"] = statistics.median(times)
        row["ours_in_process_s"] = statistics.median(inside)
        row["ours_ops"] = count_ops.count_file(ours_hpp)
        st = check_state(chain, n)
        ev = eomgen_eval(eomgen, chain, n, st)
        if ev["parameters"] != CHAINS[chain][2]:
            raise Failure("parameter defaults differ: %s vs %s" % (ev["parameters"], CHAINS[chain][2]))
        row["ours_eval"] = {"M": ev["M"], "F": ev["F"]}
        for meth in methods:
            hpp = os.path.join(work, "%s_%d_%s.hpp" % (chain, n, meth))
            cmd = [sys.executable, os.path.abspath(__file__), "derive", "--chain", chain, "--n",
                   str(n), "--method", meth, "--emit-c", hpp, "--cse", a.cse]
            if (chain, meth) in capped:
                # a smaller n of this chain already hit the cap; a larger one only takes longer
                res = {"ok": False, "timeout": "derive", "derive_s": None, "skipped": True,
                       "cap_s": a.cap}
                row[meth] = res
                print("# %s n=%d %s: skipped (n=%d hit the cap)" % (chain, n, meth,
                      capped[(chain, meth)]), file=sys.stderr)
                continue
            res = run_capped(cmd, a.cap)
            if res.get("timeout") == "derive":
                capped[(chain, meth)] = n
            # short derivations: repeat (derivation only) and take the median
            if res.get("derive_s") is not None and res["derive_s"] < a.repeat_below:
                ds = [res["derive_s"]]
                for _ in range(a.derive_reps - 1):
                    r2 = run_capped(cmd[:cmd.index("--emit-c")] + ["--no-eval"], a.cap)
                    if r2.get("derive_s") is not None:
                        ds.append(r2["derive_s"])
                res["derive_runs_s"] = ds
                res["derive_s"] = statistics.median(ds)
            if "M" in res:
                res["err_M"] = rel_err(res["M"], ev["M"])
                res["err_F"] = rel_err(res["F"], ev["F"])
                res.pop("M"), res.pop("F"), res.pop("state", None)
            row[meth] = res
            print("# %s n=%d %s: derive %s s, timeout %s, err_M %s err_F %s" % (
                chain, n, meth, fmt_s(res.get("derive_s")), res.get("timeout"),
                res.get("err_M"), res.get("err_F")), file=sys.stderr)
            if res.get("error"):
                print("#   error: %s" % res["error"][-500:], file=sys.stderr)
        # timing program: ours and every SymPy header that was emitted (none: nothing to compare,
        # and a chain SymPy cannot derive gives a header whose M and F take GCC minutes to compile)
        if not a.no_timing and any(row[m].get("header") for m in methods):
            row["timing"] = time_variants(a, work, chain, n, ours_hpp,
                                          [(m, row[m]["header"]) for m in methods
                                           if row[m].get("header")])
        log.write(json.dumps(row) + "\n")
        log.flush()
        rows.append(row)
    print_tables(rows, methods, a)
    return 0


def time_variants(a, work, chain, n, ours_hpp, sympy_hdrs):
    src = os.path.join(HERE, "sympy_timing.cpp.in")
    exe = os.path.join(work, "%s_%d_timing" % (chain, n))
    defs = ["-DOURS_HEADER=\"%s\"" % ours_hpp, "-DOURS_NS=eomgen_models::%s_chain" % chain]
    for meth, hdr in sympy_hdrs:
        defs += ["-D%s_HEADER=\"%s\"" % (meth.upper(), hdr),
                 "-D%s_NS=sympy_models::%s_%s" % (meth.upper(), chain, meth)]
    st = check_state(chain, n)
    t0 = time.perf_counter()
    sh([a.cxx, "-x", "c++", "-std=c++17", a.opt, "-I" + a.eigen, *defs, src, "-o", exe])
    compile_s = time.perf_counter() - t0
    args = [exe, str(a.min_seconds), str(a.rounds)] + ["%r" % x for x in st["q"] + st["qd"]]
    out = json.loads(sh(args))
    out["compile_s"] = compile_s
    return out


def in_process_seconds(stats):
    """parse + derive + emit of `eomgen generate --stats` ("time [ms]: parse P, derive D, emit E")"""
    for line in stats.splitlines():
        if line.startswith("time [ms]:"):
            return sum(float(part.split()[-1]) for part in line.split(":", 1)[1].split(",")) / 1000.0
    raise Failure("eomgen --stats printed no time line")


def print_tables(rows, methods, a):
    P = print
    P("\n## Derivation time of M and F (seconds; SymPy: one process each, cap %g s)\n" % a.cap)
    P("eomgen = parse, derive, CSE and emit all functions inside `eomgen generate` (its --stats "
      "times; SymPy's import is excluded likewise), median of %d; process = the whole process "
      "wall clock, start-up included. SymPy = build the system + kanes_equations / "
      "form_lagranges_equations + mass_matrix, forcing; median of %d when "
      "< %g s. Ratio = SymPy / eomgen. SymPy+C adds cse() and ccode() of the kept variant.\n"
      % (a.gen_reps, a.derive_reps, a.repeat_below))
    hdr = "| chain | n | eomgen | process | " + " | ".join(
        "%s | ratio | %s+C" % (m, m) for m in methods) + " |"
    P(hdr)
    P("|" + "---|" * (hdr.count("|") - 1))
    for r in rows:
        cells = ["%s" % r["chain"], "%d" % r["n"], fmt_s(r["ours_in_process_s"]), fmt_s(r["ours_generate_s"])]
        for m in methods:
            res = r[m]
            d = res.get("derive_s")
            if d is None:
                if res.get("timeout") == "derive":
                    cells += ["> %g%s" % (a.cap, " (skipped)" if res.get("skipped") else ""), "–", "–"]
                else:
                    cells += ["error", "–", "–"]
                continue
            cells.append(fmt_s(d))
            cells.append("%.3gx" % (d / r["ours_in_process_s"]))
            kept = [v for v in res.get("cse_variants", []) if v.get("kept")]
            if kept:
                tot = d + res.get("to_plain_s", 0) + sum(v["cse_s"] + v["print_s"] for v in res.get("cse_variants", []) if v["cse"] == kept[-1]["cse"])
                cells.append(fmt_s(tot))
            else:
                cells.append("> %g (cse)" % a.cap if res.get("timeout") == "cse" else "–")
        P("| " + " | ".join(cells) + " |")

    P("\n## Cross-check at a random state (seed %d), default parameters: max|diff| / max|eomgen|\n"
      % CHECK_SEED)
    P("Python evaluation of SymPy's M, F vs `eomgen eval`; compiled SymPy C vs eomgen header.\n")
    hdr = "| chain | n | " + " | ".join("%s M | %s F | %s C: M | %s C: F" % (m, m, m, m) for m in methods) + " |"
    P(hdr)
    P("|" + "---|" * (hdr.count("|") - 1))
    for r in rows:
        cells = [r["chain"], "%d" % r["n"]]
        tm = r.get("timing", {}).get("variants", {})
        for m in methods:
            res = r[m]
            cells += ["%.1e" % res["err_M"] if "err_M" in res else "–",
                      "%.1e" % res["err_F"] if "err_F" in res else "–"]
            v = tm.get(m)
            cells += ["%.1e" % v["err_M"] if v else "–", "%.1e" % v["err_F"] if v else "–"]
        P("| " + " | ".join(cells) + " |")

    P("\n## Operations in mass_matrix_and_forcing (count_ops.py: + - * / unary-, calls; "
      "pow(x,k) = k-1 mults)\n")
    hdr = "| chain | n | eomgen (count_ops) | eomgen --stats | " + " | ".join(
        "%s (cse) | ratio" % m for m in methods) + " |"
    P(hdr)
    P("|" + "---|" * (hdr.count("|") - 1))
    for r in rows:
        o = r["ours_ops"]
        stats = [ln for ln in r["ours_stats"].splitlines() if ln.startswith("mass_matrix_and_forcing")]
        sv = stats[0].split()[2] if stats else "?"
        cells = [r["chain"], "%d" % r["n"], "%d (+%d *%d /%d -%d f%d)" % (
            o["total"], o["add"], o["mul"], o["div"], o["neg"], o["call"]), sv]
        for m in methods:
            res = r[m]
            if res.get("ops"):
                so = res["ops"]
                cells += ["%d [%s] (+%d *%d /%d -%d f%d)" % (so["total"], res.get("best_cse"),
                          so["add"], so["mul"], so["div"], so["neg"], so["call"]),
                          "%.2fx" % (so["total"] / o["total"])]
            else:
                cells += ["–", "–"]
        P("| " + " | ".join(cells) + " |")
    P("\ncse variants tried (total ops / cse seconds):")
    for r in rows:
        for m in methods:
            vs = r[m].get("cse_variants", [])
            if vs:
                P("  %s n=%d %s: %s" % (r["chain"], r["n"], m, ", ".join(
                    "%s %d ops %.3gs" % (v["cse"], v["ops"]["total"], v["cse_s"]) for v in vs)))

    P("\n## Evaluation (ns per call, g++ %s, median of rounds, variants interleaved)\n" % a.opt)
    P("trig floor: the same call doing only sin and cos of each coordinate (one sincos each) and "
      "writing M and F, which every side's M + F computes too.\n")
    hdr = "| chain | n | trig floor | eomgen M+F | " + " | ".join("%s M+F | ratio" % m for m in methods) + \
          " | eomgen FD | " + " | ".join("%s FD | ratio" % m for m in methods) + " |"
    P(hdr)
    P("|" + "---|" * (hdr.count("|") - 1))
    for r in rows:
        tv = r.get("timing", {}).get("variants")
        if not tv:
            continue
        o = tv["eomgen"]
        floor = r["timing"].get("trig_floor_ns")
        cells = [r["chain"], "%d" % r["n"], "%.1f" % floor if floor else "–", "%.1f" % o["mf_ns"]]
        for m in methods:
            v = tv.get(m)
            cells += ["%.1f" % v["mf_ns"], "%.2fx" % (v["mf_ns"] / o["mf_ns"])] if v else ["–", "–"]
        cells.append("%.1f" % o["fd_ns"])
        for m in methods:
            v = tv.get(m)
            cells += ["%.1f" % v["fd_ns"], "%.2fx" % (v["fd_ns"] / o["fd_ns"])] if v else ["–", "–"]
        P("| " + " | ".join(cells) + " |")


def main(argv=None):
    ap = argparse.ArgumentParser(description="SymPy peer benchmark for eomgen",
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__)
    sub = ap.add_subparsers(dest="cmd", required=True)

    def common(p):
        p.add_argument("--chain", choices=sorted(CHAINS), required=True)
        p.add_argument("--n", type=int, required=True)
        p.add_argument("--method", choices=["kane", "lagrange"], required=True)
        p.add_argument("--emit-c", metavar="OUT.hpp")
        p.add_argument("--cse", default="none,basic", help="cse variants to try (none,basic)")
        p.add_argument("--seed", type=int, default=CHECK_SEED)
        p.add_argument("--no-eval", action="store_true", help="skip the numeric evaluation")

    common(sub.add_parser("derive", help="derive in this process (JSON lines)"))
    pr = sub.add_parser("run", help="derive in a child process with a cap (one JSON line)")
    common(pr)
    pr.add_argument("--cap", type=float, default=120.0, help="seconds per phase (default 120)")
    ps = sub.add_parser("state", help="print the check state")
    ps.add_argument("--chain", choices=sorted(CHAINS), required=True)
    ps.add_argument("--n", type=int, required=True)
    pb = sub.add_parser("bench", help="the whole comparison, markdown tables on stdout")
    pb.add_argument("--eomgen", default=os.path.join(ROOT, "build", "generator", "eomgen"))
    pb.add_argument("--cap", type=float, default=120.0)
    pb.add_argument("--planar", default="1,2,4,8,16,32")
    pb.add_argument("--universal", default="1,2,4,8")
    pb.add_argument("--methods", default="kane,lagrange")
    pb.add_argument("--cse", default="none,basic")
    pb.add_argument("--gen-reps", type=int, default=3)
    pb.add_argument("--derive-reps", type=int, default=3)
    pb.add_argument("--repeat-below", type=float, default=5.0,
                    help="repeat SymPy derivations shorter than this (s)")
    pb.add_argument("--no-timing", action="store_true")
    pb.add_argument("--rounds", type=int, default=9)
    pb.add_argument("--min-seconds", type=float, default=0.05)
    pb.add_argument("--cxx", default=os.environ.get("CXX", "g++"))
    pb.add_argument("--opt", default="-O2")
    pb.add_argument("--eigen", default="/usr/include/eigen3")
    pb.add_argument("--work-dir", help="keep headers and programs here (default: a mktemp dir)")
    a = ap.parse_args(argv)
    if getattr(a, "n", 1) < 1:
        ap.error("--n must be >= 1")
    try:
        if a.cmd == "derive":
            return cmd_derive(a)
        if a.cmd == "run":
            return cmd_run(a)
        if a.cmd == "state":
            emit(check_state(a.chain, a.n))
            return 0
        return cmd_bench(a)
    except Failure as e:
        print("sympy_chains: error: %s" % e, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
