"""The docstring examples run, and the stubs name what the module has."""

import doctest
import inspect
import pathlib

import numpy as np

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


def test_stubs_cover_the_module():
    stub = (pathlib.Path(aaglsd.__file__).parent / "_aaglsd.pyi").read_text()
    public = [n for n in dir(aaglsd._aaglsd) if not n.startswith("__")]
    for name in public + ["__version__"]:
        assert f"def {name}(" in stub or f"class {name}:" in stub or f"{name}: Final" in stub, name
    for attr in ("summary", "width", "height", "color", "max_segments", "workspace_bytes", "config"):
        assert hasattr(aaglsd.Detector(8, 8), attr) and f"def {attr}(self)" in stub, attr
    for field in ("segments", "dropped_segments", "dropped_candidates", "truncated_linkings",
                  "candidates", "groups", "merged"):
        assert f"    {field}: int" in stub and hasattr(aaglsd.Detector, "summary")
    assert (pathlib.Path(aaglsd.__file__).parent / "py.typed").exists()
