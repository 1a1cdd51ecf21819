"""Tests of studies/common/."""
