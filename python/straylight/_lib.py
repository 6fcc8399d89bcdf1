"""The C side: libstraycmd (tools/include/tools/api.h) through ctypes.

Every call runs one `stray` command in this process (its own code, so
the numbers and messages are the CLI's).  ctypes releases the GIL for
the whole foreign call, so other Python threads run meanwhile.  From the
main thread the call runs in a helper thread while the main thread
waits in short joins: a Ctrl-C then raises KeyboardInterrupt there, the
library's cancel flag stops the trace or the frames (within a second), and the
KeyboardInterrupt is raised once the call has returned.
"""
from __future__ import annotations

import ctypes
import json
import os
import threading
import warnings
from ctypes import (POINTER, byref, c_char_p, c_double, c_int, c_size_t,
                    c_uint16, c_void_p)
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple

import numpy as np


class Error(Exception):
    """A straylight call failed (what `stray` exits 1 for)."""


class InputError(Error, ValueError):
    """Bad input (what `stray` exits 2 for); the message is the line
    `stray` prints on stderr."""


class StrayWarning(UserWarning):
    """A note `stray` prints on stderr beside its result and goes on (a
    scene put right, a body not excluded within the curve, a partial
    sweep): raised as a warning, the result still returned."""


def _load() -> ctypes.CDLL:
    here = Path(__file__).resolve().parent / "_lib"
    path = os.environ.get("STRAYLIGHT_LIB")  # a build's own, for tests
    if not path:
        path = str(here / "libstraycmd.so.0")
    return ctypes.CDLL(path)


_L = _load()


def _fn(name: str, res, args) -> Any:
    f = getattr(_L, name)
    f.restype = res
    f.argtypes = args
    return f


_run = _fn("stray_api_run", c_int, [c_char_p, c_char_p, POINTER(c_void_p)])
_json = _fn("stray_api_json", c_char_p, [c_void_p])
_error = _fn("stray_api_error", c_char_p, [c_void_p])
_command = _fn("stray_api_command", c_char_p, [c_void_p])
_notes = _fn("stray_api_notes", c_char_p, [c_void_p])
_rows = _fn("stray_api_curve_rows", c_size_t, [c_void_p])
_ncols = _fn("stray_api_curve_columns", c_size_t, [c_void_p])
_colname = _fn("stray_api_curve_name", c_char_p, [c_void_p, c_size_t])
_column = _fn("stray_api_curve_column", POINTER(c_double),
              [c_void_p, c_size_t])
_nmeta = _fn("stray_api_curve_n_meta", c_size_t, [c_void_p])
_meta = _fn("stray_api_curve_meta", c_char_p, [c_void_p, c_size_t])
_frames_take = _fn("stray_api_frames_take", POINTER(c_uint16),
                   [c_void_p, POINTER(c_size_t), POINTER(c_int),
                    POINTER(c_int)])
_free = _fn("stray_api_free", None, [c_void_p])
_result_free = _fn("stray_api_result_free", None, [c_void_p])
_curve_read = _fn("stray_api_curve_read", c_int, [c_char_p, POINTER(c_void_p)])
_curve_write = _fn("stray_api_curve_write", c_int,
                   [c_char_p, c_char_p, c_size_t, c_size_t,
                    POINTER(c_char_p), POINTER(POINTER(c_double)), c_size_t,
                    POINTER(c_char_p), POINTER(c_void_p)])
_cancel = _fn("stray_api_cancel", None, [c_int])
_version = _fn("stray_api_version", c_char_p, [])

VERSION: str = _version().decode()


def _text(b: Optional[bytes]) -> str:
    return b.decode("utf-8", "replace") if b else ""


