"""Attenuation curves (docs/formats.md) as numpy arrays."""
from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Union

import numpy as np

from . import _lib

PathLike = Union[str, "os.PathLike[str]"]


def _meta_dict(lines: List[str]) -> Dict[str, Any]:
    """'# key: value' comment lines as a dict (other lines are skipped)."""
    meta: Dict[str, Any] = {}
    for line in lines:
        key, sep, value = line.strip().partition(":")
        if sep and key and " " not in key:
            meta[key] = value.strip()
    return meta


class Curve:
    """An attenuation curve: alpha (power ratio, 1 on axis) against the
    source angle theta_deg, with one standard error sigma when known.

    Attributes:
        theta_deg, alpha: float64 arrays, angles strictly increasing.
        sigma: float64 array, or None for a curve without a sigma column.
        columns: the further named columns (direct, order1, noise_floor...).
        meta: dict of the curve's metadata ('# key: value' lines; for a
            trace also scene, overrides, seed, rays, threads, lens, version).
        summary: the command's --json output (trace), else {}.
    """

    def __init__(self, theta_deg: Any, alpha: Any, sigma: Any = None,
                 columns: Optional[Dict[str, Any]] = None,
                 meta: Optional[Dict[str, Any]] = None,
                 lines: Optional[List[str]] = None,
                 summary: Optional[Dict[str, Any]] = None):
        self.theta_deg = np.asarray(theta_deg, dtype=np.float64)
        self.alpha = np.asarray(alpha, dtype=np.float64)
        self.sigma = (None if sigma is None
                      else np.asarray(sigma, dtype=np.float64))
        self.columns = {k: np.asarray(v, dtype=np.float64)
                        for k, v in (columns or {}).items()}
        self.meta: Dict[str, Any] = dict(meta or {})
        self.summary: Dict[str, Any] = dict(summary or {})
        # the comment lines as the library wrote or read them, for to_csv
        self._lines: List[str] = list(lines) if lines is not None else [
            f" {k}: {v}" for k, v in self.meta.items()
            if isinstance(v, str) and k not in ("command", "version")]

    @classmethod
    def _from_result(cls, res: "_lib.Result",
                     summary: Optional[Dict[str, Any]] = None) -> "Curve":
        got = res.curve()
        if got is None:
            raise _lib.Error("the command wrote no curve")
        cols, lines = got
        theta = cols.pop("theta_deg")
        alpha = cols.pop("alpha")
        sigma = cols.pop("sigma", None)
        c = cls(theta, alpha, sigma, cols, _meta_dict(lines), lines, summary)
        if res.command:
            c.meta["command"] = res.command
        return c

    def __len__(self) -> int:
        return len(self.theta_deg)

    def __repr__(self) -> str:
        kind = self.meta.get("kind", "curve")
        return (f"<straylight.Curve {kind}: {len(self)} angles "
                f"{self.theta_deg[0]:g}..{self.theta_deg[-1]:g} deg>"
                if len(self) else "<straylight.Curve empty>")

    def to_csv(self, path: PathLike) -> None:
        """Write the curve CSV (docs/formats.md) with the library's writer,
        as `stray trace --out` writes it (%.10g, the same comment lines; the
        command line is the call's)."""
        cols: Dict[str, np.ndarray] = {"theta_deg": self.theta_deg,
                                       "alpha": self.alpha}
        if self.sigma is not None:
            cols["sigma"] = self.sigma
        cols.update(self.columns)
        _lib.curve_write(os.fspath(path), str(self.meta.get("command", "")),
                         cols, self._lines)


def read_curve(path: PathLike) -> Curve:
    """Load a curve CSV (docs/formats.md) with the reader `stray` uses;
    a malformed file raises InputError with its message (file, line,
    column, value)."""
    return Curve._from_result(_lib.curve_read(os.fspath(path)))
