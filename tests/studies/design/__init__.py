"""Tests of studies/design/."""
