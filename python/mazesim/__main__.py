"""Runs the ``mazesim`` command line: ``python -m mazesim``."""

from mazesim.cli import main

raise SystemExit(main())
