"""Small worlds the environment tests share."""

#: Three cells in a row: the start in the west cell facing east, a barcode checkpoint on the way
#: and the goal in the east cell, so short episodes end at the goal and cross the barcode.
CORRIDOR = """\
format = "mazesim-world"
version = 1
name = "corridor"

[floor]
reflectance = 0.36

[grid]
cell_size = 0.25
wall_thickness = 0.01
origin = [0.0, 0.0]
map = \"\"\"
+--+--+--+
|S     G |
+--+--+--+
\"\"\"

[[checkpoints]]
id = 1
code = "10110"
center = [0.25, 0.125]
yaw = 0.0
width = 0.23
"""
