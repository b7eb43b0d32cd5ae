# SPDX-License-Identifier: MIT
"""What a render or a set of incidence-plane curves shows: a measured table,
or a model at parameters (a fit result carries both)."""

from .errors import InvalidArgumentError, Status
from .models import resolve
from .table import Table

_BAD = Status.INVALID_ARGUMENT


def shading_source(source, params):
    """(table, None, None) for a Table, else (None, Model, C params) for a
    model (name, id or Model) with params, or for a FitResult alone."""
    if isinstance(source, Table):
        if params is not None:
            raise InvalidArgumentError(
                _BAD, "params: given with a Table (a table is drawn as measured)")
        return source, None, None
    if params is None and hasattr(source, "model") and hasattr(source, "params"):
        source, params = source.model, source.params
    if params is None:
        raise InvalidArgumentError(
            _BAD, f"{source!r}: a model needs params (or pass a Table, or a fit result)")
    m, _, cp = resolve(source, params)
    return None, m, cp
