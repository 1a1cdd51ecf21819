"""Tests of studies/archive_tools/."""
