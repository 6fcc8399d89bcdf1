"""Shared fixtures: the `stray` binary the package is compared with (the
same build: STRAY_BIN, default <repo>/build/bin/stray) and small inputs
made once per session with it."""
import json
import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
STRAY = os.environ.get("STRAY_BIN", str(REPO / "build" / "bin" / "stray"))
RIGD = os.environ.get("STRAYRIGD_BIN", str(Path(STRAY).parent / "strayrigd"))

# timing and provenance differ from run to run; every other value is equal
VOLATILE = {"seconds", "paths_per_s", "casts_per_s", "trace_seconds",
            "provenance", "fit_seconds"}


def cli(*args, cwd=None, check=True):
    """Run `stray args...`: (exit code, stdout, stderr)."""
    p = subprocess.run([STRAY, *map(str, args)], capture_output=True,
                       text=True, cwd=cwd)
    if check and p.returncode != 0:
        raise AssertionError(f"stray {args} failed ({p.returncode}): "
                             f"{p.stderr}")
    return p.returncode, p.stdout, p.stderr


def cli_json(*args, cwd=None):
    return json.loads(cli("--json", *args, cwd=cwd)[1])


def stable(d):
    """A --json dict without the run-to-run keys, at every depth."""
    if isinstance(d, dict):
        return {k: stable(v) for k, v in d.items() if k not in VOLATILE}
    if isinstance(d, list):
        return [stable(v) for v in d]
    return d


def read_csv_text(path):
    """A curve CSV's header and rows as text (comments dropped)."""
    with open(path) as f:
        rows = [ln.rstrip("\n") for ln in f if not ln.startswith("#")]
    return rows[0].split(","), [r.split(",") for r in rows[1:]]


TRACE_ARGS = dict(scene="ref4", angles="0:30:10,30:60:5", rays=40000,
                  seed=3, threads=2, set={"reflectance": 0.08})
TRACE_CLI = ["trace", "--scene", "ref4", "--angles", "0:30:10,30:60:5",
             "--rays", "40000", "--seed", "3", "--threads", "2",
             "--set", "reflectance=0.08"]


@pytest.fixture(scope="session")
def work(tmp_path_factory):
    return tmp_path_factory.mktemp("straylight")


@pytest.fixture(scope="session")
def cli_trace(work):
    """`stray trace` of the shared inputs: (curve path, --json dict)."""
    out = work / "cli_trace.csv"
    summary = cli_json(*TRACE_CLI, "--out", out)
    return out, summary


@pytest.fixture(scope="session")
def sweep(work):
    """A small simulated lab sweep (strayrigd, simulators, 20 frames)."""
    cfg = work / "rig.json"
    cfg.write_text(json.dumps({
        "backend": "sim",
        "sweep": {"theta_start_deg": 0, "theta_stop_deg": 20,
                  "theta_step_deg": 5, "repeats": 1},
        "vlab": {"seed": 11}}))
    d = work / "sweep"
    subprocess.run([RIGD, "--config", str(cfg), "--sweep", str(d)],
                   check=True, capture_output=True)
    return d


@pytest.fixture(scope="session")
def mission(work):
    """A two-hour demo mission (OEM/AEM) and two heads on a flight table."""
    d = work / "mission"
    d.mkdir()
    cli("firmware-table", "--curve", REPO / "tests/vectors/fdrfw_curve.csv",
        "--out-bin", d / "flight_table.bin")
    cli("availability", "--write-oem", d / "m.oem", "--write-aem",
        d / "m.aem", "--hours", "2")
    heads = {"heads": [
        {"name": "A", "boresight_body": [0, 0.6428, -0.7660],
         "up_body": [1, 0, 0], "table": "flight_table.bin"},
        {"name": "B", "boresight_body": [0, -0.6428, -0.7660],
         "up_body": [1, 0, 0], "table": "flight_table.bin"}]}
    (d / "heads.json").write_text(json.dumps(heads))
    return d
