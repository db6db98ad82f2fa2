"""Notes carry a machine-readable kind beside their text, and stay the text scripts already test for."""

import pickle
import warnings

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson.effects import FlashTemperature, Microtexture, PatchHeating
from persson.notes import KINDS, Note, kind_of, kind_of_warning, kinds

TREAD = materials.example_tread()
SMOOTH = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e5, rms_slope=0.3)
# a measured table: no roll-off declared, the tail past q_r extrapolated
Q = np.geomspace(1e3, 1e5, 9)
TABLE = surfaces.PSD(Q, 1e-18 * (Q / 1e3) ** -3.6, q_r=1e4, extrapolated=True)
COARSE = persson.GridSettings(q_per_decade=8)


def friction(surface, effects=(), grid=COARSE, speed=(0.01, 1.0)):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = persson.Model(surface, TREAD, effects=list(effects), grid=grid).friction(np.array(speed), pressure=3e5)
    return r, [w.category for w in caught]


def test_a_note_is_its_text_with_a_kind():
    n = Note("PSD tail extrapolated past q_r", "extrapolated")
    assert isinstance(n, str) and n == "PSD tail extrapolated past q_r" and "tail" in n
    assert n.kind == "extrapolated" and kind_of(n) == "extrapolated" and kind_of("plain text") is None
    assert f"note: {n}" == "note: PSD tail extrapolated past q_r"
    assert kinds((n, "plain")) == ("extrapolated", None)
    back = pickle.loads(pickle.dumps(n))
    assert back == n and back.kind == "extrapolated"
    with pytest.raises(persson.InputError, match="kind"):
        Note("text", "opinion")
    assert set(KINDS) == {"accuracy", "convergence", "extrapolated", "assumed", "physics", "input"}


def test_warning_categories_map_to_kinds():
    from persson._checks import UnitWarning

    assert kind_of_warning(persson.AccuracyWarning) == "accuracy"
    assert kind_of_warning(persson.ConvergenceWarning) == "convergence"
    assert kind_of_warning(persson.PhysicsWarning) == "physics"
    assert kind_of_warning(UnitWarning) == "input"


def test_an_extrapolated_tail_and_a_cut_psd_are_told_apart_by_kind():
    r, _ = friction(TABLE)
    assert r.note_kinds == ("extrapolated",) and "extrapolated" in r.notes[0]
    r, cats = friction(SMOOTH, [Microtexture(q1=3e4)])
    assert "input" in r.note_kinds and persson.PhysicsWarning in cats


def test_steep_roughness_is_a_physics_note():
    r, cats = friction(surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, rms_slope=5.0))
    assert r.note_kinds == ("physics",) and "rms slope" in r.notes[0] and persson.PhysicsWarning in cats


def test_an_estimate_above_the_tolerance_is_an_accuracy_note():
    r, cats = friction(SMOOTH, grid=persson.GridSettings(q_per_decade=4, tolerance=1e-12, max_refinement=0))
    assert r.note_kinds == ("accuracy",) and persson.AccuracyWarning in cats


def test_flash_temperature_notes_say_what_was_assumed_and_what_did_not_converge():
    r, _ = friction(TABLE, [FlashTemperature()], speed=(1.0,))
    assert set(r.note_kinds) == {"extrapolated", "assumed"}
    assert "roll-off" in r.notes[r.note_kinds.index("assumed")]
    r, cats = friction(SMOOTH, [FlashTemperature(max_iter=1)], grid=persson.GridSettings(q_per_decade=8,
                                                                                          max_refinement=0),
                       speed=(3.0,))
    assert not r.converged and "convergence" in r.note_kinds and persson.ConvergenceWarning in cats
    assert any("did not converge" in n for n in r.notes)


def test_kinds_survive_pickling_of_a_result_and_old_plain_notes_still_load():
    r, _ = friction(TABLE)
    back = pickle.loads(pickle.dumps(r))
    assert back.note_kinds == r.note_kinds == ("extrapolated",)
    old = r.replace(notes=tuple(str(n) for n in r.notes))  # a result pickled before notes had kinds
    assert pickle.loads(pickle.dumps(old)).note_kinds == (None,)


def test_contact_patch_and_slip_results_carry_kinds():
    c = persson.contact(TABLE, 1e6, 1e3)
    assert c.note_kinds == ("extrapolated",)
    r, _ = friction(SMOOTH, [PatchHeating()], speed=(1.0,))
    assert r.note_kinds == ("input",) and "contact patch" in r.notes[0]
    contact = persson.slip.Contact(length=0.02, width=0.01, stiffness=3e9)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = persson.slip.mu_slip(persson.Model(TABLE, TREAD, grid=COARSE), [0.05, 1.0], 1.0, pressure=3e5,
                                 contact=contact)
    assert s.note_kinds == ("extrapolated",)
