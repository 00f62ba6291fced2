"""Validation of drivefem against independent references."""
