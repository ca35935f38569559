"""Messages from a plan worker to its parent, in a form the parent can read without trusting the sender.

The parent never unpickles what a worker sends: a hostile plan can reach the worker's end of the pipe and
write anything to it, and unpickling runs code. A message is instead one byte string:

    8-byte little-endian header length | JSON header | raw array bytes ...

The header is a JSON object; `{"__array__": k}` anywhere in it stands for the k-th array, described in the
header's "arrays" list by dtype (numeric and bool only, never object), shape and byte length. Decoding
checks every length and rebuilds arrays with `np.frombuffer`, so a forged message is at worst a wrong
value or a `WireError`, never code running in the parent.
"""

from __future__ import annotations

import json
import math
import struct
from typing import Any

import numpy as np

_LEN = struct.Struct("<Q")
_DTYPES = frozenset({"bool", "uint8", "int8", "uint16", "int16", "uint32", "int32", "uint64", "int64",
                     "float16", "float32", "float64"})
MAX_HEADER_BYTES = 64 << 20
MAX_ARRAY_DIMS = 8


class WireError(ValueError):
    """A message from the worker that does not follow the format."""


def encode(obj: Any) -> bytes:
    """`obj`: JSON-like data (dict/list/tuple/str/int/float/bool/None) with numpy arrays anywhere."""
    arrays: list[np.ndarray] = []

    def walk(x: Any) -> Any:
        if isinstance(x, np.ndarray):
            a = np.ascontiguousarray(x)
            if a.dtype.name not in _DTYPES:
                raise TypeError(f"arrays of dtype {a.dtype} cannot be sent")
            arrays.append(a)
            return {"__array__": len(arrays) - 1}
        if isinstance(x, dict):
            return {str(k): walk(v) for k, v in x.items()}
        if isinstance(x, (list, tuple)):
            return [walk(v) for v in x]
        if isinstance(x, np.generic):
            return x.item()
        if x is None or isinstance(x, (str, bool, int, float)):
            return x
        raise TypeError(f"cannot send a {type(x).__name__}")

    body = walk(obj)
    meta = [{"dtype": a.dtype.name, "shape": list(a.shape), "nbytes": int(a.nbytes)} for a in arrays]
    header = json.dumps({"body": body, "arrays": meta}, allow_nan=True).encode()
    return b"".join([_LEN.pack(len(header)), header, *(a.tobytes() for a in arrays)])


def decode(data: bytes) -> Any:
    """The inverse of `encode`, for bytes that anyone may have written; raises WireError."""
    view = memoryview(data)
    if len(view) < _LEN.size:
        raise WireError("message shorter than its length field")
    (n,) = _LEN.unpack(view[:_LEN.size])
    if n > MAX_HEADER_BYTES or _LEN.size + n > len(view):
        raise WireError("header length out of range")
    try:
        header = json.loads(bytes(view[_LEN.size:_LEN.size + n]))
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError) as e:
        raise WireError(f"header is not JSON: {e}") from None
    if not isinstance(header, dict) or not isinstance(header.get("arrays"), list):
        raise WireError("header has no array list")
    arrays, offset = [], _LEN.size + n
    for meta in header["arrays"]:
        arrays.append(_array(meta, view, offset))
        offset += meta["nbytes"]
    if offset != len(view):
        raise WireError("message length does not match its arrays")

    def walk(x: Any, depth: int = 0) -> Any:
        if depth > 200:
            raise WireError("message nested too deeply")
        if isinstance(x, dict):
            if set(x) == {"__array__"}:
                k = x["__array__"]
                if not isinstance(k, int) or isinstance(k, bool) or not 0 <= k < len(arrays):
                    raise WireError("bad array reference")
                return arrays[k]
            return {k: walk(v, depth + 1) for k, v in x.items()}
        if isinstance(x, list):
            return [walk(v, depth + 1) for v in x]
        return x

    return walk(header.get("body"))


def _array(meta: Any, view: memoryview, offset: int) -> np.ndarray:
    if not isinstance(meta, dict) or meta.get("dtype") not in _DTYPES:
        raise WireError("array of a type that is not allowed")
    shape, nbytes = meta.get("shape"), meta.get("nbytes")
    if (not isinstance(shape, list) or len(shape) > MAX_ARRAY_DIMS
            or not all(isinstance(d, int) and not isinstance(d, bool) and d >= 0 for d in shape)
            or not isinstance(nbytes, int) or nbytes < 0):
        raise WireError("bad array shape")
    dtype = np.dtype(meta["dtype"])
    if math.prod(shape) * dtype.itemsize != nbytes or offset + nbytes > len(view):
        raise WireError("array size does not match its shape")
    return np.frombuffer(view[offset:offset + nbytes], dtype=dtype).reshape(shape).copy()
