"""The contract of docs/python.md: one function per `stray` command.

Each runs the command's own code through libstraycmd (see _lib.py);
keyword arguments not named here are passed as the command's long
options (``mag_max=8`` is ``--mag-max 8``; True is a flag).
"""
from __future__ import annotations

import os
import re
import tempfile
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _lib
from .curve import Curve, PathLike

CurveLike = Union[Curve, PathLike, Tuple[Any, Any], Tuple[Any, Any, Any]]


def _sets(overrides: Optional[Mapping[str, Any]]) -> Optional[list]:
    if not overrides:
        return None
    return [f"{k}={_lib._opt_text(v)}" for k, v in overrides.items()]


class _CurveFile:
    """A curve argument as the file the command reads: a path as given,
    else the curve written by the library's writer to a scratch file."""

    def __init__(self, curve: CurveLike, what: str = "curve"):
        self.tmp: Optional[tempfile.TemporaryDirectory] = None
        if isinstance(curve, (str, os.PathLike)):
            self.path = os.fspath(curve)
            return
        if isinstance(curve, tuple):
            if len(curve) not in (2, 3):
                raise _lib.InputError(f"{what}: (theta_deg, alpha[, sigma]) "
                                      "arrays expected")
            curve = Curve(*curve)
        if not isinstance(curve, Curve):
            raise TypeError(f"{what}: a straylight.Curve, a path or "
                            "(theta_deg, alpha[, sigma]) arrays")
        self.tmp = tempfile.TemporaryDirectory(prefix="straylight-")
        self.path = os.path.join(self.tmp.name, f"{what}.csv")
        curve.to_csv(self.path)

    def __enter__(self) -> str:
        return self.path

    def __exit__(self, *exc: Any) -> None:
        if self.tmp is not None:
            self.tmp.cleanup()


def trace(scene: str = "ref4", angles: Optional[str] = None,
          rays: Optional[int] = None, seed: Optional[int] = None,
          threads: Optional[int] = None,
          set: Optional[Mapping[str, Any]] = None,
          lens: Optional[CurveLike] = None, **options: Any) -> Curve:
    """Monte Carlo attenuation curve of a baffle (`stray trace`).

    Args:
        scene: 'ref4' (built in) or a scene file.
        angles: the angle list ("0:30:5,30:90:0.5"; None or "auto": the
            grid fitted to the scene's direct cut-off).
        rays, seed, threads: paths, random seed, tracer threads (the
            command's defaults when None); the same seed and threads give
            the same alpha and sigma as `stray trace` to the last bit.
        set: scene overrides, {"reflectance": 0.08} is --set reflectance=0.08.
        lens: a lens curve (Curve, path, arrays) or "ideal:DEG": a system
            curve.
        **options: further `stray trace` options (batches=64, ...).

    Returns:
        the Curve (theta_deg, alpha, sigma, columns direct/order1/...,
        meta, summary = the --json run summary).
    """
    lens_file = (_CurveFile(lens, "lens") if lens is not None and
                 not (isinstance(lens, str) and lens.startswith("ideal:"))
                 else None)
    with (lens_file or _Nothing()) as lens_path:
        opts = _lib.options(scene=scene, angles=angles, rays=rays,
                            seed=seed, threads=threads, set=_sets(set),
                            lens=lens_path or lens, **options)
        res = _lib.call("trace", opts)
    summary = res.json or {}
    c = Curve._from_result(res, summary)
    src = c.meta.get("source", "")
    m = re.search(r"(\d+) paths, seed (\d+)", src)
    c.meta.update({
        "scene": scene,
        "overrides": dict(set or {}),
        "seed": int(m.group(2)) if m else seed,
        "rays": int(m.group(1)) if m else rays,
        "threads": summary.get("threads", threads),
        "lens": None if lens is None else
        (lens if isinstance(lens, str) else "array"),
        "version": _lib.VERSION,
    })
    return c


class _Nothing:
    def __enter__(self) -> None:
        return None

    def __exit__(self, *exc: Any) -> None:
        return None


def photometry(sensor: str = "st16-like", **options: Any) -> Dict[str, Any]:
    """Photon fluxes of Sun, Moon, zero-magnitude star, Vega and the
    reference star in the sensor's passband (`stray photometry --json`)."""
    return _lib.call("photometry", _lib.options(sensor=sensor,
                                                **options)).json or {}


def fdr(sensor: str = "st16-like", source: str = "sun",
        rate: Optional[float] = 5, alpha: Optional[float] = None,
        **options: Any) -> Dict[str, Any]:
    """The attenuation alpha_required for `rate` false stars per image,
    and with alpha the rate there (`stray fdr --json`)."""
    return _lib.call("fdr", _lib.options(sensor=sensor, source=source,
                                         rate=rate, alpha=alpha,
                                         **options)).json or {}


def exclusion(curve: CurveLike, sensor: str = "st16-like",
              **options: Any) -> Dict[str, Any]:
    """Sun, Moon (and with earth_albedo, Earth-limb) exclusion angles of a
    system curve (`stray exclusion --json`).  curve: a Curve, a path, or
    (theta_deg, alpha[, sigma]) arrays; an in-memory curve goes to the
    command as the CSV the library writes (%.10g), the file the CLI
    would read."""
    with _CurveFile(curve) as path:
        return _lib.call("exclusion", _lib.options(curve=path, sensor=sensor,
                                                   **options)).json or {}


