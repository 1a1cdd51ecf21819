"""Tests of engine/impact/laws/."""
