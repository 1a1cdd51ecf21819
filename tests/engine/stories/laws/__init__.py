"""Tests of engine/stories/laws/."""
