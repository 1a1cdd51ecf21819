"""Tests of pipeline/execute/."""
