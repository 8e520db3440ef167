"""Verification cases and independent exact reference solutions for moorline."""
