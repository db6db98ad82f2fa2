"""Citation keys of the slip models (DOIs, ISBNs or project keys read by :mod:`frictioncite`)."""

from __future__ import annotations

__all__ = ["PACEJKA_BOOK", "SAKAI_1981", "CANUDAS_2003", "MAGIC_FORMULA", "PIARC_1995", "DO_2004", "RADO_1994",
           "CARSLAW_JAEGER", "JAEGER_1942", "BLOK_1937", "PERSSON_TREAD_2026", "DIJKS_1974", "LEU_HENRY_1978",
           "LA_TORRE_2001", "GOMPERTZ_1825", "STRIBECK_1902", "LAMPAERT_2002", "MOORE_1975", "HORNE_DREHER_1963",
           "AKAIKE_1974", "HURVICH_TSAI_1989", "SCHWARZ_1978", "GOLUB_PEREYRA_1973", "EN_13036_4",
           "GENT_2012", "TIMOSHENKO_GERE", "BURCKHARDT_1993"]


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


#: I. A. Dijks, A multifactor examination of wet skid resistance of car tires, SAE Technical Paper 741106 (1974).
DIJKS_1974 = "10.4271/741106"


#: M. C. Leu, J. J. Henry, Prediction of skid resistance as a function of speed from pavement texture measurements,
#: Transportation Research Record 666, 7-13 (1978): the exponential law behind the PIARC model.
LEU_HENRY_1978 = "leu-henry:trr-666-1978"


#: F. La Torre, L. Domenichini, Friction prediction models, 2nd International Colloquium on Vehicle Tyre Road
#: Interaction, Florence, paper 01.08B, 133-147 (2001).
LA_TORRE_2001 = "latorre-domenichini:vtri-2001"


#: B. Gompertz, On the nature of the function expressive of the law of human mortality, Phil. Trans. R. Soc. Lond.
#: 115, 513-583 (1825): the Gompertz function (used for friction against speed by M. E. van den Bol, cited by Do et
#: al. 2004).
GOMPERTZ_1825 = "10.1098/rstl.1825.0026"


#: R. Stribeck, Die wesentlichen Eigenschaften der Gleit- und Rollenlager, Z. Ver. Dtsch. Ing. 46, 1341-1348,
#: 1432-1438, 1463-1470 (1902): friction against eta V / p, the Stribeck curve.
STRIBECK_1902 = "stribeck:zvdi-46-1902"


#: V. Lampaert, J. Swevers, F. Al-Bender, Experimental comparison of different friction models for accurate
#: low-velocity tracking, KU Leuven, Department of Mechanical Engineering (2002): the static Stribeck law
#: mu_c + (mu_s - mu_c) exp(-(V/V_s)^alpha) + beta V.
LAMPAERT_2002 = "lampaert-swevers-albender:kuleuven-2002"


#: D. F. Moore, The Friction of Pneumatic Tyres, Elsevier, Amsterdam (1975): the three zones of a tyre on a wet road
#: (squeeze film, transition, dry contact) and the squeeze-film time of the transition zone.
MOORE_1975 = "moore:friction-pneumatic-tyres-1975"


#: W. B. Horne, R. C. Dreher, Phenomena of pneumatic tire hydroplaning, NASA Technical Note D-2056 (1963): the
#: fluid inertia pressure rho V^2 / 2 that lifts the front of the footprint.
HORNE_DREHER_1963 = "nasa:tn-d-2056"


#: H. Akaike, A new look at the statistical model identification, IEEE Trans. Autom. Control 19, 716-723 (1974).
AKAIKE_1974 = "10.1109/TAC.1974.1100705"


#: C. M. Hurvich, C.-L. Tsai, Regression and time series model selection in small samples, Biometrika 76, 297-307
#: (1989): the small-sample correction AICc.
HURVICH_TSAI_1989 = "10.1093/biomet/76.2.297"


#: G. Schwarz, Estimating the dimension of a model, Ann. Stat. 6, 461-464 (1978): the Bayesian information criterion.
SCHWARZ_1978 = "10.1214/aos/1176344136"


#: G. H. Golub, V. Pereyra, The differentiation of pseudo-inverses and nonlinear least squares problems whose
#: variables separate, SIAM J. Numer. Anal. 10, 413-432 (1973): variable projection.
GOLUB_PEREYRA_1973 = "10.1137/0710036"


#: EN 13036-4, Road and airfield surface characteristics - Test methods - Part 4: Method for measurement of
#: slip/skid resistance of a surface: the pendulum test (British Pendulum Number, BPN).
EN_13036_4 = "en:13036-4"
#: A. N. Gent (ed.), Engineering with Rubber: How to Design Rubber Components, 3rd ed., Hanser, Munich (2012),
#: ch. 3: a bonded rubber block in shear, its stiffness lowered by bending.
GENT_2012 = "gent:engineering-with-rubber-2012"


#: S. P. Timoshenko, J. M. Gere, Mechanics of Materials, Van Nostrand Reinhold (1972): deflection of a beam in
#: bending and shear.
TIMOSHENKO_GERE = "timoshenko-gere:mechanics-of-materials-1972"


#: M. Burckhardt, Fahrwerktechnik: Radschlupf-Regelsysteme, Vogel, Wuerzburg (1993): mu(s) = c1 (1 - exp(-c2 s))
#: - c3 s with constants per road surface (dry asphalt c1 = 1.2801, c2 = 23.99, c3 = 0.52).
BURCKHARDT_1993 = "burckhardt:radschlupf-regelsysteme-1993"


#: Study on the influence of environmental conditions on road friction characteristics, Lubricants 11(7), 277
#: (2023): the road-friction trailer, its Magic Formula identification and its two-coefficient brush with the
#: bristle kinematics dx = s x and Sakai's n = 4 pressure (Section 4, Eqs. 11-25, Figures 16-20).
TRAILER_2023 = "10.3390/lubricants11070277"
__all__ += ["TRAILER_2023"]
