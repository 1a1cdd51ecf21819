"""Eq. 9 re-derived: the impact damping coefficient C_imp by energy equilibrium (section 3.2).

For every (COR, m_eff, v_imp) of a grid, a1 in C_imp = a1 (1 - COR^2) (Eq. 8) is found such
that the hysteresis area of a two-body impact through a rubber bumper equals the kinetic energy
loss of Eq. 5; then C_imp = c0 (1 - COR^2) / (COR^p1 m_eff^p2 v_imp^p3) is fitted in log space
and set beside the paper's c0 = 1.55, p1 = 0.7076, p2 = 0.0025, p3 = 0.9755 (read from the
bumper law, engine.impact.laws.rubber_bumper.EQ9_*). The numerics (batched bisection, least
squares) live in engine.damping_fit; this recipe only chooses the grid and the bumper, labels
the results and draws them.
"""
from __future__ import annotations

import numpy as np

from engine.impact.laws.rubber_bumper import (
    EQ9_COEFFICIENT,
    EQ9_COR_EXPONENT,
    EQ9_MASS_EXPONENT,
    EQ9_VELOCITY_EXPONENT,
)

from .common.plot import letter_panels, plt, short_title, store_caption
from .common.recipe import Recipe, Verdict

# One large pad of the paper's rubber (K_r 55,835 kN/m^2, n 2.65, alpha 2.25), thick enough
# that the heaviest, fastest impact of the grid (320 t at 4 m/s) stays below delta_u.
BUMPER = dict(thickness=0.20, area=1.0, strain=1.0, n_bumpers=1)
# Eq. 9's constants, as the bumper law declares them.
PAPER = {"c0": EQ9_COEFFICIENT, "p1": EQ9_COR_EXPONENT, "p2": EQ9_MASS_EXPONENT,
         "p3": EQ9_VELOCITY_EXPONENT}
# Agreement bands for the paper check.
TOLERANCE = {"c0": 0.10, "p1": 0.10, "p2": 0.01, "p3": 0.05}


def grid(quick: bool) -> dict[str, np.ndarray]:
    """COR 0.3-0.9, m_eff 10 kg - 320 t (geometric), v_imp 0.5-4 m/s (geometric)."""
    if quick:
        return {"cor": np.array([0.3, 0.6, 0.9]), "m_eff": np.array([10.0, 320e3]),
                "v_imp": np.array([0.5, 4.0])}
    return {"cor": np.round(np.arange(0.3, 0.91, 0.1), 2), "m_eff": np.geomspace(10, 320e3, 6),
            "v_imp": np.geomspace(0.5, 4.0, 7)}


