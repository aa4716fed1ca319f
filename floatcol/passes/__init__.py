"""The renderer's passes, one module each, plain arrays in and out (docs/architecture.md):

- geometry.py   the column pass of one layer (Gordon's floating column, kernels/column.py)
- horizon.py    the line drawing of the floating horizon (method="horizon")
- finish.py     shading and colour of one layer's G-buffer (its material) -> rgba, side
- antialias.py  section 6.4 across columns: the staircases' pass, or sub-columns
- composite.py  several layers merged front to back by depth
"""
