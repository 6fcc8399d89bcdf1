"""straylight: star-tracker stray light from Python.

Every function runs the same library code as the `stray` command (the
C calls of libstraycmd, tools/include/tools/api.h): the same inputs, seed
and threads give the same numbers to the last bit, the dicts hold the
values of the command's ``--json`` output, and bad input raises
:class:`InputError` with the line ``stray`` prints; a note ``stray``
prints beside its result (a body not excluded within the curve, a
partial sweep) is a :class:`StrayWarning`.  Long calls release
the GIL; Ctrl-C stops a long trace or frames within a second.  See docs/python.md.

>>> import straylight as sl
>>> c = sl.trace("ref4", angles="0:30:5,30:90:0.5", rays=200_000, seed=1)
>>> sl.exclusion(c)["sun_deg"]
"""
from ._lib import VERSION as _VERSION, Error, InputError, StrayWarning
from .api import (Availability, Frames, availability, diagnose, exclusion,
                  fdr, frames, photometry, reduce, trace)
from .curve import Curve, read_curve

__version__: str = _VERSION
"""The library's version, as `stray --version` prints it after "stray "."""

__all__ = ["__version__", "Error", "InputError", "StrayWarning", "Curve",
           "read_curve",
           "trace", "photometry", "fdr", "exclusion", "frames", "Frames",
           "reduce", "diagnose", "availability", "Availability"]