def compute(args):
    from engine import damping_fit
    from engine.impact.laws import rubber_bumper
    from engine.units import power_law_units
    from pipeline.archive import labelled_dataset, variable
    from pipeline.provenance import two_body_attributes

    axes = grid(args.quick)
    shape = tuple(len(a) for a in axes.values())
    cor, m_eff, v = (a.ravel() for a in np.meshgrid(*axes.values(), indexing="ij"))
    found = damping_fit.find_a1(cor, m_eff, v, BUMPER, rtol=1e-4 if args.quick else 1e-6)
    fit = damping_fit.fit_power_law(cor, m_eff, v, found.c_imp)
    c_fit = fit.c_imp(cor, m_eff, v)
    c_eq9 = damping_fit.power_law_c_imp(cor, m_eff, v, **PAPER)
    with_fit, contact = damping_fit.impact(cor, m_eff, v, c_fit, BUMPER)
    with_eq9, _ = damping_fit.impact(cor, m_eff, v, c_eq9, BUMPER)
    n = float(contact.n[0])

    dims = tuple(axes)

    def var(values, units, long_name, grid_shaped=True):
        values = np.asarray(values)
        return variable(dims if grid_shaped else (), values.reshape(shape) if grid_shaped
                        else values, units, long_name)

    data = {
        "a1": var(found.a1, "s m-1", "a1 of Eq. 8 at energy equilibrium (A_h = Eq. 5 loss)"),
        "c_imp_found": var(found.c_imp, "s m-1", "C_imp = a1 (1 - COR^2) at energy equilibrium"),
        "hysteresis_area": var(found.hysteresis_area, "J", "hysteresis area A_h at the a1 found"),
        "energy_loss": var(found.energy_loss, "J",
                           "kinetic energy loss of Eq. 5, 1/2 m_eff (1 - COR^2) v_imp^2"),
        "cor_found": var(found.cor_realised, "1", "realised COR with the a1 found"),
        "peak_indentation": var(found.peak_indentation, "m", "peak indentation at the a1 found"),
        "peak_force": var(found.peak_force, "N", "peak impact force at the a1 found"),
        "c_imp_fit": var(c_fit, "s m-1", "C_imp of the refitted power law"),
        "c_imp_eq9": var(c_eq9, "s m-1", "C_imp of the paper's Eq. 9"),
        "cor_fit": var(with_fit.cor, "1", "realised COR with the refitted power law"),
        "cor_eq9": var(with_eq9.cor, "1", "realised COR with the paper's Eq. 9"),
        "bisection_steps": var(found.iterations, "1", "bisection steps run", False),
        "bisection_rtol": var(1e-4 if args.quick else 1e-6, "1",
                              "relative width of the final a1 bracket", False),
        "k_imp": var(contact.k[0], power_law_units(n),
                     f"impact stiffness k_imp of the pad (Eq. 12), {power_law_units(n)}", False),
        "exponent": var(n, "1", "exponent n of the bumper law", False),
        "thickness": var(BUMPER["thickness"], "m", "pad thickness", False),
        "bumper_area": var(BUMPER["area"], "m2", "pad contact area", False),
        "strain": var(BUMPER["strain"], "1", "ultimate compressive strain of the rubber", False),
        "delta_u": var(contact.delta_u[0], "m", "indentation at which the pad is crushed", False),
    }
    for name, value in PAPER.items():
        data[f"fit_{name}"] = var(getattr(fit, name), _UNITS[name],
                                  f"{_MEANING[name]}, refitted", False)
        data[f"paper_{name}"] = var(value, _UNITS[name], f"{_MEANING[name]}, paper's Eq. 9",
                                    False)
    data["fit_rms_log_error"] = var(fit.rms_log_error, "1",
                                    "rms of ln(fitted C_imp / found C_imp)", False)
    coords = {
        "cor": ("cor", axes["cor"], {"units": "1", "long_name": "target coefficient of "
                                     "restitution"}),
        "m_eff": ("m_eff", axes["m_eff"], {"units": "kg", "long_name": "effective mass "
                                           "m1 m2 / (m1 + m2) (two equal bodies of 2 m_eff)"}),
        "v_imp": ("v_imp", axes["v_imp"], {"units": "m s-1", "long_name": "impact velocity"}),
    }
    title = ("bumpers: the impact damping coefficient C_imp of the rubber-bumper law re-derived "
             "by energy equilibrium (paper section 3.2, Eq. 9)")
    arguments = {"bumper": BUMPER, **{name: list(map(float, values))
                                      for name, values in axes.items()}}
    ds = labelled_dataset(data, coords, two_body_attributes(title, arguments))
    ds.attrs["rubber_k_r_pa"] = rubber_bumper.PARAMETERS.k_r.default
    ds.attrs["rubber_alpha"] = rubber_bumper.PARAMETERS.alpha.default
    return ds


# c0's unit depends on the fitted exponents: a string UDUNITS refuses, repeated in long_name.
_UNITS = {"c0": "SI: C_imp s m-1 with m_eff kg, v_imp m s-1", "p1": "1", "p2": "1", "p3": "1"}
_MEANING = {"c0": "coefficient c0 of C_imp = c0 (1-COR^2) / (COR^p1 m_eff^p2 v_imp^p3), in "
                  + _UNITS["c0"],
            "p1": "COR exponent p1", "p2": "effective-mass exponent p2",
            "p3": "impact-velocity exponent p3"}


