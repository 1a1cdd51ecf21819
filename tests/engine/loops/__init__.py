"""Tests of engine/loops/."""
