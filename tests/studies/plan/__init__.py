"""Tests of studies/plan/."""
