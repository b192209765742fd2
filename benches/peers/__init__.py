"""Peers of mazesim for `benches/bench_vs_peers.py`: the canonical workload written by hand.

``workload`` holds what the three runners share (the mazes, the e-puck, the lookup tables and
the Braitenberg rule); ``numpy_peer`` and ``pymunk_peer`` are the two alternatives a Python user
could pick instead of mazesim.
"""
