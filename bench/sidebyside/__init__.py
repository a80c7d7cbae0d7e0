"""bench/side_by_side.py in modules by concern (its docstring lists them)."""
