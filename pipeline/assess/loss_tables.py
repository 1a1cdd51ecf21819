"""The tables pelicun reads that FEMA P-58's database does not hold, for
pipeline.assess.loss: the irreparable-drift fragility with pelicun's irreparable placeholder,
and the building's replacement consequence. Pure functions returning DataFrames in pelicun's
columns (pandas imported when called).

Units: drift ratios 1, costs in USD of 2011, times in worker-days.
"""
from __future__ import annotations


def fragilities(median: float, beta: float):
    """The irreparable-drift fragility (lognormal in the residual drift ratio: median, beta)
    and the irreparable placeholder (a DataFrame in pelicun's damage-model columns)."""
    import pandas as pd

    rows = {
        "excessiveRID": ["Residual Interstory Drift Ratio", "unitless", "lognormal",
                         median, beta],
        "irreparable": ["One", "unitless", None, 1e10, None],
    }
    columns = pd.MultiIndex.from_tuples([("Demand", "Type"), ("Demand", "Unit"),
                                         ("LS1", "Family"), ("LS1", "Theta_0"),
                                         ("LS1", "Theta_1")])
    table = pd.DataFrame.from_dict(rows, orient="index")
    table.columns = columns
    table[("Demand", "Directional")] = 1
    table[("Demand", "Offset")] = 0
    table["Incomplete"] = 0
    return table


def replacement(cost: float, time: float):
    """The replacement consequence (a DataFrame in pelicun's loss-model columns): the
    building's cost (USD 2011) and time (worker-days), without dispersion."""
    import pandas as pd

    index = pd.MultiIndex.from_tuples([("replacement", "Cost"), ("replacement", "Time")])
    return pd.DataFrame({("Quantity", "Unit"): ["1 EA", "1 EA"],
                         ("DV", "Unit"): ["USD_2011", "worker_day"],
                         ("DS1", "Theta_0"): [cost, time]}, index=index)
