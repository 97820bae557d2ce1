"""Tables as dicts of numpy arrays, with a pandas DataFrame on request."""

from __future__ import annotations

from typing import Any, Mapping


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
