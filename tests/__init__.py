"""Tests, mirroring the packages: engine/, pipeline/, studies/; reference/ holds the independent
models the engine is checked against; helpers.py what several tests share."""