def plot(ds):
    fig, (ax_c, ax_r) = plt.subplots(1, 2, figsize=(7.5, 3.4),
                                     gridspec_kw={"width_ratios": [1.15, 1]})
    v = ds.v_imp.values
    v_line = np.geomspace(v.min(), v.max(), 50)
    m_mid = float(np.exp(np.log(ds.m_eff.values).mean()))
    colors = plt.cm.viridis(np.linspace(0, 0.9, ds.sizes["cor"]))
    fit = {p: float(ds[f"fit_{p}"]) for p in PAPER}
    paper = {p: float(ds[f"paper_{p}"]) for p in PAPER}
    for cor, color in zip(ds.cor.values, colors, strict=True):
        found = (ds.c_imp_found.sel(cor=cor) / (1 - cor**2)).values  # (m_eff, v_imp)
        for row in found:
            ax_c.plot(v, row, ls="none", marker="o", mfc="none", color=color)
        ax_c.plot(v_line, _law(cor, m_mid, v_line, fit), color=color, label=f"{cor:.1f}")
        ax_c.plot(v_line, _law(cor, m_mid, v_line, paper), color=color, ls="--", lw=0.9)
    ax_c.set_xscale("log")
    ax_c.set_yscale("log")
    ax_c.set_xlabel("Impact velocity $v_{imp}$ (m/s)")
    ax_c.set_ylabel("$C_{imp}$ / (1 - COR$^2$)  (s/m)")
    ax_c.set_title("Impact damping coefficient")
    ticks = [t for t in (0.5, 1, 2, 4) if v.min() <= t <= v.max()]
    ax_c.set_xticks(ticks, [f"{t:g}" for t in ticks])
    low, high = ax_c.get_ylim()
    low = low / 1.5  # room for the style legend below the lines
    ax_c.set_ylim(low, high)
    ticks = [t for t in (0.1, 0.2, 0.5, 1, 2, 3, 5, 10, 20, 50) if low <= t <= high]
    ax_c.set_yticks(ticks, [f"{t:g}" for t in ticks])
    ax_c.minorticks_off()
    colour_legend = ax_c.legend(title="COR", loc="upper right", ncol=2, fontsize=6,
                                title_fontsize=7)
    ax_c.add_artist(colour_legend)
    styles = [plt.Line2D([], [], ls="none", marker="o", mfc="none", color="k",
                         label=f"energy equilibrium (all {ds.sizes['m_eff']} $m_{{eff}}$, "
                               "coincident)"),
              plt.Line2D([], [], color="k", label=_law_text("refit", fit)),
              plt.Line2D([], [], color="k", ls="--", lw=0.9,
                         label=_law_text("Eq. 9", paper) + f" at $m_{{eff}}$ = {_mass(m_mid)}")]
    ax_c.legend(handles=styles, loc="lower left", fontsize=6)

    target = ds.cor.values
    width = 0.012
    for name, label, color, shift in (("cor_eq9", "Eq. 9 (paper)", "C3", -width),
                                      ("cor_fit", "refit", "C0", width)):
        error = (ds[name] / ds.cor - 1).values.reshape(len(target), -1) * 100
        for x, values in zip(target, error, strict=True):
            ax_r.plot(np.full(values.size, x + shift), values, ls="none", marker="o", ms=2.5,
                      color=color, alpha=0.6)
        ax_r.plot([], [], ls="none", marker="o", color=color, label=label)
    ax_r.axhline(0, color="k", lw=0.8)
    for level in (-3, 3):
        ax_r.axhline(level, color="0.5", lw=0.8, ls=":", label="$\\pm$3%" if level > 0 else None)
    ax_r.set_xticks(target)
    ax_r.set_xlabel("Target COR")
    ax_r.set_ylabel("Realised COR / target - 1 (%)")
    ax_r.set_title("Realised COR, all $m_{eff}$ and $v_{imp}$")
    ax_r.legend(loc="upper right")
    letter_panels((ax_c, ax_r))
    short_title(fig, "Eq. 9 re-derived by energy equilibrium (paper section 3.2)")
    store_caption(ds, caption(ds))
    fig.tight_layout()
    return fig


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    v = ds.v_imp.values
    return ("Eq. 9 re-derived by energy equilibrium (paper section 3.2): "
            f"{ds.sizes['cor']} COR x {ds.sizes['m_eff']} $m_{{eff}}$ "
            f"({_mass(ds.m_eff.values.min())} to {_mass(ds.m_eff.values.max())}) x "
            f"{ds.sizes['v_imp']} $v_{{imp}}$ ({v.min():g} to {v.max():g} m/s). (a) the impact "
            "damping coefficient found by energy equilibrium (markers), the refit law (solid) "
            "and the paper's Eq. 9 (dashed), coloured by COR; (b) the COR each law realises, "
            "over every $m_{eff}$ and $v_{imp}$ (the refit's is the same at every one).")


