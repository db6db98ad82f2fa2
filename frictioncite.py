"""Citations for the physics: a ``@doi`` decorator and the registry behind it.

Every analysis function that implements a published formula is decorated with the DOIs (or other stable
references) of the papers it relies on. Results keep the list, so that a report can cite its physics::

    from frictioncite import doi

    @doi("10.1063/1.1388626")
    def contact_area(...):
        ...

    contact_area.__citations__          # ('10.1063/1.1388626',)
    frictioncite.references(contact_area)   # formatted references

The decorator does not wrap the function (numba kernels and hot paths keep their speed); it only attaches
the attribute ``__citations__`` and records the DOIs in a module-level table of known references. The table
is read-only data, not state that changes results.
"""

from __future__ import annotations

from typing import Callable, Iterable, TypeVar

__all__ = ["doi", "citations_of", "references", "REFERENCES"]

F = TypeVar("F")

#: Human-readable form of the references the packages cite, keyed by DOI (or ``isbn:``/``iso:`` key).
REFERENCES: dict[str, str] = {
    "10.1063/1.1388626": "B. N. J. Persson, Theory of rubber friction and contact mechanics, "
    "J. Chem. Phys. 115, 3840 (2001).",
    "10.1088/0953-8984/17/1/R01": "B. N. J. Persson, O. Albohr, U. Tartaglino, A. I. Volokitin, E. Tosatti, "
    "On the nature of surface roughness with application to contact mechanics, sealing, rubber friction and "
    "adhesion, J. Phys.: Condens. Matter 17, R1 (2005).",
    "10.1016/j.surfrep.2006.04.001": "B. N. J. Persson, Contact mechanics for randomly rough surfaces, "
    "Surf. Sci. Rep. 61, 201 (2006).",
    "10.1088/0953-8984/18/32/025": "B. N. J. Persson, Rubber friction: role of the flash temperature, "
    "J. Phys.: Condens. Matter 18, 7789 (2006).",
    "10.1103/PhysRevLett.99.125502": "B. N. J. Persson, Relation between interfacial separation and load: "
    "a general theory of contact mechanics, Phys. Rev. Lett. 99, 125502 (2007).",
    "10.1088/0953-8984/20/21/215214": "C. Yang, B. N. J. Persson, Contact mechanics: contact area and "
    "interfacial separation from small contact to full contact, J. Phys.: Condens. Matter 20, 215214 (2008).",
    "10.1021/ja01619a008": "M. L. Williams, R. F. Landel, J. D. Ferry, The temperature dependence of "
    "relaxation mechanisms in amorphous polymers and other glass-forming liquids, J. Am. Chem. Soc. 77, "
    "3701 (1955).",
    "10.1088/2051-672X/aa51f8": "T. D. B. Jacobs, T. Junge, L. Pastewka, Quantitative characterization of "
    "surface topography using spectral analysis, Surf. Topogr.: Metrol. Prop. 5, 013001 (2017).",
    "10.1016/j.apsadv.2021.100190": "A. Sanner, W. G. Nöhring, L. A. Thimons, T. D. B. Jacobs, L. Pastewka, "
    "Scale-dependent roughness parameters for topography analysis, Appl. Surf. Sci. Adv. 7, 100190 (2022).",
    "10.5254/1.3547607": "M. Klüppel, G. Heinrich, Rubber friction on self-affine road tracks, Rubber Chem. "
    "Technol. 73, 578 (2000).",
    "iso:13473-1:2019": "ISO 13473-1:2019, Characterization of pavement texture by use of surface profiles - "
    "Part 1: Determination of mean profile depth.",
    "isbn:9780080970165": "H. B. Pacejka, Tire and Vehicle Dynamics, 3rd ed., Butterworth-Heinemann, Oxford "
    "(2012): brush model (ch. 3), Magic Formula (ch. 4).",
    "10.1080/00423119208969994": "H. B. Pacejka, E. Bakker, The Magic Formula tyre model, Vehicle System "
    "Dynamics 21 (sup1), 1 (1992).",
    "sakai:ijvd-1981": "H. Sakai, Theoretical and experimental studies on the dynamic properties of tyres, "
    "Parts 1-4, Int. J. Vehicle Design 2 (1981).",
    "piarc:01.04.T-1995": "PIARC, International PIARC Experiment to Compare and Harmonize Texture and Skid "
    "Resistance Measurements, report 01.04.T, Paris (1995).",
    "hal:hal-00851262": "M.-T. Do, P. Marsac, A. Mosset, Tribology approach to predict the variation of "
    "tire/wet road friction with slip speed, 5th Symposium on Pavement Surface Characteristics (SURF 2004), "
    "Toronto (2004), HAL hal-00851262.",
    "rado:psu-phd-1994": "Z. Rado, A study of road surface texture and its relationship to friction, PhD "
    "thesis, The Pennsylvania State University (1994).",
    "isbn:978-0-471-04894-7": "J. D. Ferry, Viscoelastic Properties of Polymers, 3rd ed., Wiley, New York (1980).",
    "10.1214/ss/1038425655": "P. H. C. Eilers, B. D. Marx, Flexible smoothing with B-splines and penalties, "
    "Statist. Sci. 11, 89 (1996).",
    "10.1016/S0020-7683(98)00055-9": "S. W. Park, R. A. Schapery, Methods of interconversion between linear "
    "viscoelastic material functions. Part I - a numerical method based on Prony series, Int. J. Solids Struct. "
    "36, 1653 (1999).",
    "10.1137/1.9781611971217": "C. L. Lawson, R. J. Hanson, Solving Least Squares Problems, SIAM Classics in "
    "Applied Mathematics 15 (1995).",
    "10.1063/1.4919221": "B. Lorenz, Y. R. Oh, S. K. Nam, S. H. Jeon, B. N. J. Persson, Rubber friction on road "
    "surfaces: Experiment and theory for low sliding speeds, J. Chem. Phys. 142, 194701 (2015).",
    "arxiv:2602.22078": "B. N. J. Persson, N. Miyashita, Tire tread block dynamics, arXiv:2602.22078 (2026).",
    "10.1007/s11249-024-01838-4": "Y. Xu, L. Zhu, F. Xiao, Y. Zhou, A new fudge factor for Persson's theory of "
    "purely normal elastic rough surface contact, Tribol. Lett. 72 (2024).",
    "arxiv:1102.5412": "A. Almqvist, C. Campana, N. Prodanov, B. N. J. Persson, Interfacial separation between "
    "elastic solids with randomly rough surfaces: comparison between theory and numerical techniques, J. Mech. "
    "Phys. Solids 59, 2355 (2011).",
    "wang-muser:tribol-lett-65-2017": "A. Wang, M. H. Müser, Gauging Persson theory on adhesion, Tribol. Lett. "
    "65(3) (2017).",
    "10.1098/rspa.1966.0242": "J. A. Greenwood, J. B. P. Williamson, Contact of nominally flat surfaces, Proc. R. "
    "Soc. A 295, 300 (1966).",
    "10.1007/BF01520701": "H. C. Booij, G. P. J. M. Thoone, Generalization of Kramers-Kronig transforms and some "
    "approximations of relations between viscoelastic quantities, Rheol. Acta 21, 15 (1982).",
    "10.1137/0717021": "F. N. Fritsch, R. E. Carlson, Monotone piecewise cubic interpolation, SIAM J. Numer. Anal. "
    "17, 238 (1980).",
    "10.1137/0905021": "F. N. Fritsch, J. Butland, A method for constructing local monotone piecewise cubic "
    "interpolants, SIAM J. Sci. Stat. Comput. 5, 300 (1984).",
    "10.1007/BF01404567": "P. Craven, G. Wahba, Smoothing noisy data with spline functions, Numer. Math. 31, 377 "
    "(1979).",
    "10.1111/j.2517-6161.1974.tb00994.x": "M. Stone, Cross-validatory choice and assessment of statistical "
    "predictions, J. R. Stat. Soc. B 36, 111 (1974).",
    "isbn:9780120782505": "Y. Bard, Nonlinear Parameter Estimation, Academic Press, New York (1974).",
    "isbn:9780471617600": "G. A. F. Seber, C. J. Wild, Nonlinear Regression, Wiley, New York (1989): asymptotic "
    "confidence intervals for the regression function (ch. 5).",
    "isbn:9780198533689": "H. S. Carslaw, J. C. Jaeger, Conduction of Heat in Solids, 2nd ed., Oxford (1959).",
    "jaeger:jprsnsw-76-203-1942": "J. C. Jaeger, Moving sources of heat and the temperature at sliding contacts, "
    "J. Proc. R. Soc. N.S.W. 76, 203 (1942).",
    "blok:imeche-lubrication-1937": "H. Blok, Theoretical study of temperature rise at surfaces of actual contact "
    "under oiliness lubricating conditions, General Discussion on Lubrication and Lubricants, IMechE, vol. 2, 222 "
    "(1937).",
    "10.3390/lubricants11070277": "Study on the influence of environmental conditions on road friction "
    "characteristics, Lubricants 11(7), 277 (2023), published 26 June 2023 (authors not identified here; "
    "affiliations: College of Industrial Technology, Nihon University; Consortium on Advanced Road-Friction "
    "Database; Institute of Innovation for Future Society, Nagoya University; Faculty of Engineering, Osaka Sangyo "
    "University; Absolute Co., Ltd.): road-friction trailer with three fixed-slip tires, load-cell force balance "
    "(Eqs. 4-10), tire offset correction, three-point Magic Formula identification of peak and locked mu along the "
    "road.",
    "jcgm:100-2008": "JCGM 100:2008, Evaluation of measurement data - Guide to the expression of uncertainty in "
    "measurement (GUM), section 5.1 (law of propagation of uncertainty).",
    "vonneumann:ams-12-153-1941": "J. von Neumann, R. H. Kent, H. R. Bellinson, B. I. Hart, The mean square "
    "successive difference, Ann. Math. Statist. 12, 153 (1941).",
    "10.1080/01621459.1993.10476408": "P. J. Rousseeuw, C. Croux, Alternatives to the median absolute deviation, "
    "J. Am. Statist. Assoc. 88, 1273 (1993).",
    "isbn:9780750669184": "H. B. Pacejka, Tyre and Vehicle Dynamics, 2nd ed., Butterworth-Heinemann, Oxford (2006), "
    "Appendix 3, Table A3.1: Magic Formula coefficients of a measured 205/60 R15 passenger-car tyre.",
    "10.1088/0953-8984/27/17/175008": "G. Fortunato, V. Ciaravola, A. Furno, B. Lorenz, B. N. J. Persson, General "
    "theory of frictional heating with application to rubber friction, J. Phys.: Condens. Matter 27, 175008 (2015).",
    "10.1076/vesd.39.3.189.14152": "C. Canudas-de-Wit, P. Tsiotras, E. Velenis, M. Basset, G. Gissinger, Dynamic "
    "friction models for road/tire longitudinal interaction, Vehicle System Dynamics 39, 189 (2003).",
    "10.1080/10298436.2017.1369776": "M. Kane, M.-T. Do, V. Cerezo, Z. Rado, C. Khelifi, Contribution to pavement "
    "friction modelling: an introduction of the wetting effect, Int. J. Pavement Eng. (published online 6 September "
    "2017).",
    "kane:tire-pavement-tool": "Tire/pavement friction: presentation of a comprehensive physical tool through "
    "advanced contact modelling (authors and venue not identified; braking tests of a Renault Clio 3 on a "
    "university test track on the campus of Nantes, France; the element model of M. Kane and co-workers).",
    "10.1098/rstl.1886.0005": "O. Reynolds, On the theory of lubrication and its application to Mr. Beauchamp "
    "Tower's experiments, Phil. Trans. R. Soc. Lond. 177, 157 (1886).",
    "hamrock:fffl-2004": "B. J. Hamrock, S. R. Schmid, B. O. Jacobson, Fundamentals of Fluid Film Lubrication, 2nd "
    "ed., Marcel Dekker, New York (2004), ch. 8 (fixed-incline slider bearing).",
    "nasa:TN-D-2056": "W. B. Horne, R. C. Dreher, Phenomena of pneumatic tire hydroplaning, NASA TN D-2056 (1963).",
    "10.2346/1.2174340": "T. B. Rhyne, Development of a vertical stiffness relationship for belted radial tires, "
    "Tire Sci. Technol. 33, 136 (2005).",
    "10.1063/1.457480": "H. Flyvbjerg, H. G. Petersen, Error estimates on averages of correlated data, J. Chem. "
    "Phys. 91, 461 (1989).",
    "10.2307/1412159": "C. Spearman, The proof and measurement of association between two things, Am. J. Psychol. "
    "15, 72 (1904).",
    "10.1093/biomet/30.1-2.81": "M. G. Kendall, A new measure of rank correlation, Biometrika 30, 81 (1938).",
    "10.1109/TSMC.1979.4310076": "N. Otsu, A threshold selection method from gray-level histograms, IEEE Trans. "
    "Syst. Man Cybern. 9, 62 (1979).",
    "10.4271/741106": "I. A. Dijks, A multifactor examination of wet skid resistance of car tires, SAE Technical "
    "Paper 741106 (1974).",
    "leu-henry:trr-666-1978": "M. C. Leu, J. J. Henry, Prediction of skid resistance as a function of speed from "
    "pavement texture measurements, Transportation Research Record 666, 7 (1978).",
    "latorre-domenichini:vtri-2001": "F. La Torre, L. Domenichini, Friction prediction models, 2nd International "
    "Colloquium on Vehicle Tyre Road Interaction, Florence, paper 01.08B, 133 (2001).",
    "10.1098/rstl.1825.0026": "B. Gompertz, On the nature of the function expressive of the law of human mortality, "
    "Phil. Trans. R. Soc. Lond. 115, 513 (1825).",
    "stribeck:zvdi-46-1902": "R. Stribeck, Die wesentlichen Eigenschaften der Gleit- und Rollenlager, Z. Ver. Dtsch. "
    "Ing. 46, 1341, 1432, 1463 (1902).",
    "lampaert-swevers-albender:kuleuven-2002": "V. Lampaert, J. Swevers, F. Al-Bender, Experimental comparison of "
    "different friction models for accurate low-velocity tracking, KU Leuven, Department of Mechanical Engineering "
    "(2002).",
    "moore:friction-pneumatic-tyres-1975": "D. F. Moore, The Friction of Pneumatic Tyres, Elsevier, Amsterdam (1975).",
    "nasa:tn-d-2056": "W. B. Horne, R. C. Dreher, Phenomena of pneumatic tire hydroplaning, NASA Technical Note "
    "D-2056 (1963).",
    "10.1109/TAC.1974.1100705": "H. Akaike, A new look at the statistical model identification, IEEE Trans. Autom. "
    "Control 19, 716 (1974).",
    "10.1093/biomet/76.2.297": "C. M. Hurvich, C.-L. Tsai, Regression and time series model selection in small "
    "samples, Biometrika 76, 297 (1989).",
    "10.1214/aos/1176344136": "G. Schwarz, Estimating the dimension of a model, Ann. Stat. 6, 461 (1978).",
    "isbn:9780471170822": "N. R. Draper, H. Smith, Applied Regression Analysis, 3rd ed., Wiley, New York "
    "(1998).",
    "cook-weisberg:residuals-1982": "R. D. Cook, S. Weisberg, Residuals and Influence in Regression, Chapman and "
    "Hall, New York (1982).",
    "10.1137/0710036": "G. H. Golub, V. Pereyra, The differentiation of pseudo-inverses and nonlinear least squares "
    "problems whose variables separate, SIAM J. Numer. Anal. 10, 413 (1973).",
    "en:13036-4": "EN 13036-4, Road and airfield surface characteristics - Test methods - Part 4: Method for "
    "measurement of slip/skid resistance of a surface: the pendulum test.",
    "dealy-plazek:rheol-bull-78-16-2009": "J. M. Dealy, D. J. Plazek, Time-temperature superposition - a users "
    "guide, Rheology Bulletin 78 (2), 16 (2009).",
    "gent:engineering-with-rubber-2012": "A. N. Gent (ed.), Engineering with Rubber: How to Design Rubber "
    "Components, 3rd ed., Hanser, Munich (2012), ch. 3.",
    "timoshenko-gere:mechanics-of-materials-1972": "S. P. Timoshenko, J. M. Gere, Mechanics of Materials, Van "
    "Nostrand Reinhold, New York (1972).",
    "burckhardt:radschlupf-regelsysteme-1993": "M. Burckhardt, Fahrwerktechnik: Radschlupf-Regelsysteme, Vogel, "
    "Wuerzburg (1993).",
    "carbone:epje-29-275-2009": "G. Carbone, B. Lorenz, B. N. J. Persson, A. Wohlers, Contact mechanics and rubber "
    "friction for randomly rough surfaces with anisotropic statistical properties, Eur. Phys. J. E 29, 275 (2009).",
    "10.1140/epje/i2019-11844-5": "L. Afferrante, C. Putignano, N. Menga, G. Carbone, Friction in rough contacts of "
    "linear viscoelastic surfaces with anisotropic statistical properties, Eur. Phys. J. E 42, 80 (2019).",
    "10.1080/01621459.1995.10476572": "R. E. Kass, A. E. Raftery, Bayes factors, J. Am. Stat. Assoc. 90, 773 (1995).",
    "10.1214/aoms/1177731909": "A. Wald, J. Wolfowitz, On a test whether two samples are from the same "
    "population, Ann. Math. Stat. 11, 147 (1940).",
    "10.2307/3002019": "F. E. Satterthwaite, An approximate distribution of estimates of variance components, "
    "Biometrics Bulletin 2, 110 (1946).",
    "gasser:biometrika-73-625-1986": "T. Gasser, L. Sroka, C. Jennen-Steinmetz, Residual variance and residual "
    "pattern in nonlinear regression, Biometrika 73, 625 (1986).",
    "10.1093/biomet/70.1.1": "R. D. Cook, S. Weisberg, Diagnostics for heteroscedasticity in regression, "
    "Biometrika 70, 1 (1983).",
    "10.2307/1910133": "G. C. Chow, Tests of equality between sets of coefficients in two linear regressions, "
    "Econometrica 28, 591 (1960).",
    "10.1080/01621459.1987.10478472": "S. G. Self, K.-Y. Liang, Asymptotic properties of maximum likelihood "
    "estimators and likelihood ratio tests under nonstandard conditions, J. Am. Stat. Assoc. 82, 605 (1987).",
}


