"""Multi-core plants: plant files, linking shared variables and copy plans, running a plant."""
