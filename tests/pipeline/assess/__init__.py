"""Tests of pipeline/assess/."""