class Frames:
    """Rendered detector frames and the run's summary.

    Attributes:
        images: uint16 array (frames, rows, cols) over the library's own
            buffer (no copy; freed with the last array that views it).
        summary: the values of `stray frames --json`.
    """

    def __init__(self, images: np.ndarray, summary: Dict[str, Any]):
        self.images = images
        self.summary = summary

    def __repr__(self) -> str:
        return f"<straylight.Frames {self.images.shape}>"


def frames(curve: Optional[CurveLike] = None, theta: Optional[float] = None,
           frames: int = 1, window: Optional[int] = None, seed: int = 1,
           alpha: Optional[float] = None, **options: Any) -> Frames:
    """Detector frames for the Sun at theta off boresight through curve (or
    at the attenuation alpha), star detection and false stars against the
    FDR model (`stray frames`).  window=PX renders a PX x PX window at the
    detector centre (None: the full frame)."""
    cf = _CurveFile(curve) if curve is not None else _Nothing()
    with cf as path:
        res = _lib.call("frames", _lib.options(
            curve=path, theta=theta, alpha=alpha, frames=frames,
            window=window, seed=seed, **options))
    images = res.frames()
    if images is None:
        raise _lib.Error("stray frames: no frames rendered")
    return Frames(images, res.json or {})


def reduce(sweep_dir: Union[PathLike, Sequence[PathLike]],
           **options: Any) -> Tuple[Curve, Dict[str, Any]]:
    """The lens attenuation curve, noise floor and ghosts from a lab
    sweep folder, or several of one lens (`stray reduce`): the curve and
    the --json dict."""
    dirs = ([os.fspath(sweep_dir)] if isinstance(sweep_dir, (str, os.PathLike))
            else [os.fspath(d) for d in sweep_dir])
    out = options.pop("out", None)
    with tempfile.TemporaryDirectory(prefix="straylight-") as tmp:
        res = _lib.call("reduce", _lib.options(
            out=out or os.path.join(tmp, "lens.csv"), **options), args=dirs)
    summary = res.json or {}
    return Curve._from_result(res, summary), summary


def diagnose(measured: CurveLike, scene: str = "ref4",
             **options: Any) -> Dict[str, Any]:
    """What the model of scene gets wrong against a measured curve (with
    sigma): named causes with intervals, the Sun exclusion angle before
    and after, and the curves of the plot (`stray diagnose --json`).
    set={...} overrides the scene; lens= makes it a system diagnosis."""
    overrides = options.pop("set", None)
    lens = options.pop("lens", None)
    with _CurveFile(measured, "measured") as path, \
            (_CurveFile(lens, "lens") if lens is not None and not
             (isinstance(lens, str) and lens.startswith("ideal:"))
             else _Nothing()) as lens_path:
        return _lib.call("diagnose", _lib.options(
            scene=scene, set=_sets(overrides), lens=lens_path or lens,
            **options), args=[path]).json or {}


class Availability(dict):
    """`stray availability --json` as a dict, with the time series.

    Attributes:
        series: structured array, one row per covered frame: t_s, utc
            (datetime64[us]), albedo, per head <h>_flags, <h>_sun_deg,
            <h>_false_stars and the flag bits by name (<h>_sun_excluded,
            ..., bool), any_available (bool).
    """

    series: np.ndarray


def _series(path: str) -> np.ndarray:
    with open(path) as f:
        lines = [ln for ln in f if not ln.startswith("#")]
    raw = np.genfromtxt(lines, delimiter=",", names=True, dtype=None,
                        encoding="utf-8")
    raw = np.atleast_1d(raw)
    fields = []
    for name in raw.dtype.names:
        if name == "utc":
            fields.append((name, "datetime64[us]"))
        elif name == "any_available" or raw.dtype[name].kind in "iu" and \
                not name.endswith("_flags") and not name.endswith("_stars"):
            fields.append((name, "?"))
        elif name.endswith("_flags"):
            fields.append((name, "u1"))
        else:
            fields.append((name, "f8"))
    out = np.empty(raw.shape, dtype=fields)
    for name, kind in fields:
        if name == "utc":
            out[name] = np.array([s.rstrip("Z") for s in raw[name]],
                                 dtype="datetime64[us]")
        else:
            out[name] = raw[name].astype(kind)
    return out


def availability(oem: PathLike, aem: PathLike, heads: PathLike,
                 **options: Any) -> Availability:
    """Availability of several heads along a mission from CCSDS OEM/AEM
    files (`stray availability --json`), with .series (step_s=..., hours=...
    and the command's other options pass through)."""
    out = options.pop("out", None)
    with tempfile.TemporaryDirectory(prefix="straylight-") as tmp:
        csv = out or os.path.join(tmp, "series.csv")
        res = _lib.call("availability", _lib.options(
            oem=oem, aem=aem, heads=heads, out=csv, **options))
        a = Availability(res.json or {})
        a.series = _series(os.fspath(csv))
    return a