def _mass(kg: float) -> str:
    return f"{kg / 1e3:.3g} t" if kg >= 1e3 else f"{kg:.3g} kg"


def _law(cor, m_eff, v, p):
    """C_imp / (1 - COR^2) of the power law with constants p (s/m): engine.damping_fit's."""
    from engine.damping_fit import power_law_c_imp

    return power_law_c_imp(cor, m_eff, v, **p) / (1 - cor**2)


def _law_text(name, p) -> str:
    return (f"{name}: {p['c0']:.3f} / (COR$^{{{p['p1']:.3f}}}$ $m_{{eff}}^{{{p['p2']:.4f}}}$ "
            f"$v^{{{p['p3']:.3f}}}$)")


def check(ds) -> list[Verdict]:
    """Paper 3.2: the energy-equilibrium a1 over (COR, m_eff, v_imp) fits Eq. 9:
    c0 = 1.55, p1 = 0.7076, p2 = 0.0025, p3 = 0.9755."""
    fit = {p: float(ds[f"fit_{p}"]) for p in PAPER}
    balance = float(np.abs(ds.hysteresis_area / ds.energy_loss - 1).max())
    crushed = bool(np.any(ds.peak_indentation >= ds.delta_u))
    common = (f"{ds.a1.size} points, A_h = dE within {balance:.1e}, pad "
              f"{'CRUSHED' if crushed else 'not crushed'}, rms log misfit "
              f"{float(ds.fit_rms_log_error):.4f}")
    eq9 = (ds.cor_eq9 / ds.cor - 1).values
    refit = (ds.cor_fit / ds.cor - 1).values
    common += (f"; realised COR with Eq. 9 {eq9.min():+.1%} to {eq9.max():+.1%} of the target, "
               f"with the refit {refit.min():+.1%} to {refit.max():+.1%}")
    numbers = {"fit": fit, "paper": PAPER, "tolerance": TOLERANCE, "energy_balance": balance,
               "crushed": crushed, "eq9_cor_error": [float(eq9.min()), float(eq9.max())],
               "refit_cor_error": [float(refit.min()), float(refit.max())]}
    out = []
    for p, meaning in (("c0", "coefficient"), ("p1", "COR exponent"),
                       ("p2", "mass exponent"), ("p3", "velocity exponent")):
        paper = PAPER[p]
        if p == "c0":
            ok = abs(fit[p] / paper - 1) <= TOLERANCE[p]
            finding = (f"c0 = {fit[p]:.3f} ({fit[p] / paper - 1:+.1%}; tolerance "
                       f"{TOLERANCE[p]:.0%})")
        elif p == "p2":
            ok = abs(fit[p]) <= TOLERANCE[p]
            finding = (f"p2 = {round(fit[p], 4) + 0.0:.4f} (a pure power law is "
                       f"scale-invariant: expected 0; tolerance |p2| <= {TOLERANCE[p]})")
        else:
            ok = abs(fit[p] - paper) <= TOLERANCE[p]
            finding = f"{p} = {fit[p]:.4f} ({fit[p] - paper:+.4f}; tolerance {TOLERANCE[p]})"
        out.append(Verdict("Eq. 9", f"Energy equilibrium gives the {meaning} {p} = {paper}",
                           f"{finding}; {common}", ok, numbers))
    return out


recipe = Recipe(
    name="damping_calibration", figure="Eq. 9",
    summary="Re-derive Eq. 9 (the impact damping coefficient C_imp) by energy equilibrium of "
            "two-body impacts over a (COR, m_eff, v_imp) grid and refit its power law",
    compute=compute, plot=plot, check=check, records=None,
    chosen="grid COR 0.3-0.9 step 0.1 x m_eff 10 kg-320 t (6, geometric) x v_imp 0.5-4 m/s "
           "(7, geometric) (--quick: COR 0.3, 0.6, 0.9 x 10 kg, 320 t x 0.5, 4 m/s); "
           "a 1.0 x 1.0 m, 0.2 m thick pad of the paper's rubber (K_r 55,835 kN/m^2, n 2.65, "
           "alpha 2.25), strain 1.0 so delta_u = 0.2 m (never reached); two equal bodies of "
           "2 m_eff; a1 by bisection to 1e-6 relative (1e-4 with --quick)",
    not_resumable="it runs the two-body simulator itself, a few seconds of batched "
                  "impacts, not the sweep executor")
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
