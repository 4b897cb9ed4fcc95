"""The wide bit engine (issue 18): stretches, LUT mapping."""
