"""Tests of pipeline/motions/."""
