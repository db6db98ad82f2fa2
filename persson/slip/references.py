"""Citation keys of the slip models (DOIs, ISBNs or project keys read by :mod:`frictioncite`)."""

from __future__ import annotations

__all__ = ["PACEJKA_BOOK", "SAKAI_1981", "CANUDAS_2003", "MAGIC_FORMULA", "PIARC_1995", "DO_2004", "RADO_1994",
           "CARSLAW_JAEGER", "JAEGER_1942", "BLOK_1937", "PERSSON_TREAD_2026"]


#: H. B. Pacejka, Tire and Vehicle Dynamics (3rd ed., 2012), brush model: chapter 3.
PACEJKA_BOOK = "isbn:9780080970165"


#: H. Sakai, Theoretical and experimental studies on the dynamic properties of tyres (Int. J. Vehicle Design, 1981).
SAKAI_1981 = "sakai:ijvd-1981"


#: C. Canudas-de-Wit, P. Tsiotras, E. Velenis, M. Basset, G. Gissinger, Dynamic friction models for road/tire
#: longitudinal interaction, Vehicle System Dynamics 39 (3), 189-226 (2003): Stribeck-type friction of the
#: brush elements, g(v) = mu_C + (mu_S - mu_C) exp(-|v/v_s|^alpha).
CANUDAS_2003 = "10.1076/vesd.39.3.189.14152"


#: H. B. Pacejka, E. Bakker, The Magic Formula tyre model, Vehicle System Dynamics 21 (S1), 1-18 (1992).
MAGIC_FORMULA = "10.1080/00423119208969994"


#: PIARC (World Road Association), International PIARC experiment to compare and harmonize texture and skid
#: resistance measurements, report 01.04.T (1995).
PIARC_1995 = "piarc:01.04.T-1995"


#: M.-T. Do, P. Marsac, A. Mosset, Tribology approach to predict the variation of tire/wet road friction with
#: slip speed, 5th Symposium on Pavement Surface Characteristics (SURF 2004), Toronto (HAL hal-00851262).
DO_2004 = "hal:hal-00851262"


#: Z. Rado, A study of road surface texture and its relationship to friction, PhD thesis, Pennsylvania State
#: University (1994).
RADO_1994 = "rado:psu-phd-1994"


#: H. S. Carslaw, J. C. Jaeger, Conduction of Heat in Solids, 2nd ed., Oxford (1959), ch. II.
CARSLAW_JAEGER = "isbn:9780198533689"


#: J. C. Jaeger, Moving sources of heat and the temperature at sliding contacts, J. Proc. R. Soc. N.S.W. 76,
#: 203-224 (1942).
JAEGER_1942 = "jaeger:jprsnsw-76-203-1942"


#: H. Blok, Theoretical study of temperature rise at surfaces of actual contact under oiliness lubricating
#: conditions, General Discussion on Lubrication and Lubricants, IMechE, London, vol. 2, 222-235 (1937).
BLOK_1937 = "blok:imeche-lubrication-1937"


#: B. N. J. Persson, N. Miyashita, Tire tread block dynamics, arXiv:2602.22078 (2026): background and flash
#: temperature.
PERSSON_TREAD_2026 = "arxiv:2602.22078"
