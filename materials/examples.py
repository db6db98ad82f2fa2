"""Example materials shipped with the package (synthetic, documented, for demos and tests)."""

from __future__ import annotations

import numpy as np

from .viscoelastic import WLF, Prony, Thermal

__all__ = ["example_tread", "EXAMPLE_TREAD_LABEL"]

#: Label carried by :func:`example_tread` so that reports never mistake it for measured data.
EXAMPLE_TREAD_LABEL = "synthetic tread compound (materials.example_tread); not measured data"


def example_tread() -> Prony:
    r"""A synthetic passenger-car tread compound: generalized Maxwell solid with WLF shift. **Synthetic.**

    The compound is invented (no measurement behind it) but has the features of a filled SBR/BR tread:

    * reference temperature :math:`T_{ref} = 20` C with the "universal" WLF constants
      :math:`C_1 = 8.86`, :math:`C_2 = 101.6` K (Williams, Landel & Ferry 1955), which put the glass
      transition about 50 K below :math:`T_{ref}`:
      :math:`\log_{10} a_T = -C_1 (T - T_{ref}) / (C_2 + T - T_{ref})`;
    * relaxed (rubbery plateau) modulus :math:`E_\infty = 3` MPa, glassy modulus
      :math:`E_\infty + \sum_i E_i = 2` GPa;
    * a smooth, log-normal relaxation spectrum centred at :math:`\tau = 10^{-10.5}` s (at 20 C) with a
      standard deviation of 1.7 decades, plus a weak (1 %) long-time tail centred four decades slower that
      mimics the filler contribution; 55 relaxation times log-spaced 3 per decade from
      :math:`10^{-15}` to :math:`10^{3}` s (dense enough that E', E'' are smooth, ripple < 1 %):

      .. math::
          E(\omega, T) = E_\infty + \sum_i E_i \frac{i\omega a_T \tau_i}{1 + i\omega a_T\tau_i},\qquad
          E_i \propto e^{-(\log_{10}\tau_i + 10.5)^2 / (2\cdot 1.7^2)}
          + 0.01\, e^{-(\log_{10}\tau_i + 6.5)^2 / (2\cdot 2.5^2)}

    Resulting characteristics (computed, see ``tests/test_materials_example.py``): E'' peaks at 1 Hz near
    :math:`T_g \approx -33` C (tan delta peaks at 1 Hz near -21 C, maximum tan delta about 0.8);
    :math:`E'(1\,\mathrm{Hz}, 20\,C) \approx 3.4` MPa; :math:`E(10^4\,\mathrm{Hz}, 20\,C) \approx 11 + 5i` MPa;
    the transition (10-90 % of log E') spans about 7 decades of frequency.

    Thermal properties: density 1150 kg/m^3, specific heat 1800 J/(kg K), conductivity 0.25 W/(m K)
    (typical of carbon-black/silica filled tread rubber).

    Returns
    -------
    Prony
        With ``.E(omega, T)`` (complex Pa, vectorized, broadcasting ``omega`` against ``T``; Im E odd in omega;
        E(0) = E_inf), ``.wlf``, ``.log10_aT(T)``, ``.thermal`` and ``.label`` (says "synthetic").
    """
    log_tau = np.linspace(-15.0, 3.0, 55)
    weight = (np.exp(-0.5 * ((log_tau + 10.5) / 1.7) ** 2)
              + 0.01 * np.exp(-0.5 * ((log_tau + 6.5) / 2.5) ** 2))
    E_inf = 3.0e6
    E_glassy = 2.0e9
    E_i = (E_glassy - E_inf) * weight / weight.sum()
    return Prony(E_inf=E_inf, E_i=E_i, tau_i=10.0 ** log_tau,
                 wlf=WLF(C1=8.86, C2=101.6, T_ref=20.0),
                 thermal=Thermal(density=1150.0, specific_heat=1800.0, conductivity=0.25),
                 label=EXAMPLE_TREAD_LABEL)
