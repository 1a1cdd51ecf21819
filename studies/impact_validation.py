"""Fig. 6: force-indentation loops of two 300 kg steel rods colliding through a rubber bumper.

The Kajita et al. (2006) impact test simulated with the paper's model (section 3.4): a 10 mm
thick, 40 x 40 mm rubber pad, k_imp = 0.45 kN/mm^2.65 (Eq. 11-12: K_r = 55,835 kN/m^2,
alpha = 2.25), COR 0.45, C_imp of Eq. 9, against Hertzdamp with the same k and n = 2.65 and
its published damping chi = 3 (1 - COR^2) / 4. Panel (a): the static curve k_st delta^2.65,
k_st = 0.2 kN/mm^2.65; panels (b)-(d): one impact velocity each. The paper does not state the
velocities: chosen inside the tested range of the same apparatus (0.2-1.0 m/s), giving peak
forces of a few tens of kN.
"""
from __future__ import annotations

import numpy as np

from engine.impact import LAWS
from engine.units import KN, MM, kn_per_mm_n, power_law_units

from .common.paper import (
    STRAIN,
    TEST_COR,
    TEST_K_ST_KN_MM,
    TEST_PAD_AREA,
    TEST_PAD_THICKNESS,
    TEST_ROD_MASS,
)
from .common.plot import letter_panels, plt, short_title, store_caption
from .common.recipe import Recipe, Verdict

# The test (rod mass, pad, static fit, COR) and the rubber's ultimate strain (0.8: delta_u =
# 8 mm) are the paper's, studies.common.paper; the rubber's exponent n is the bumper law's.
EXPONENT = LAWS["bumper"].PARAMETERS.n.default  # 2.65
# Past delta_u the rods would bear steel on steel: the axial stiffness E A / L of one
# 1000 x 200 x 200 mm steel bar of the test (E = 205 GPa). The impacts below do not reach it.
K_W = 205e9 * 0.2 * 0.2 / 1.0  # N/m (8200 kN/mm)
VELOCITIES = (0.5, 0.75, 1.0)  # m/s
MODELS = ("proposed", "hertzdamp")
MODEL_LABELS = {"proposed": "Proposed model (Eq. 4, 6, 9)",
                "hertzdamp": "Hertzdamp, $\\chi$ = 3(1 - COR$^2$)/4"}


def contacts(velocities):
    """The two laws at each velocity, model-major: (2 V,) Contact members."""
    from engine import Contact

    v = np.asarray(velocities, dtype=float)
    m_eff = TEST_ROD_MASS / 2
    proposed = Contact.bumper(1.0, thickness=TEST_PAD_THICKNESS, strain=STRAIN, n_bumpers=1,
                              k_w=K_W, cor=np.full(v.shape, TEST_COR), m_eff=m_eff,
                              area=TEST_PAD_AREA, n=EXPONENT)
    hertzdamp = Contact.hertzdamp(1.0, k=proposed.k, n=EXPONENT, cor=TEST_COR, m_eff=m_eff,
                                  chi_rule="lankarani")
    return Contact.concat([proposed, hertzdamp])


