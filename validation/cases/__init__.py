"""Validation case modules (discovered automatically by :func:`validation.registry.load_all`)."""
