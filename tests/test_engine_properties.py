"""Properties the contact mechanics must have for any surface and modulus (hypothesis-generated cases)."""

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import materials
import persson
import surfaces

cases = st.fixed_dictionaries({
    "hurst": st.floats(0.3, 0.95),
    "hrms": st.floats(1e-6, 1e-3),
    "q0": st.floats(1e2, 1e4),
    "decades": st.floats(1.0, 4.0),
    "E1": st.floats(1e6, 1e9),
    "tan_delta": st.floats(0.0, 1.5),
    "pressure": st.floats(1e4, 2e6),
    "gamma": st.floats(0.0, 1.0),
})


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(cases)
def test_contact_area_and_friction_are_physical(c):
    s = surfaces.SelfAffine(hurst=c["hurst"], q0=c["q0"], q1=c["q0"] * 10 ** c["decades"], hrms=c["hrms"])
    m = materials.ConstantModulus(c["E1"], c["E1"] * c["tan_delta"])
    model = persson.Model(s, m, gamma=c["gamma"])
    r = model.friction(1.0, pressure=c["pressure"])
    P = r.area_q[0]
    assert 0.0 < r.contact_area <= 1.0
    assert P[0] == 1.0 and np.all(np.diff(P) <= 1e-15)        # contact only shrinks with magnification
    assert np.all(np.diff(r.G_q[0]) >= 0)                      # G is a cumulative integral of a positive integrand
    assert r.mu >= 0.0 and np.isfinite(r.mu)
    assert r.mean_separation >= 0 and np.isfinite(r.mean_separation)  # 0 to double precision in full contact
    higher = model.friction(1.0, pressure=2 * c["pressure"])
    assert higher.contact_area >= r.contact_area               # more load, more contact
    assert higher.mean_separation <= r.mean_separation         # ... and a smaller gap