def compute(args):
    import engine
    from engine.impact.laws import rubber_bumper
    from pipeline.archive import labelled_dataset
    from pipeline.archive import variable as var
    from pipeline.provenance import two_body_attributes

    v = np.asarray(VELOCITIES)
    contact = contacts(v)
    res = engine.two_body(TEST_ROD_MASS, TEST_ROD_MASS, np.tile(v, len(MODELS)), contact)
    shape = (len(MODELS), len(v))
    force = res.force.reshape(*shape, -1)
    # Indentation after the contact has ended is the bodies flying apart: stored as zero.
    in_contact = force > 0
    last = force.shape[-1] - 1 - np.argmax(in_contact[..., ::-1], axis=-1)  # last F > 0
    n_contact = last + 2  # through the step at which the loop closes (F = 0)
    step = np.arange(force.shape[-1])
    after = step >= n_contact[..., None]
    indentation = np.where(after, 0.0, np.maximum(res.indentation.reshape(force.shape), 0.0))

    # Approach branch (up to the peak indentation) of each loop against k delta^n.
    k = contact.k[0]
    peak_step = np.argmax(indentation, axis=-1)
    approach = (step <= peak_step[..., None]) & (indentation > 0)
    elastic = k * indentation**EXPONENT
    deviation = np.where(approach, np.abs(force / np.where(approach, elastic, 1.0) - 1), 0.0)

    mv = ("model", "velocity")
    per_case = {name: getattr(res, name).reshape(shape) for name in
                ("peak_force", "peak_indentation", "cor", "hysteresis_area",
                 "dissipated_energy", "dt", "expected_energy_loss")}
    energy_loss = per_case["expected_energy_loss"][0]  # Eq. 5, the same for both models
    c_imp = (rubber_bumper.damping_prefactor(TEST_COR, TEST_ROD_MASS / 2)
             / v**rubber_bumper.EQ9_VELOCITY_EXPONENT)
    data = {
        "indentation": var((*mv, "step"), indentation, "m",
                           "indentation (relative approach of the rods), zero after separation"),
        "force": var((*mv, "step"), force, "N", "impact force, zero after separation"),
        "dt": var(mv, per_case["dt"], "s", "integration step of the two-body simulation"),
        "n_contact_steps": var(mv, n_contact, "1",
                               "stored steps up to and including the closing of the loop"),
        "peak_force": var(mv, per_case["peak_force"], "N", "peak impact force"),
        "peak_indentation": var(mv, per_case["peak_indentation"], "m", "peak indentation"),
        "cor_measured": var(mv, per_case["cor"], "1",
                            "measured coefficient of restitution, -v_out / v_imp"),
        "hysteresis_area": var(mv, per_case["hysteresis_area"], "J",
                               "area of the force-indentation loop (energy dissipated)"),
        "dissipated_energy": var(mv, per_case["dissipated_energy"], "J",
                                 "kinetic energy lost, 1/2 m_eff (v_imp^2 - v_out^2)"),
        "energy_loss_eq5": var("velocity", energy_loss, "J",
                               f"kinetic energy loss of Eq. 5 with COR {TEST_COR}"),
        "area_ratio": var(mv, per_case["hysteresis_area"] / energy_loss, "1",
                          "hysteresis area / Eq. 5 energy loss"),
        "approach_deviation": var(mv, deviation.max(axis=-1), "1",
                                  "max relative deviation of the approach branch from "
                                  "k_imp delta^n"),
        "c_imp": var("velocity", c_imp, "s m-1", "impact damping coefficient C_imp of Eq. 9 "
                     "(proposed model)"),
        "chi_hertzdamp": var((), contact.chi[-1], "1",
                             "Hertzdamp damping factor chi = 3 (1 - COR^2) / 4"),
        "k_imp": var((), k, power_law_units(EXPONENT),
                     f"impact stiffness k_imp (Eq. 12), also Hertzdamp's k, "
                     f"{power_law_units(EXPONENT)}"),
        "k_st": var((), TEST_K_ST_KN_MM * kn_per_mm_n(EXPONENT), power_law_units(EXPONENT),
                    "static stiffness k_st of the static test fit (Fig. 6a), "
                    f"{power_law_units(EXPONENT)}"),
        "exponent": var((), EXPONENT, "1", "exponent n of both laws"),
        "cor": var((), TEST_COR, "1", "target coefficient of restitution"),
        "rod_mass": var((), TEST_ROD_MASS, "kg", "mass of each steel rod (m1 = m2)"),
        "m_eff": var((), TEST_ROD_MASS / 2, "kg", "effective mass m1 m2 / (m1 + m2)"),
        "thickness": var((), TEST_PAD_THICKNESS, "m", "bumper thickness"),
        "bumper_area": var((), TEST_PAD_AREA, "m2", "bumper contact area (40 x 40 mm)"),
        "strain": var((), STRAIN, "1", "ultimate compressive strain of the rubber"),
        "delta_u": var((), contact.delta_u[0], "m", "indentation at which the rubber is "
                       "crushed, strain x thickness"),
        "k_w": var((), K_W, "N m-1", "stiffness past delta_u (axial E A / L of one steel rod)"),
    }
    coords = {
        "model": ("model", np.array(MODELS), {"units": "1", "long_name": "impact model"}),
        "velocity": ("velocity", v, {"units": "m s-1", "long_name": "impact velocity v_imp"}),
        "step": ("step", step, {"units": "1", "long_name": "integration step (time / dt)"}),
    }
    title = ("bumpers: two steel rods colliding through a rubber pad (the impact test of "
             "Kajita et al. 2006, paper Fig. 6), two impact laws")
    arguments = {"velocities": list(VELOCITIES), "rod_mass": TEST_ROD_MASS,
                 "pad_thickness": TEST_PAD_THICKNESS, "pad_area": TEST_PAD_AREA,
                 "strain": STRAIN, "k_w": K_W, "cor": TEST_COR, "n": EXPONENT,
                 "models": list(MODELS)}
    return labelled_dataset(data, coords, two_body_attributes(title, arguments))


