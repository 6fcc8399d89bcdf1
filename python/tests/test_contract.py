"""Every function of docs/python.md against `stray` on the same inputs:
the same values (arrays to the last bit where the CLI prints them so,
dicts equal to --json but for timing and provenance)."""
import csv

import numpy as np
import pytest

import straylight as sl
from conftest import (STRAY, TRACE_ARGS, TRACE_CLI, cli, cli_json,
                      read_csv_text, stable)


def test_version_is_the_cli_s():
    assert cli("--version")[1].strip() == "stray " + sl.__version__


@pytest.fixture(scope="module")
def curve():
    return sl.trace(**TRACE_ARGS)


def test_trace_equals_cli(curve, cli_trace):
    path, summary = cli_trace
    header, rows = read_csv_text(path)
    cols = {"theta_deg": curve.theta_deg, "alpha": curve.alpha,
            "sigma": curve.sigma, **curve.columns}
    assert header == list(cols)
    for k, name in enumerate(header):
        # the CSV holds %.10g of the doubles the library computed
        assert [r[k] for r in rows] == ["%.10g" % v for v in cols[name]]
    # the run summary: worst_rel_sigma is a full-precision function of
    # every alpha and sigma, equal to the last bit
    want = stable(summary)
    assert want.pop("out") == str(path)
    assert stable(curve.summary) == want
    for a in (curve.theta_deg, curve.alpha, curve.sigma):
        assert a.dtype == np.float64
    assert curve.meta["seed"] == 3 and curve.meta["rays"] == 40000
    assert curve.meta["overrides"] == {"reflectance": 0.08}
    assert curve.meta["version"] == sl.__version__


def test_trace_repeats_to_the_bit(curve):
    again = sl.trace(**TRACE_ARGS)
    assert again.alpha.tobytes() == curve.alpha.tobytes()
    assert again.sigma.tobytes() == curve.sigma.tobytes()


def test_to_csv_is_the_cli_s_file(curve, cli_trace, tmp_path):
    path, _ = cli_trace
    mine = tmp_path / "c.csv"
    curve.to_csv(mine)
    strip = lambda p: [ln for ln in open(p) if not ln.startswith("# command")]
    assert strip(mine) == strip(path)
    assert "# command: stray --json trace --scene ref4" in mine.read_text()


def test_read_curve_round_trip(cli_trace):
    path, _ = cli_trace
    c = sl.read_curve(path)
    header, rows = read_csv_text(path)
    assert c.alpha.tolist() == [float(r[1]) for r in rows]
    assert c.sigma.tolist() == [float(r[2]) for r in rows]
    assert list(c.columns) == header[3:]
    assert c.meta["kind"] == "baffle"


def test_curve_csv_reads_in_numpy_as_documented(cli_trace):
    path, _ = cli_trace
    a = np.genfromtxt((ln for ln in open(path) if not ln.startswith("#")),
                      delimiter=",", names=True)
    assert a.dtype.names[:3] == ("theta_deg", "alpha", "sigma")
    assert a["alpha"].tolist() == sl.read_curve(path).alpha.tolist()


def test_photometry_equals_cli():
    assert stable(sl.photometry()) == stable(cli_json("photometry"))
    assert stable(sl.photometry(sensor="st16-like")) == \
        stable(cli_json("photometry", "--sensor", "st16-like"))


def test_fdr_equals_cli():
    assert stable(sl.fdr()) == stable(cli_json("fdr", "--rate", "5"))
    assert stable(sl.fdr(source="moon", rate=2, alpha=3e-6)) == stable(
        cli_json("fdr", "--source", "moon", "--rate", "2", "--alpha", "3e-6"))


def test_exclusion_curve_path_and_arrays(curve, cli_trace, tmp_path):
    path, _ = cli_trace
    want = stable(cli_json("exclusion", "--curve", path))
    assert stable(sl.exclusion(path)) == want
    # an in-memory curve goes through the CSV the CLI reads: the same file
    got = stable(sl.exclusion(curve))
    got.pop("curve"), want.pop("curve")
    assert got == want
    c = sl.read_curve(path)
    own = tmp_path / "ta.csv"
    sl.Curve(c.theta_deg, c.alpha, c.sigma).to_csv(own)
    w2 = stable(cli_json("exclusion", "--curve", own))
    g2 = stable(sl.exclusion((c.theta_deg, c.alpha, c.sigma)))
    g2.pop("curve"), w2.pop("curve")
    assert g2 == w2


def _read_fits_u16(path):
    """A primary-HDU BITPIX 16 / BZERO 32768 image as uint16 (rows, cols)."""
    raw = open(path, "rb").read()
    cards, off = {}, 0
    while True:
        block = raw[off:off + 2880]
        off += 2880
        done = False
        for i in range(0, 2880, 80):
            card = block[i:i + 80].decode("ascii")
            key = card[:8].strip()
            if key == "END":
                done = True
                break
            if card[8:10] == "= ":
                cards[key] = card[10:].split("/")[0].strip()
        if done:
            break
    cols, rows = int(cards["NAXIS1"]), int(cards["NAXIS2"])
    assert int(cards["BITPIX"]) == 16
    data = np.frombuffer(raw, dtype=">i2", count=rows * cols, offset=off)
    return (data.astype(np.int32) + 32768).astype(np.uint16).reshape(rows,
                                                                     cols)


