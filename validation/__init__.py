"""Validation against measured friction: datasets, comparison, diagnosis of missing effects, reports."""

from .errors import InputError

__all__ = ["InputError"]
