"""Small worlds the environment tests share."""


def grid_world(name: str, cells: str) -> str:
    """The text of a world of 0.25 m cells drawn by ``cells`` (a ``[grid]`` map: ``S`` the start,
    ``G`` the goal), its south-west corner at the origin."""
    return f'''\
format = "mazesim-world"
version = 1
name = "{name}"

[floor]
reflectance = 0.36

[grid]
cell_size = 0.25
wall_thickness = 0.01
origin = [0.0, 0.0]
map = """
{cells.strip()}
"""
'''


#: Three cells in a row: the start in the west cell facing east, a barcode checkpoint on the way
#: and the goal in the east cell, so short episodes end at the goal and cross the barcode.
CORRIDOR = grid_world(
    "corridor",
    """
+--+--+--+
|S     G |
+--+--+--+
""",
) + (
    """
[[checkpoints]]
id = 1
code = "10110"
center = [0.25, 0.125]
yaw = 0.0
width = 0.23
"""
)

#: Two rows of three cells, the start in the middle of the south row, the goal in the north-west
#: cell. The true way goes east, up the east column and back west along the north row (4 cells);
#: a robot that has seen only the start cell's walls assumes the short way west then north (2
#: cells) open, and finds the wall north of the south-west cell only when it gets there.
TRAP = grid_world(
    "trap",
    """
+--+--+--+
|G       |
+--+--+  +
|   S    |
+--+--+--+
""",
)


#: The two walls of a straight corridor 1.2 m long and 0.2 m wide, along x through the origin.
CORRIDOR_WALLS = """
[[walls]]
center = [0.0, 0.105]
size = [1.2, 0.01]

[[walls]]
center = [0.0, -0.105]
size = [1.2, 0.01]
"""
