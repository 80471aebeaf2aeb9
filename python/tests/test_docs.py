"""The Python examples of the documentation run from any directory: every ```python block of
docs/reference/python.md and docs/guides/python-dask.md, in order, in one namespace per
document, with a temporary directory as the working directory (so no example may rely on a
path of the repository). Blocks that need an optional package skip when it is missing; the
Slurm block (a cluster) and interactive ``>>>`` transcripts are not run."""

import importlib.util
import os
import re
from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parents[2] / "docs"
PAGES = [DOCS / "reference" / "python.md", DOCS / "guides" / "python-dask.md"]

# A block importing one of these runs only where it is installed.
OPTIONAL = ("pygmo", "pymoo", "matplotlib", "dask", "pandas")


def python_blocks(text: str):
    """The ```python blocks of a Markdown text, their indentation removed."""
    for m in re.finditer(r"^( *)```python\n(.*?)^\1```", text, re.S | re.M):
        indent = len(m.group(1))
        yield "\n".join(line[indent:] for line in m.group(2).splitlines())


def missing_module(code: str):
    for name in OPTIONAL:
        if re.search(rf"^\s*(import|from) {name}\b", code, re.M) and importlib.util.find_spec(name) is None:
            return name
    return None


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_documented_examples_run_from_any_directory(page, tmp_path, monkeypatch):
    if not page.exists():
        pytest.skip(f"{page} not found (tests run from a clone of the repository)")
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "__main__"}
    exec("import reentry", namespace)
    ran = 0
    for i, code in enumerate(python_blocks(page.read_text())):
        if code.lstrip().startswith(">>>") or "SLURMCluster" in code:
            continue
        absent = missing_module(code)
        if absent is not None:
            print(f"{page.name} block {i}: skipped, {absent} is not installed")
            continue
        exec(compile(code, f"{page.name} (block {i})", "exec"), namespace)
        ran += 1
    assert ran > 0, f"no example of {page.name} ran"
    assert os.getcwd() == str(tmp_path)
