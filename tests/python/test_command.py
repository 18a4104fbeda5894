"""`eomgen python`: builds a module that imports with nothing else on the path, reuses its
cached build, and refuses bad requests with a message and a non-zero status."""
import os
import pathlib
import subprocess
import sys
import sysconfig

import pytest

from conftest import EOMGEN, SOURCE_DIR

# the builds are kept between runs of the suite, keyed by content like simulate's
CACHE = pathlib.Path(os.environ.get("EOMGEN_TEST_CACHE_DIR", "cache")).parent / "python_command_cache"
SUFFIX = sysconfig.get_config_var("EXT_SUFFIX")


def eomgen(*arguments, check=True):
    run = subprocess.run([EOMGEN, *map(str, arguments)], capture_output=True, text=True, timeout=900)
    if check:
        assert run.returncode == 0, run.stderr
    return run


def run_python(code, path):
    environment = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    environment["PYTHONPATH"] = str(path)
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=environment,
                          cwd=path.parent, timeout=120)


@pytest.mark.parametrize("model", ["cart_pole", "four_bar"])
def test_the_module_imports_with_nothing_else_on_the_path(tmp_path, model):
    out = tmp_path / "modules"
    run = eomgen("python", SOURCE_DIR / "models" / f"{model}.eom", "-o", out, "--cache-dir", CACHE)
    module = out / f"{model}{SUFFIX}"
    assert run.stdout == f"module: {module}\n"
    assert sorted(p.name for p in out.iterdir()) == [module.name]
    check = run_python(f"import numpy as np, {model} as m; M = m.mass_matrix(0.0, np.zeros(m.nq)); "
                       "print(m.name, M.shape)", out)
    assert check.returncode == 0, check.stderr
    assert check.stdout == f"{model} ({'2, 2' if model == 'cart_pole' else ', '.join(['3'] * 2)})\n"


def test_a_second_build_of_the_same_model_is_the_cached_one(tmp_path):
    first = eomgen("python", SOURCE_DIR / "models" / "cart_pole.eom", "-o", tmp_path / "a", "--cache-dir", CACHE)
    second = eomgen("python", SOURCE_DIR / "models" / "cart_pole.eom", "-o", tmp_path / "b", "--cache-dir", CACHE)
    assert "using the cached build" in second.stderr
    assert (tmp_path / "a" / f"cart_pole{SUFFIX}").read_bytes() == (tmp_path / "b" / f"cart_pole{SUFFIX}").read_bytes()


def test_another_module_name_is_the_name_to_import(tmp_path):
    eomgen("python", SOURCE_DIR / "models" / "cart_pole.eom", "-o", tmp_path, "--module-name", "cartpole2",
           "--cache-dir", CACHE)
    check = run_python("import cartpole2; print(cartpole2.name)", tmp_path)
    assert check.stdout == "cart_pole\n", check.stderr


def test_source_only_writes_the_header_and_the_binding_source(tmp_path):
    eomgen("python", SOURCE_DIR / "models" / "cart_pole.eom", "-o", tmp_path, "--source-only")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["model.hpp", "module.cpp"]
    source = (tmp_path / "module.cpp").read_text()
    assert "PYBIND11_MODULE(cart_pole, m)" in source and '#include "eompy/module.hpp"' in source
    assert "linearization_terms" in (tmp_path / "model.hpp").read_text()


@pytest.mark.parametrize("name", ["class", "1abc", "my-module", "lambda"])
def test_a_module_name_that_python_cannot_import_is_a_usage_error(tmp_path, name):
    run = eomgen("python", SOURCE_DIR / "models" / "cart_pole.eom", "-o", tmp_path, "--module-name", name,
                 "--cache-dir", CACHE, check=False)
    assert run.returncode == 2
    assert "--module-name: expected a Python identifier" in run.stderr
    assert list(tmp_path.iterdir()) == []


def test_a_model_with_an_error_is_reported_at_its_position_and_nothing_is_written(tmp_path):
    model = tmp_path / "broken.eom"
    model.write_text("model broken\ncoordinate q\nparameter m = 1 [kg]\nparticle p(mass = m, at = w + q*a.4)\n")
    run = eomgen("python", model, "-o", tmp_path / "out", check=False)
    assert run.returncode == 1
    assert run.stderr.startswith(f"{model}:4:")
    assert not (tmp_path / "out").exists() or list((tmp_path / "out").iterdir()) == []


def test_an_output_directory_that_is_a_file_is_refused(tmp_path):
    target = tmp_path / "file"
    target.write_text("keep me")
    run = eomgen("python", SOURCE_DIR / "models" / "cart_pole.eom", "-o", target, check=False)
    assert run.returncode == 2 and "is not a directory" in run.stderr
    assert target.read_text() == "keep me"


def test_a_model_named_with_every_name_that_broke_generated_code_builds_and_imports(tmp_path):
    # tests/cli/models/colliding_names.eom: C++ keywords, macros, the header's own names, and
    # Python's keywords (lambda, import); the module is named NULL_, as its header's namespace
    eomgen("python", SOURCE_DIR / "tests" / "cli" / "models" / "colliding_names.eom", "-o", tmp_path,
           "--cache-dir", CACHE)
    check = run_python(
        "import math, NULL_ as m\n"
        "p = m.Parameters(lambda_=1.5)\n"
        "assert p.lambda_ == 1.5 and p.import_ == 2.11 and p.class_ == 1.51 and p.outputs_ == 1.31\n"
        "assert len(p.to_dict()) == m.np and m.parameter_defaults['lambda'] == 1.17\n"
        "assert eval(repr(p), {'NULL_': m}) == p\n"
        "T = m.kinetic_energy(0.0, [0.3, 0.4], [-0.2, 0.5], p)\n"
        "assert math.isfinite(T) and T > 0\n"
        "print(m.name, m.state_names, m.input_names)", tmp_path)
    assert check.returncode == 0, check.stderr
    assert check.stdout == "NULL ('errno', '__theta', 'errno_dot', '__theta_dot') ('stdin', '_u_')\n"
