"""The scouts' speeds (rad/s), by the name their controllerArgs give."""

SPEEDS = {"fast": 5.0, "slow": 2.0}