def test_frames_equal_cli_without_a_copy(cli_trace, tmp_path):
    # The bare baffle's light at 35 deg (alpha 1.4e-4) fills every pixel to
    # the ADC's full scale, which `stray frames` refuses: a system curve,
    # the baffle's off-axis alpha times 1e-3 (a lens), as a CSV of its own.
    c = sl.read_curve(cli_trace[0])
    path = tmp_path / "system.csv"
    with open(path, "w") as fh:
        fh.write("theta_deg,alpha,sigma\n")
        for t, a, e in zip(c.theta_deg, c.alpha, c.sigma):
            k = 1.0 if t == 0 else 1e-3
            fh.write("%.17g,%.17g,%.17g\n" % (t, a * k, e * k))
    f = sl.frames(curve=path, theta=35, frames=2, window=96, seed=7)
    want = cli_json("frames", "--curve", path, "--theta", "35", "--frames",
                    "2", "--window", "96", "--seed", "7", "--out-dir",
                    tmp_path / "fr", "--save", "2")
    got, want = stable(f.summary), stable(want)
    want.pop("out_dir", None), got.pop("out_dir", None)
    assert got == want
    assert f.images.shape == (2, 96, 96) and f.images.dtype == np.uint16
    with open(tmp_path / "fr" / "manifest.csv") as m:
        files = [r["file"] for r in csv.DictReader(
            ln for ln in m if not ln.startswith("#"))]
    assert len(files) == 2
    for i, name in enumerate(files):
        assert np.array_equal(f.images[i], _read_fits_u16(tmp_path / "fr" /
                                                          name))
    # numpy over the library's buffer: not owned, its base a C buffer
    assert not f.images.flags.owndata
    base = f.images
    while isinstance(base, np.ndarray):
        base = base.base
    assert type(base).__module__ == "straylight._lib"
    import ctypes
    assert f.images.__array_interface__["data"][0] == ctypes.addressof(base)


def test_reduce_equals_cli(sweep, tmp_path):
    c, d = sl.reduce(sweep)
    want = cli_json("reduce", sweep, "--out", tmp_path / "l.csv")
    got, want = stable(d), stable(want)
    got.pop("out"), want.pop("out")
    assert got == want
    header, rows = read_csv_text(tmp_path / "l.csv")
    assert [r[1] for r in rows] == ["%.10g" % v for v in c.alpha]
    assert [r[2] for r in rows] == ["%.10g" % v for v in c.sigma]
    assert list(c.columns) == ["noise_floor"]


@pytest.fixture(scope="module")
def measured(tmp_path_factory):
    d = tmp_path_factory.mktemp("diag")
    cli("trace", "--scene", "ref4", "--set", "reflectance=0.08", "--angles",
        "0:10:5,10:60:2.5", "--rays", "60000", "--threads", "2", "--out",
        d / "truth.csv")
    cli("photometer", "--truth", d / "truth.csv", "--out", d / "m.csv")
    return d / "m.csv"


def test_diagnose_equals_cli(measured):
    opts = ["--rays", "20000", "--threads", "2", "--causes",
            "reflectance,floor"]
    want = stable(cli_json("diagnose", measured, "--scene", "ref4", *opts))
    got = stable(sl.diagnose(measured, scene="ref4", rays=20000, threads=2,
                             causes="reflectance,floor"))
    assert got == want
    assert len(got["curves"]["model_after"]) == got["n"]
    # a Curve in memory: the same file the CLI reads
    got2 = stable(sl.diagnose(sl.read_curve(measured), scene="ref4",
                              rays=20000, threads=2,
                              causes="reflectance,floor"))
    assert got2["causes"] == want["causes"]


def test_availability_equals_cli(mission):
    m = mission
    args = ["--oem", m / "m.oem", "--aem", m / "m.aem", "--heads",
            m / "heads.json"]
    want = stable(cli_json("availability", *args, "--out", m / "a.csv"))
    a = sl.availability(m / "m.oem", m / "m.aem", m / "heads.json")
    assert isinstance(a, dict) and stable(dict(a)) == want
    s = a.series
    with open(m / "a.csv") as f:
        rows = list(csv.DictReader(ln for ln in f if not ln.startswith("#")))
    assert len(s) == len(rows) == want["covered_epochs"]
    assert s["t_s"].tolist() == [float(r["t_s"]) for r in rows]
    assert s["A_sun_deg"].tolist() == [float(r["A_sun_deg"]) for r in rows]
    assert s["A_flags"].tolist() == [int(r["A_flags"]) for r in rows]
    assert s["utc"][0] == np.datetime64(rows[0]["utc"].rstrip("Z"))
    assert s["utc"].dtype == np.dtype("datetime64[us]")
    # the named flags are the bitmask's bits
    for bit, name in enumerate(["sun_excluded", "moon_excluded",
                                "earth_excluded"]):
        assert (s["B_" + name] == ((s["B_flags"] >> bit) & 1).astype(bool)
                ).all()
    assert s["any_available"].dtype == np.bool_
