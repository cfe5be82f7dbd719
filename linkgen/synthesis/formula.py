"""A formula of x such as ``log10(x)`` or ``x**2 + 3*sin(x)``, read safely (no ``eval``) and evaluated on arrays.

Allowed: numbers, x, pi, e, + - * / ** and parentheses, and the functions in :data:`FUNCTIONS`.
"""
from __future__ import annotations

import ast
import math
import operator
from collections.abc import Callable

import numpy as np

from camgen.core.errors import SpecError

FUNCTIONS: dict[str, Callable[[np.ndarray], np.ndarray]] = {
    "log": np.log, "log10": np.log10, "log2": np.log2, "exp": np.exp, "sqrt": np.sqrt, "abs": np.abs,
    "sin": np.sin, "cos": np.cos, "tan": np.tan, "asin": np.arcsin, "acos": np.arccos, "atan": np.arctan,
    "sinh": np.sinh, "cosh": np.cosh, "tanh": np.tanh}
CONSTANTS = {"pi": math.pi, "e": math.e}
_BINARY = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
           ast.Pow: operator.pow}


def _node(node: ast.AST, x: np.ndarray, field: str) -> np.ndarray:
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
        return np.full(x.shape, float(node.value))
    if isinstance(node, ast.Name) and node.id == "x":
        return x
    if isinstance(node, ast.Name) and node.id in CONSTANTS:
        return np.full(x.shape, CONSTANTS[node.id])
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        return _BINARY[type(node.op)](_node(node.left, x, field), _node(node.right, x, field))
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        value = _node(node.operand, x, field)
        return -value if isinstance(node.op, ast.USub) else value
    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in FUNCTIONS
            and len(node.args) == 1 and not node.keywords):
        return FUNCTIONS[node.func.id](_node(node.args[0], x, field))
    shown = ast.unparse(node) if isinstance(node, ast.expr) else type(node).__name__
    raise SpecError(f"cannot read {shown!r}: a formula of x uses numbers, x, pi, e, + - * / ** and "
                    f"{', '.join(FUNCTIONS)}", field)


def evaluate(text: str, x: np.ndarray, field: str = "task.function") -> np.ndarray:
    """The formula ``text`` at every x; a one-line :class:`SpecError` on ``field`` if it cannot be read or is not a
    finite number at some x."""
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError:
        raise SpecError(f"cannot read {text!r} as a formula of x, e.g. 'log10(x)'", field) from None
    with np.errstate(all="ignore"):
        y = _node(tree.body, np.asarray(x, dtype=float), field)
    bad = ~np.isfinite(y)
    if np.any(bad):
        raise SpecError(f"{text} is not a finite number at x = {float(np.asarray(x)[bad][0]):g}", field)
    return y
