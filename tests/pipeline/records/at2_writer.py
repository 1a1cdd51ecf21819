"""AT2 files written for the record layer's tests: PEER's header lines, values as PEER prints
them, a whole file."""
import numpy as np

NGA_HEAD = ("PEER NGA STRONG MOTION DATABASE RECORD",
            "Kobe Japan, 1/16/1995, KJMA, 0",
            "ACCELERATION TIME SERIES IN UNITS OF G")


OLD_HEAD = ("PEER STRONG MOTION DATABASE RECORD. PROCESSING BY DWP.",
            "NORTHRIDGE, 1/17/94 12:31, SYLMAR-CONVERTER STA, 142 (DWP STATION 74)",
            "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=unknown LP=unknown")


def at2_tokens(n, seed=0):
    """PEER-style text values ('-.1416764E-03') and the floats they denote, in g."""
    values = np.random.default_rng(seed).normal(scale=0.2, size=n)
    text = [f"{v:.7E}".replace("0.", ".", 1) for v in values]
    return text, np.array([float(t) for t in text])


def write_at2(path, head, count_line, tokens, per_line=5, newline="\n", trailing=""):
    """An AT2 file at `path`: the header lines, the count line, `per_line` values a row."""
    rows = ["".join(f"{t:>15}" for t in tokens[i:i + per_line])
            for i in range(0, len(tokens), per_line)]
    lines = [*head, count_line + trailing, *rows]
    path.write_bytes((newline.join(lines) + newline).encode())
    return path


def simple_at2(tmp_path, count_line="NPTS=     12, DT=   .0100 SEC,", tokens=None, name="bad.AT2",
               head=NGA_HEAD):
    """A 12-value AT2 file in tmp_path (a count line or values to spoil)."""
    tokens = at2_tokens(12)[0] if tokens is None else tokens
    return write_at2(tmp_path / name, head, count_line, tokens)