def plot(ds):
    fig, axes = plt.subplots(2, 2, figsize=(6.5, 5.2), sharex=True, sharey=True)
    n = float(ds.exponent)
    delta_u_mm = float(ds.delta_u) / MM
    grid_mm = np.linspace(0, delta_u_mm, 200)
    k_st = float(ds.k_st) / kn_per_mm_n(n)  # kN/mm^n
    k_imp = float(ds.k_imp) / kn_per_mm_n(n)
    static = k_st * grid_mm**n

    ax = axes[0, 0]
    ax.plot(grid_mm, static, color="k", ls=":",
            label=f"Static: $k_{{st}}$ = {k_st:.2g} kN/mm$^{{{n:g}}}$")
    ax.plot(grid_mm, k_imp * grid_mm**n, color="0.5", ls="--",
            label=f"Impact: $k_{{imp}}$ = {k_imp:.2f} kN/mm$^{{{n:g}}}$")
    ax.set_title("Static test curve")
    ax.axvline(delta_u_mm, color="0.3", lw=0.8)
    ax.annotate(f"$\\delta_u$ = {delta_u_mm:g} mm", (delta_u_mm, 2), xytext=(-3, 0),
                textcoords="offset points", ha="right", va="bottom")
    ax.legend(loc="upper left")
    styles = {"proposed": dict(color="C0"), "hertzdamp": dict(color="C3", ls="-.")}
    for ax, v in zip(axes.flat[1:], ds.velocity.values, strict=True):
        for model in ds.model.values:
            case = ds.sel(model=model, velocity=v)
            end = int(case.n_contact_steps)
            ax.plot(case.indentation.values[:end] / MM, case.force.values[:end] / KN,
                    label=MODEL_LABELS.get(str(model), str(model)), **styles.get(str(model), {}))
        ax.plot(grid_mm, static, color="k", ls=":", lw=0.9, label="Static curve")
        ax.set_title(f"$v_{{imp}}$ = {v:.2g} m/s")
    axes[0, 1].legend(loc="upper left")
    # Loop direction, on the fastest impact's proposed loop.
    ax = axes[1, 1]
    case = ds.sel(model=ds.model.values[0], velocity=ds.velocity.values[-1])
    peak = int(np.argmax(case.indentation.values))
    d_mm, f_kn = case.indentation.values / MM, case.force.values / KN
    unloaded = peak + int(np.argmax(f_kn[peak:] < 0.3 * f_kn[peak]))
    for i, text, offset, ha in ((peak // 2, "approach", (-32, 14), "right"),
                                (unloaded, "restitution", (14, 10), "left")):
        ax.annotate(text, (d_mm[i], f_kn[i]), xytext=offset, textcoords="offset points",
                    fontsize=7, color="C0", ha=ha,
                    arrowprops=dict(arrowstyle="->", color="C0", lw=0.7))
    for ax in axes[1]:
        ax.set_xlabel("Indentation (mm)")
    for ax in axes[:, 0]:
        ax.set_ylabel("Impact force (kN)")
    axes[0, 0].set_xlim(0, 1.06 * delta_u_mm)
    axes[0, 0].set_ylim(0, 1.15 * max(float(ds.peak_force.max()) / KN, static[-1]))
    letter_panels(axes)
    short_title(fig, "Fig. 6: impact tests of a 10 mm rubber bumper")
    store_caption(ds, caption(ds))
    fig.tight_layout()
    return fig


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    return (f"Fig. 6: a 10 mm rubber bumper between two {float(ds.rod_mass):g} kg steel rods "
            f"(COR {float(ds.cor):g}). (a) the static test curve and the impact stiffness; "
            "(b)-(d) force against indentation at three impact velocities, the proposed model "
            "and the Hertz-damp model against the static curve (dotted); all panels on one "
            "scale.")


def check(ds) -> list[Verdict]:
    """Paper 3.4: the proposed loop's area matches the Eq. 5 energy loss with COR 0.45 and its
    approach follows k delta^n; Hertzdamp's loop area differs significantly."""
    def listed(values, fmt="{:.3f}"):
        return ", ".join(fmt.format(x) for x in np.ravel(values))

    prop, hertz = ds.sel(model="proposed"), ds.sel(model="hertzdamp")
    v_text = listed(ds.velocity.values, "{:g}")
    crushed = bool(np.any(ds.peak_indentation >= ds.delta_u))
    context = (f"v_imp = {v_text} m/s; peak force {listed(prop.peak_force / KN, '{:.1f}')} kN "
               f"(proposed), {listed(hertz.peak_force / KN, '{:.1f}')} kN (Hertzdamp); peak "
               f"indentation {listed(prop.peak_indentation / MM, '{:.2f}')} mm vs delta_u "
               f"{float(ds.delta_u) / MM:g} mm: {'crushed' if crushed else 'not crushed'}")
    deviation = float(prop.approach_deviation.max())
    return [
        Verdict("3.4", "The proposed model's hysteresis area matches the kinetic energy loss "
                f"of Eq. 5 (COR {float(ds.cor):g})",
                f"A_h / dE(Eq. 5) = {listed(prop.area_ratio)} (measured COR "
                f"{listed(prop.cor_measured)}), within 5%; {context}",
                bool(np.all(np.abs(prop.area_ratio - 1) < 0.05)),
                {"area_ratio": prop.area_ratio.values, "cor_measured": prop.cor_measured.values,
                 "velocity": ds.velocity.values, "peak_force": prop.peak_force.values,
                 "peak_indentation": prop.peak_indentation.values}),
        Verdict("3.4", "Hertzdamp's loop area differs significantly from the Eq. 5 loss",
                f"Hertzdamp (chi = {float(ds.chi_hertzdamp):.3f}) A_h / dE = "
                f"{listed(hertz.area_ratio)} (measured COR {listed(hertz.cor_measured)}); "
                "significant: more than 20% off",
                bool(np.all(np.abs(hertz.area_ratio - 1) > 0.2)),
                {"area_ratio": hertz.area_ratio.values,
                 "cor_measured": hertz.cor_measured.values}),
        Verdict("3.4", "The proposed approach branch follows k_imp delta^n",
                f"max relative deviation {deviation:.1e} (below 1e-6)", deviation < 1e-6,
                {"max_relative_deviation": deviation}),
    ]


recipe = Recipe(
    name="impact_validation", figure="Fig. 6",
    summary="Force-indentation loops of two 300 kg steel rods colliding through a 10 mm rubber "
            "bumper: the proposed model vs Hertzdamp at three impact velocities",
    compute=compute, plot=plot, check=check, records=None,
    chosen="impact velocities 0.5, 0.75, 1.0 m/s (inside the 0.2-1.0 m/s of the Kajita et al. "
           "apparatus; peak forces 17-47 kN); k_w = 8200 kN/mm past delta_u = 8 mm (axial "
           "E A / L of one 1000 x 200 x 200 mm steel rod; not reached); Hertzdamp with "
           "k = k_imp, n = 2.65, chi = 3(1-COR^2)/4",
    not_resumable="it runs the two-body simulator itself, one batch of a few impacts, "
                  "not the sweep executor")
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
