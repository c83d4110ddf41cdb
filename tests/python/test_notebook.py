"""examples/k01_tour.ipynb executed by nbclient (issue 31) against the build tree's module (PYTHONPATH), with small
sizes set in a cell inserted after its `parameters` cell (as papermill does): every cell runs without an error,
the background run reaches 100 % and finishes, and its figures are drawn.  The executed notebook and its figures
(PNG) are saved in <build>/notebook-output/k01_tour/ to be looked at.  The committed notebook must carry no outputs."""
import base64
import json
import os
import pathlib
import sys
import time

import pytest

import archipelago as ap  # PYTHONPATH = the build tree's python folder

# Missing packages fail the test rather than skip it: scripts/install-deps.sh installs them, and CI must run it.
try:
    import ipykernel  # noqa: F401
    import matplotlib  # noqa: F401
    import nbclient
    import nbformat
except ImportError as e:
    pytest.fail(f"{e}: the notebook's test needs python3-nbclient, python3-ipykernel and python3-matplotlib "
                "(bash scripts/install-deps.sh)", pytrace=False)

NOTEBOOK = pathlib.Path(__file__).resolve().parents[2] / "examples" / "k01_tour.ipynb"
# M ≥ subsets (16); 32 × 4·10⁶ blocks of 16 steps = 2·10⁹ steps: about a second on two cores.
SMALL = """PRESET = "k0.1-minute"
OVERRIDES = {"M": 32, "T": 4_000_000}
THREADS = 2
PORTRAIT_POINTS = 2_000_000
CHAIN_POINTS = 200_000
PROFILE_POINTS = 200
MANIFOLD_LENGTH = 4.0
"""


def outputs_dir():
    """<build>/notebook-output/k01_tour: the module is <build>/python/archipelago/."""
    build = pathlib.Path(ap.__file__).resolve().parents[2]
    d = build / "notebook-output" / "k01_tour"
    d.mkdir(parents=True, exist_ok=True)
    for old in d.iterdir():
        old.unlink()
    return d


def kernel_spec(tmp_path):
    """A kernel spec that runs this interpreter (the one whose NumPy and matplotlib the test found), whatever
    `python3` is first on PATH."""
    spec = tmp_path / "kernels" / "archipelago-test"
    spec.mkdir(parents=True)
    (spec / "kernel.json").write_text(json.dumps({
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "archipelago test", "language": "python"}))
    return str(tmp_path)


def test_committed_notebook_has_no_outputs():
    nb = nbformat.read(NOTEBOOK, as_version=4)
    nbformat.validate(nb)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert code and all(c.outputs == [] and c.execution_count is None for c in code), \
        "strip the outputs of examples/k01_tour.ipynb before committing it"
    assert sum("parameters" in c.metadata.get("tags", []) for c in code) == 1


def test_notebook_runs(tmp_path, monkeypatch):
    nb = nbformat.read(NOTEBOOK, as_version=4)
    where = next(i for i, c in enumerate(nb.cells) if "parameters" in c.metadata.get("tags", []))
    nb.cells.insert(where + 1, nbformat.v4.new_code_cell(SMALL, metadata={"tags": ["injected-parameters"]}))
    monkeypatch.setenv("JUPYTER_PATH", kernel_spec(tmp_path) + os.pathsep + os.environ.get("JUPYTER_PATH", ""))
    # The kernel imports the module the test imported (PYTHONPATH may be relative; the kernel runs in tmp_path).
    monkeypatch.setenv("PYTHONPATH", str(pathlib.Path(ap.__file__).resolve().parents[1]))
    monkeypatch.setenv("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # ipykernel's debugger warns about frozen modules
    monkeypatch.setenv("MPLBACKEND", "module://matplotlib_inline.backend_inline")
    client = nbclient.NotebookClient(nb, kernel_name="archipelago-test", timeout=1200,
                                     resources={"metadata": {"path": str(tmp_path)}})
    started = time.monotonic()
    try:
        client.execute()  # raises CellExecutionError, with the cell and its traceback, if a cell fails
    finally:
        out = outputs_dir()
        nbformat.write(nb, out / "k01_tour.executed.ipynb")
        figures = []
        for i, cell in enumerate(nb.cells):
            for j, o in enumerate(cell.get("outputs", [])):
                if "image/png" in o.get("data", {}):
                    path = out / f"cell{i:02d}-{j}.png"
                    path.write_bytes(base64.b64decode(o["data"]["image/png"]))
                    figures.append(path.name)
        print(f"notebook executed in {time.monotonic() - started:.1f} s; figures in {out}: {figures}")

    def text(cell):
        return "".join(o.get("text", "") + o.get("data", {}).get("text/plain", "") for o in cell.outputs)

    # the portrait, fig. 6, the segment and its zoom, the rotation profile, the manifolds and lobes
    assert len(figures) == 5, figures
    flux = next(text(c) for c in nb.cells if c.cell_type == "code" and "ap.flux(K)" in c.source)
    digits = float(flux.split(" digits agree")[0].split(": ")[-1])
    assert digits >= 9, flux  # the two independent flux methods agree (issue #28's criterion)
    profile = next(text(c) for c in nb.cells if c.cell_type == "code" and "rotation_profile" in c.source)
    assert "plateaus (p/q: starts)" in profile, profile
    bar = next(text(c) for c in nb.cells if c.cell_type == "code" and "job.wait()" in c.source)
    assert "100.0%" in bar, bar  # the progress display, updated in place, reached the end
    summary = json.loads(text(nb.cells[-1]).strip().splitlines()[-1])
    assert summary["finished"] and summary["blocks_done"] == summary["T"] == 4_000_000, summary
    assert summary["segments"] > 0 and summary["chain_period"] >= 1, summary
