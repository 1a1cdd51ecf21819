"""Tests of engine/impact/."""
