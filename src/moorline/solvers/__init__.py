"""Analyses: each takes a mesh (and a state where needed) and returns a result object."""
