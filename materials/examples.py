"""Example materials shipped with the package (synthetic, documented, for demos and tests)."""

from __future__ import annotations

import numpy as np

from .laws import TemperatureShift
from .viscoelastic import WLF, Prony, Thermal

__all__ = ["example_tread", "EXAMPLE_TREAD_LABEL", "example_tire_tread", "EXAMPLE_TIRE_TREAD_LABEL"]

#: Label carried by :func:`example_tread` so that reports never mistake it for measured data.
EXAMPLE_TREAD_LABEL = "synthetic tread compound (materials.example_tread); not measured data"

#: Label carried by :func:`example_tire_tread`.
EXAMPLE_TIRE_TREAD_LABEL = "synthetic passenger-car tread compound (materials.example_tire_tread); not measured data"


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


def example_tire_tread() -> Prony:
    r"""A synthetic passenger-car tread compound with the DMA features of a filled tread and a shift law for hot
    rubber. **Synthetic.**

    Generalized Maxwell solid (67 relaxation times, 3 per decade from :math:`10^{-16}` to :math:`10^{6}` s at
    20 C): relaxed modulus 4.5 MPa, glassy modulus 1 GPa, a log-normal glass-transition spectrum centred at
    :math:`\tau = 10^{-8.5}` s with a standard deviation of 1.6 decades, and 8 % of the strength in a broad
    (3 decades) tail centred at :math:`10^{-6}` s that stands for the filler network, which keeps the loss of a
    filled compound up at warm temperatures:

    .. math:: E_i \propto 0.92\,\phi(\log_{10}\tau_i; -8.5, 1.6) + 0.08\,\phi(\log_{10}\tau_i; -6, 3)

    (:math:`\phi` normalised Gaussian weights). Temperature law: the "universal" WLF constants at a glass
    transition :math:`T_g = -25` C (:math:`C_1^g = 17.44`, :math:`C_2^g = 51.6` K, Williams, Landel & Ferry 1955),
    referred to 20 C (:math:`C_1 = 9.316`, :math:`C_2 = 96.6` K), handing over to an Arrhenius law above
    :math:`T_g + 100` K = 75 C, continuous in :math:`\log_{10} a_T` and its slope (Ferry 1980, ch. 11; Dealy &
    Plazek 2009; :meth:`materials.TemperatureShift.with_upper`). The law is not fitted to data: it carries no
    fitted range.

    At 10 Hz (computed, ``tests/test_slip_realism.py``): tan delta peaks near -10 C (0.56), is 0.42 at 0 C and
    0.10 at 60 C; E' is 31 MPa at 0 C, 11 MPa at 20 C and 5.4 MPa at 60 C, the range of passenger-car tread
    compounds. Thermal properties as :func:`example_tread`.

    Returns
    -------
    Prony
    """
    log_tau = np.linspace(-16.0, 6.0, 67)
    main = np.exp(-0.5 * ((log_tau + 8.5) / 1.6) ** 2)
    tail = np.exp(-0.5 * ((log_tau + 6.0) / 3.0) ** 2)
    weight = 0.92 * main / main.sum() + 0.08 * tail / tail.sum()
    E_inf, E_glassy = 4.5e6, 1.0e9
    Tg = -25.0
    C2 = 51.6 + (20.0 - Tg)
    law = TemperatureShift(WLF(C1=17.44 * 51.6 / C2, C2=C2, T_ref=20.0)).with_upper(Tg + 100.0)
    return Prony(E_inf=E_inf, E_i=(E_glassy - E_inf) * weight, tau_i=10.0 ** log_tau, wlf=law,
                 thermal=Thermal(density=1150.0, specific_heat=1800.0, conductivity=0.25),
                 label=EXAMPLE_TIRE_TREAD_LABEL)
