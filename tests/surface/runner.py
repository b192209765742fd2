"""Runs plans of hostile calls (``python -m surface.runner PLANS.json``, from ``tests/``) under
a 4 GiB address-space cap, and prints one line per call saying how it ended. Before each call
it prints which one it is about to make, so that an abort or a hang names its call. Each call
has a watchdog that presses Ctrl-C after :data:`CALL_LIMIT` seconds: long work that Ctrl-C stops
is allowed (asking for 2**70 steps is not a bug); a call that ignores Ctrl-C is caught by the
caller's time limit."""

from __future__ import annotations

import contextlib
import importlib
import io
import json
import os
import resource
import signal
import sys
import tempfile
import threading
from pathlib import Path
from typing import Any

CALL_LIMIT = 2.0
ADDRESS_SPACE_CAP = 4 << 30


def _target(path: str, instance: str | None, world: Any, tmp: Path) -> Any:
    import mazesim

    module_name, _, qualname = path.partition(":")
    if instance is not None and instance.startswith("auto:"):
        from surface.values import sample_instance

        module, _, name = instance[len("auto:") :].rpartition(".")
        owner = sample_instance(getattr(importlib.import_module(module), name), world, tmp)
        return getattr(owner, qualname.split(".", 1)[1])
    if instance is not None:
        owner = eval(instance, {"mazesim": mazesim, "world": world, "tmp": tmp})  # noqa: S307
        return getattr(owner, qualname.split(".", 1)[1])
    obj: Any = importlib.import_module(module_name)
    for part in qualname.split("."):
        obj = getattr(obj, part)
    return obj


def _allowed(error: BaseException) -> bool:
    import mazesim

    if isinstance(error, mazesim.MazesimError):
        return True
    try:
        import gymnasium.error

        return isinstance(error, gymnasium.error.Error)
    except ImportError:
        return False


def run_one(plan: dict[str, Any], world: Any, tmp: Path) -> dict[str, Any]:
    """Makes one call of the plan; says how it ended, how many characters it printed and how
    long its error's message was. A command's standard output is its product (a study's JSON,
    a controller's lines), as long as the result it reports: what it printed is counted on its
    standard error, where its messages go."""
    out, err = io.StringIO(), io.StringIO()
    outcome = _run_one(plan, world, tmp, out, err)
    product = 0 if plan["path"].startswith("cli:") else len(out.getvalue())
    outcome["printed"] = product + len(err.getvalue())
    return outcome


def _run_one(
    plan: dict[str, Any], world: Any, tmp: Path, out: io.StringIO, err: io.StringIO
) -> dict[str, Any]:
    from surface.values import make, word

    timer = threading.Timer(CALL_LIMIT, os.kill, (os.getpid(), signal.SIGINT))
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            if plan["path"].startswith("cli:"):
                from mazesim.cli import main

                argv = [w if not w.startswith("=") else word(w[1:], tmp) for w in plan["argv"]]
                timer.start()
                code = main(argv)
                timer.cancel()
                text = err.getvalue()
                if "internal error" in text or code not in (0, 1, 2, 130):
                    return {"how": "escaped", "what": f"exit {code}: {text[-600:]}"}
                return {"how": "ended", "what": f"exit {code}"}
            target = _target(plan["path"], plan["instance"], world, tmp)
            args = {name: make(key, tmp) for name, key in plan["args"].items()}
            positional = [args.pop(name) for name in plan["positional"] if name in args]
            positional += [make(key, tmp) for key in plan.get("more", [])]
            timer.start()
            target(*positional, **args)
            timer.cancel()
            return {"how": "ended", "what": "returned"}
    except KeyboardInterrupt:
        return {"how": "ended", "what": "stopped by Ctrl-C after the call limit"}
    except SystemExit as stop:
        # A command's main(argv) ends as a command does; nothing else may end the process.
        ok = plan["path"].endswith(":main") and stop.code in (0, 1, 2, 130)
        return {"how": "ended" if ok else "escaped", "what": f"SystemExit({stop.code})"}
    except BaseException as error:  # noqa: BLE001 - any other exception is the finding
        how = "refused" if _allowed(error) else "escaped"
        try:
            whole = str(error)
        except Exception as unreadable:  # noqa: BLE001 - an error whose message fails is a finding
            how, whole = "escaped", f"(its message raised {type(unreadable).__name__})"
        what = f"{type(error).__module__}.{type(error).__name__}: {whole[:300]}"
        return {"how": how, "what": what, "message": len(whole)}
    finally:
        timer.cancel()


def _import_ahead() -> None:
    """Imports every module of the package, and matplotlib's pyplot, before the first call.

    The package imports some modules (and matplotlib) only when a call needs them. A first
    import that takes longer than :data:`CALL_LIMIT` (a loaded machine) would be cut by the
    watchdog's Ctrl-C half way, leaving a half-made module behind that fails every later call
    with an error of its own (matplotlib's ``KeyError: 'Text:kwdoc'``): a finding of the
    walk, not of the package. Modules whose optional dependencies are missing are skipped."""
    import pkgutil

    import mazesim

    os.environ.setdefault("MPLBACKEND", "Agg")
    names = ["matplotlib.pyplot"]
    modules = pkgutil.walk_packages(mazesim.__path__, "mazesim.", onerror=lambda _name: None)
    names += [m.name for m in modules if not m.name.endswith("__main__")]
    for name in names:
        with contextlib.suppress(Exception):
            importlib.import_module(name)


def main() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE_CAP, ADDRESS_SPACE_CAP))
    plans = json.loads(Path(sys.argv[1]).read_text(encoding="utf-8"))
    _import_ahead()
    import mazesim

    world = mazesim.World.builtin("seed-maze")
    with tempfile.TemporaryDirectory() as scratch:
        tmp = Path(scratch)
        os.chdir(tmp)
        for index, plan in enumerate(plans):
            print(f"CALL {index}", flush=True)
            outcome = run_one(plan, world, tmp)
            print("RESULT " + json.dumps({"index": index, **outcome}), flush=True)
        os.chdir("/")
    print("ALL DONE", flush=True)


if __name__ == "__main__":
    main()
