"""Workflow support: scene validation and grids, job parameters, targets, provenance."""
