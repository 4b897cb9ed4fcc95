"""The partitioning compiler of parallel and free-running mode.
"""
