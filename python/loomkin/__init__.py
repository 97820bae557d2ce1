"""loomkin: motion design for weaving machines, from Python.

The numbers come from the loomkin Rust crates (the same code as the ``loomkin`` command line):
this package only converts arguments and results. Reports are dicts keyed as the CLI's ``--json``
(units in the key names: ``_m``, ``_deg``, ``_nm``, ``_rpm`` …); sampled curves and tables are
dicts of float64 numpy arrays (:class:`Table`, with ``.frame()`` for a pandas DataFrame).

Modules: :mod:`loomkin.laws`, :mod:`loomkin.cycles`, :mod:`loomkin.servo`, :mod:`loomkin.picking`,
:mod:`loomkin.dobby`, :mod:`loomkin.shed`, :mod:`loomkin.loom`, :mod:`loomkin.drive`,
:mod:`loomkin.dynamics`, :mod:`loomkin.cams`, :mod:`loomkin.insertion`.

Sweeps and Monte-Carlo studies take ``shard=(i, n)`` (the CLI's ``--shard I/N``) for a cluster
(Dask, Ray): :func:`concat` joins the shards' tables, and the Monte-Carlo functions' ``from_draws``
makes the report of the unsharded run from them (docs/python.md).

Errors are :class:`LoomkinError` (a ``ValueError``) with ``.field`` and ``.allowed``;
:class:`OutOfRangeError` adds ``.value``, ``.unit``, ``.low``, ``.high``. Long computations release
the GIL.
"""

from ._loomkin import __version__, Cycle, Law, LoomkinError, OutOfRangeError
from ._table import Table, concat
from . import cams, cycles, dobby, drive, dynamics, insertion, laws, loom, picking, servo, shed

__all__ = [
    "__version__",
    "Cycle",
    "Law",
    "LoomkinError",
    "OutOfRangeError",
    "Table",
    "concat",
    "cams",
    "cycles",
    "dobby",
    "drive",
    "dynamics",
    "insertion",
    "laws",
    "loom",
    "picking",
    "servo",
    "shed",
]
