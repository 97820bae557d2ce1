"""Tables as dicts of numpy arrays, with a pandas DataFrame on request."""

from __future__ import annotations

from typing import Any, Iterable, Mapping, Optional, Tuple, Union

#: Shard I of N of a sweep's or study's rows, as the CLI's ``--shard I/N``: ``(I, N)`` or ``"I/N"``.
Shard = Union[Tuple[int, int], str, None]


class Table(dict):
    """Columns of equal length: a dict of column name (with its unit) to numpy array.

    ``frame()`` gives a ``pandas.DataFrame`` with the same columns (pandas must be installed).
    """

    def frame(self) -> Any:
        """The columns as a pandas DataFrame, in the same order."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("Table.frame() needs pandas: pip install pandas") from e
        return pd.DataFrame(dict(self))


def table(columns: Mapping[str, Any]) -> Table:
    """Wraps a dict of columns (as the extension module returns them) as a :class:`Table`."""
    return Table(columns)


def concat(tables: Iterable[Mapping[str, Any]]) -> Table:
    """Tables of the same columns one after the other, as one :class:`Table`: the shards' tables
    of a sweep or a Monte-Carlo study (``shard=(i, n)`` for i = 1 … n, in order) give the table
    of the unsharded call, value for value. Numeric columns are numpy arrays, other columns lists;
    a pandas DataFrame is taken as a table of its columns. Tables without columns are skipped."""
    import numpy as np

    # A table without columns (the rows of an empty shard, when there are more shards than rows)
    # adds nothing.
    tables = [t for t in tables if len(t.keys()) > 0]
    if not tables:
        return Table()
    names = list(tables[0].keys())
    for i, t in enumerate(tables[1:], start=2):
        if list(t.keys()) != names:
            from ._loomkin import LoomkinError

            err = LoomkinError(f"table {i}: its columns ({', '.join(map(str, t.keys()))}) are not table 1's "
                               f"({', '.join(map(str, names))})")
            err.field, err.allowed = "tables", None
            raise err
    out = Table()
    for name in names:
        cols = [t[name] for t in tables]
        if all(isinstance(c, np.ndarray) or hasattr(c, "to_numpy") for c in cols):
            out[name] = np.concatenate([np.asarray(c) for c in cols])
        else:
            out[name] = [x for c in cols for x in c]
    return out


def _draw_tables(from_draws: Optional[Any]) -> Optional[Any]:
    """``from_draws`` as the extension module takes it: paths as they are, each table (a
    :class:`Table`, a dict of columns or a pandas DataFrame) as a dict of float64 arrays."""
    import os

    import numpy as np

    if from_draws is None or isinstance(from_draws, (str, os.PathLike)):
        return from_draws
    one = isinstance(from_draws, Mapping) or hasattr(from_draws, "to_numpy")
    items = [from_draws] if one else list(from_draws)
    return [x if isinstance(x, (str, os.PathLike))
            else {str(k): np.ascontiguousarray(v, dtype=np.float64) for k, v in x.items()} for x in items]


def _summary_texts(from_summaries: Optional[Any]) -> Optional[Any]:
    """``from_summaries`` as the extension module takes it: each summary (a dict, as
    ``summary=True`` returns it) as JSON text, each path as its file's text (one or more
    summaries, as the CLI's ``--summary`` writes them)."""
    import json
    import os

    if from_summaries is None:
        return None
    one = isinstance(from_summaries, (Mapping, str, os.PathLike))
    items = [from_summaries] if one else list(from_summaries)
    out = []
    for x in items:
        if isinstance(x, Mapping):
            out.append(json.dumps(x))
        else:
            with open(os.fspath(x), encoding="utf-8") as f:
                out.append(f.read())
    return out
