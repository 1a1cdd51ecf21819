"""Tests of engine/stories/."""
