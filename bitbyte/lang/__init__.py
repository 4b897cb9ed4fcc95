"""The language layer: the one definition, the program model, parser, errors, build configuration, cost model, stimulus and trace formats. Imports nothing above it."""
