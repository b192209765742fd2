"""Pictures of a running world, with numpy and matplotlib alone (no gymnasium): the top-down
frame (:mod:`mazesim.render.topdown`) that envs, videos and the live view draw, and the live
window (:mod:`mazesim.render.live`) that shows frames as a run goes."""
