"""Code the project's controllers share: wheel speeds for a forward speed and a turn."""


def wheel_speeds(forward: float, turn: float) -> tuple[float, float]:
    """Left and right wheel speeds (rad/s)."""
    return forward - turn, forward + turn
