"""The docstring examples run, and the stubs match the compiled module."""

import doctest
import inspect
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import aaglsd
import aaglsd._aaglsd
import aaglsd.bench


def run_doctests(obj, name):
    finder = doctest.DocTestFinder()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    globs = {"np": np, "aaglsd": aaglsd}
    if inspect.ismodule(obj):
        globs.update(vars(obj))
    for test in finder.find(obj, name, module=False, globs=globs):
        runner.run(test)
    return runner.summarize(verbose=False)


def test_docstring_examples_run():
    attempted = 0
    for name in ("detect", "config", "Detector"):
        failed, n = run_doctests(getattr(aaglsd, name), name)
        assert failed == 0 and n > 0, name
        attempted += n
    for mod in (aaglsd, aaglsd.bench):
        failed, n = run_doctests(mod, mod.__name__)
        assert failed == 0 and n > 0, mod.__name__
        attempted += n
    assert attempted >= 15


def test_stubs_ship_with_the_package():
    here = pathlib.Path(aaglsd.__file__).parent
    assert (here / "py.typed").exists() and (here / "_aaglsd.pyi").exists()


def test_stubs_match_the_runtime(tmp_path):
    """mypy's stubtest: every stub signature against the compiled module."""
    pytest.importorskip("mypy", reason="mypy not installed: stubtest SKIPPED")
    r = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "aaglsd", "--mypy-config-file", "/dev/null"],
        capture_output=True, text=True, cwd=tmp_path,
    )
    assert r.returncode == 0, r.stdout + r.stderr
