"""The type aliases of mechcli's annotations, in one place.

Pure typing: imports nothing of mechcli and costs nothing at run time beyond
``typing`` (the modules that use the aliases import them under
``from __future__ import annotations``, so annotations are never evaluated,
except a record's field types, which ``dataclasses`` keeps as strings).
"""

from __future__ import annotations

from typing import Callable, Union

import numpy as np

__all__ = ["Array", "ArrayFunc", "BoolArray", "FloatOrArray", "IntArray"]

#: an array of floats (numpy's ``float64``)
Array = np.ndarray
#: an array of booleans (a mask)
BoolArray = np.ndarray
#: an array of integers (indices)
IntArray = np.ndarray
#: a length, angle or other value, or an array of them (broadcast together)
FloatOrArray = Union[float, np.ndarray]
#: a vectorised function of one variable: values at the array of inputs
ArrayFunc = Callable[[np.ndarray], np.ndarray]