class Result:
    """One call's result; frees the C side when collected."""

    def __init__(self, handle: c_void_p, rc: int):
        self.handle = handle
        self.rc = rc

    def __del__(self):
        if self.handle:
            _result_free(self.handle)
            self.handle = None

    @property
    def json(self) -> Optional[Dict[str, Any]]:
        t = _json(self.handle)
        return json.loads(t) if t else None

    @property
    def error(self) -> str:
        return _text(_error(self.handle))

    @property
    def notes(self) -> List[str]:
        return _text(_notes(self.handle)).splitlines()

    @property
    def command(self) -> str:
        return _text(_command(self.handle))

    def check(self) -> "Result":
        if self.rc == 2:
            raise InputError(self.error)
        if self.rc != 0:
            raise Error(self.error or "failed")
        return self

    def curve(self) -> Optional[Tuple[Dict[str, np.ndarray], List[str]]]:
        """The curve's columns (copies) and comment lines, or None."""
        n = _rows(self.handle)
        if n == 0:
            return None
        cols = {}
        for k in range(_ncols(self.handle)):
            name = _text(_colname(self.handle, k))
            cols[name] = np.ctypeslib.as_array(_column(self.handle, k),
                                               shape=(n,)).copy()
        lines = [_text(_meta(self.handle, i))
                 for i in range(_nmeta(self.handle))]
        return cols, lines

    def frames(self) -> Optional[np.ndarray]:
        """The rendered frames as a (frames, rows, cols) uint16 array over
        the library's own buffer (no copy), freed with the array."""
        n, rows, cols = c_size_t(), c_int(), c_int()
        p = _frames_take(self.handle, byref(n), byref(rows), byref(cols))
        if not p:
            return None
        shape = (n.value, rows.value, cols.value)
        owner = _Owned.wrap(ctypes.cast(p, c_void_p).value,
                            int(np.prod(shape)))
        return np.frombuffer(owner, dtype=np.uint16).reshape(shape)


class _Owned:
    """A C buffer of uint16 that numpy views; freed by the library's free
    when the last array over it is gone."""

    @staticmethod
    def wrap(address: int, count: int):
        base = c_uint16 * count

        class Buffer(base):  # type: ignore[valid-type, misc]
            def __del__(self):
                _free(address)

        return Buffer.from_address(address)


def _opt_text(v: Any) -> Any:
    """A Python value as option text ('%r' of a float reads back to the
    same double); True a flag; lists repeat the option."""
    if v is None or v is False or v is True:
        return v
    if isinstance(v, (list, tuple)):
        return [_opt_text(x) for x in v]
    if isinstance(v, float):
        return repr(v)
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, np.floating):
        return repr(float(v))
    return os.fspath(v) if isinstance(v, os.PathLike) else str(v)


def options(**kw: Any) -> Dict[str, Any]:
    """Keyword arguments as the command's long options (mag_max -> mag-max)."""
    out: Dict[str, Any] = {}
    for k, v in kw.items():
        if v is None or v is False:
            continue
        out[k.replace("_", "-")] = _opt_text(v)
    return out


def call(cmd: str, opts: Dict[str, Any],
         args: Optional[List[str]] = None) -> Result:
    """Run `stray --json <cmd>` with opts in this process; raise on failure."""
    payload = dict(opts)
    if args:
        payload["args"] = [_opt_text(a) for a in args]
    text = json.dumps(payload).encode()
    handle = c_void_p()
    box: Dict[str, int] = {}
    done = threading.Event()

    def work() -> None:
        try:
            box["rc"] = _run(cmd.encode(), text, byref(handle))
        finally:
            done.set()

    if threading.current_thread() is not threading.main_thread():
        work()
    else:
        # An Event, not Thread.join: before Python 3.13 a join interrupted
        # by Ctrl-C marks the thread finished while it still runs.
        threading.Thread(target=work, name="straylight-" + cmd,
                         daemon=True).start()
        try:
            while not done.wait(0.05):
                pass
        except KeyboardInterrupt:
            # the call clears the flag when it starts: set it until done
            _cancel(1)
            while not done.wait(0.05):
                _cancel(1)
            if handle:
                _result_free(handle)
            raise
    result = Result(handle, box["rc"])
    for line in result.notes:
        # stacklevel 3: the user's line that called straylight.<cmd>
        warnings.warn(line, StrayWarning, stacklevel=3)
    return result.check()


def curve_read(path: str) -> Result:
    handle = c_void_p()
    rc = _curve_read(os.fsencode(os.fspath(path)), byref(handle))
    return Result(handle, rc).check()


def curve_write(path: str, command: str, columns: Dict[str, np.ndarray],
                lines: List[str]) -> None:
    names = list(columns)
    arrays = [np.ascontiguousarray(columns[k], dtype=np.float64)
              for k in names]
    n = len(arrays[0])
    if any(len(a) != n for a in arrays):
        raise InputError(f"{path}: columns of different lengths")
    c_names = (c_char_p * len(names))(*[k.encode() for k in names])
    c_cols = (POINTER(c_double) * len(names))(
        *[a.ctypes.data_as(POINTER(c_double)) for a in arrays])
    c_meta = (c_char_p * max(1, len(lines)))(
        *[m.encode() for m in lines] or [None])
    handle = c_void_p()
    rc = _curve_write(os.fsencode(os.fspath(path)), command.encode(), n,
                      len(names), c_names, c_cols, len(lines), c_meta,
                      byref(handle))
    Result(handle, rc).check()
