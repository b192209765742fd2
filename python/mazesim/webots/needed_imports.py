"""Imports inside ``try`` that a module needs all the same.

A controller's module may import a package inside ``try: ... except ImportError:`` and still
use the names it binds while the module loads: in the annotations of a function a class body
defines (``def forward(self, x: torch.Tensor)``, which Python evaluates when it defines the
function unless the module has ``from __future__ import annotations``), its default values and
decorators, a class's bases, or a statement of the module's or a class's body. Without the
package that module then fails with a ``NameError`` as it loads, in Webots as here, so the
package is needed as much as an import outside ``try``. A name the ``except`` clause binds
again (a stand-in class), and a use the module guards (the branches of ``a if FLAG else b``,
the right of ``and``/``or``, a lambda's body, a statement under ``if``, ``try``, ``with`` or a
loop) do not count: Python evaluates them only when the package is there or not at all.
"""

from __future__ import annotations

import ast
from collections.abc import Iterator

__all__ = ["needed_guarded_imports"]


def _bound_names(statement: ast.Import | ast.ImportFrom) -> set[str]:
    """The names an import statement binds."""
    names = set()
    for alias in statement.names:
        if alias.name == "*":
            continue
        if alias.asname:
            names.add(alias.asname)
        elif isinstance(statement, ast.Import):
            names.add(alias.name.split(".")[0])
        else:
            names.add(alias.name)
    return names


def _rebound(handlers: list[ast.ExceptHandler]) -> set[str]:
    """The names the ``except`` clauses of a ``try`` bind (stand-ins for the imports')."""
    names: set[str] = set()
    for handler in handlers:
        for node in ast.walk(handler):
            if isinstance(node, (ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
                names.add(node.name)
            elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
                names.add(node.id)
            elif isinstance(node, (ast.Import, ast.ImportFrom)):
                names |= _bound_names(node)
    return names


def _loaded(expression: ast.AST | None) -> Iterator[str]:
    """The names an expression surely evaluates (not in a conditional branch or a lambda)."""
    if expression is None:
        return
    if isinstance(expression, ast.Name):
        yield expression.id
        return
    if isinstance(expression, ast.IfExp):
        yield from _loaded(expression.test)
        return
    if isinstance(expression, ast.BoolOp):
        yield from _loaded(expression.values[0])
        return
    if isinstance(expression, ast.Lambda):
        yield from (name for d in expression.args.defaults for name in _loaded(d))
        return
    for child in ast.iter_child_nodes(expression):
        yield from _loaded(child)


def _signature(function: ast.FunctionDef | ast.AsyncFunctionDef, lazy: bool) -> Iterator[ast.AST]:
    """The parts of a function definition Python evaluates when it runs the ``def``."""
    arguments = function.args
    yield from function.decorator_list
    yield from arguments.defaults
    yield from (d for d in arguments.kw_defaults if d is not None)
    if lazy:
        return
    every = [*arguments.posonlyargs, *arguments.args, *arguments.kwonlyargs]
    every += [a for a in (arguments.vararg, arguments.kwarg) if a is not None]
    yield from (a.annotation for a in every if a.annotation is not None)
    if function.returns is not None:
        yield function.returns


def _evaluated(body: list[ast.stmt], lazy: bool) -> Iterator[ast.AST]:
    """The expressions a module's or a class's body evaluates as it runs, surely."""
    for statement in body:
        if isinstance(statement, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield from _signature(statement, lazy)
        elif isinstance(statement, ast.ClassDef):
            yield from statement.decorator_list
            yield from statement.bases
            yield from (k.value for k in statement.keywords)
            yield from _evaluated(statement.body, lazy)
        elif isinstance(statement, (ast.Assign, ast.AugAssign, ast.Expr, ast.Return)):
            yield statement.value  # type: ignore[misc]
        elif isinstance(statement, ast.AnnAssign):
            if statement.value is not None:
                yield statement.value
            if not lazy:
                yield statement.annotation


def needed_guarded_imports(tree: ast.Module) -> list[ast.Import | ast.ImportFrom]:
    """The import statements inside the ``try`` blocks of a module's top level whose names the
    module evaluates as it loads, though the ``except`` clause does not bind them again."""
    lazy = any(
        isinstance(s, ast.ImportFrom)
        and s.module == "__future__"
        and any(a.name == "annotations" for a in s.names)
        for s in tree.body
    )
    guarded: dict[str, ast.Import | ast.ImportFrom] = {}
    for statement in tree.body:
        if not isinstance(statement, ast.Try):
            continue
        stand_ins = _rebound(statement.handlers)
        for inner in statement.body:
            if isinstance(inner, (ast.Import, ast.ImportFrom)):
                for name in _bound_names(inner) - stand_ins:
                    guarded.setdefault(name, inner)
    if not guarded:
        return []
    used = {name for part in _evaluated(tree.body, lazy) for name in _loaded(part)}
    needed = [guarded[name] for name in guarded if name in used]
    return list(dict.fromkeys(needed))