def doi(*keys: str) -> Callable[[F], F]:
    """Attach the references ``keys`` (DOIs) to a function or class.

    Parameters
    ----------
    *keys : str
        DOIs (``"10.xxxx/yyy"``) or other stable keys of the publications the object implements.

    Returns
    -------
    decorator
        Returns the object unchanged except for the tuple attribute ``__citations__`` (appended to any
        citations the object already carries).
    """
    if not keys or not all(isinstance(k, str) and k for k in keys):
        raise ValueError("doi() needs one or more non-empty reference strings")

    def attach(obj: F) -> F:
        previous = tuple(getattr(obj, "__citations__", ()))
        obj.__citations__ = previous + tuple(k for k in keys if k not in previous)  # type: ignore[attr-defined]
        return obj

    return attach


def citations_of(*objects: object) -> tuple[str, ...]:
    """Union, in first-seen order, of the ``__citations__`` of ``objects`` (functions, classes, results).

    Parameters
    ----------
    *objects : object
        Anything; objects without citations contribute nothing. Iterables of keys are accepted too.

    Returns
    -------
    tuple of str
        The reference keys.
    """
    seen: list[str] = []
    for obj in objects:
        if isinstance(obj, str):
            keys: Iterable[str] = (obj,)
        elif isinstance(obj, (tuple, list, set, frozenset)):
            keys = citations_of(*obj)
        else:
            keys = getattr(obj, "__citations__", None) or getattr(obj, "citations", None) or ()
            if not isinstance(keys, (tuple, list)):
                keys = ()  # e.g. a property object looked up on a class
        for k in keys:
            if k not in seen:
                seen.append(k)
    return tuple(seen)


def references(*objects: object) -> list[str]:
    """Formatted references for the citations of ``objects`` (unknown keys are shown as ``doi:key``)."""
    return [REFERENCES.get(k, f"doi:{k}" if k.startswith("10.") else k) for k in citations_of(*objects)]
