"""validation.rigs: a friction trailer's raw channels reduced back to the friction field that made them.

The synthetic runs are made here by an independent forward model of the trailer: a known mu(slip) field along a
road with two pavements (a Magic Formula per pavement, dry or wet), tires at fore/aft offsets braked at fixed
slips, normal loads that breathe, a chain whose tight side carries the braking torque, and load cells whose forces
solve the wheel assembly's balance (Eqs. 4-7 of the trailer article, solved here as 2x2 linear systems), plus noise
and a drifting load-cell offset. Zero rows (tires lifted: no force on the road) open and close each run.
"""

import math
import re
import warnings

import numpy as np
import pytest

import materials
import persson
import surfaces
import validation
from persson.slip import Contact
from persson.tire import magic_formula_from_points
from validation import ChannelWarning, InputError, rigs
from validation.errors import IdentificationWarning

G = 9.80665
RIG = {"tires": [
    dict(wheel_radius_m=0.30, offset_m=0.00, l_left_m=0.12, l_right_m=0.10, l_span_m=0.45, mass_kg=20.0),
    dict(wheel_radius_m=0.31, offset_m=0.78, l_left_m=0.11, l_right_m=0.12, l_span_m=0.40, mass_kg=22.0),
    dict(wheel_radius_m=0.30, offset_m=1.67, l_left_m=0.12, l_right_m=0.10, l_span_m=0.45, mass_kg=20.0),
]}
SLIPS = (0.05, 0.14, 0.35)        # set by the sprockets
STEP_M = 150.0                    # where pavement A ends and pavement B begins
#: Magic Formula (B, C, D) per pavement and condition: peak D, locked D sin(C atan B).
SURFACES = {("A", False): (12.0, 1.65, 1.20), ("B", False): (12.0, 1.70, 1.10),
            ("A", True): (12.0, 1.65, 0.95), ("B", True): (10.0, 1.80, 0.60)}
HZ = 100.0
SIGMA_CELL = 2.0                  # N, every load cell
ZERO_S = 1.0                      # s of zero rows at each end


def true_mu(s, x, wet, step_m=STEP_M):
    out = np.empty(np.broadcast(s, x).shape)
    s, x = np.broadcast_arrays(s, x)
    for pave, sel in (("A", x < step_m), ("B", x >= step_m)):
        B, C, D = SURFACES[(pave, wet)]
        out[sel] = D * np.sin(C * np.arctan(B * s[sel]))
    return out


def true_peak_lock(pave, wet):
    B, C, D = SURFACES[(pave, wet)]
    assert C > 1 and math.tan(math.pi / (2 * C)) / B < 1      # the peak lies inside 0 < s < 1
    return D, D * math.sin(C * math.atan(B))


def forward_run(seconds=40.0, *, wet=False, seed=0, drift=True, start_m=0.0, chain=True, noise=1.0, v0=12.0,
                step_m=STEP_M):
    """Raw channels of one run, and the truth: (columns, truth dict)."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, seconds, 1.0 / HZ)
    n = t.size
    dv = 0.4 * v0 / 12.0
    v = v0 + dv * np.sin(2 * np.pi * t / 9.0)
    x = start_m + v0 * t + dv * 9.0 / (2 * np.pi) * (1.0 - np.cos(2 * np.pi * t / 9.0))    # exact integral of v
    zero = (t < ZERO_S) | (t >= seconds - ZERO_S)
    cols = {"t_s": t, "v_m_s": v, "zero": zero.astype(float)}
    truth = {"x": x, "mu": [], "slip": []}
    for k, (tire, s0) in enumerate(zip(RIG["tires"], SLIPS), start=1):
        lL, lR, ls, m, r = (tire[c] for c in ("l_left_m", "l_right_m", "l_span_m", "mass_kg", "wheel_radius_m"))
        slip = np.full(n, s0)
        mu = true_mu(slip, x - tire["offset_m"], wet, step_m)
        load = 500.0 + 15.0 * np.sin(2 * np.pi * t / 1.3 + k)
        fb, nl = np.where(zero, 0.0, mu * load), np.where(zero, 0.0, load)
        pre = 250.0                                             # chain pretension, N
        fcu, fcd = pre + fb * r / 0.1, np.full(n, pre)          # the tight side carries the braking torque
        th = np.radians(4.0 + k)
        cx, cz = (fcu + fcd) * np.cos(th), (fcu - fcd) * np.sin(th)
        # x: FxL + FxR = F_B + cx (Eq. 4); lL FxL - lR FxR + ls cx = 0 (Eq. 7, l_c = l_s)
        fxl, fxr = np.linalg.solve(np.array([[1.0, 1.0], [lL, -lR]]), np.stack([fb + cx, -ls * cx]))
        # z: FzL + FzR + cz + m g = N (Eq. 5); -lL FzL + lR FzR + ls cz = 0 (Eq. 6)
        fzl, fzr = np.linalg.solve(np.array([[1.0, 1.0], [-lL, lR]]), np.stack([nl - cz - m * G, -ls * cz]))
        e = noise * rng.standard_normal((4, n))
        cols[f"fxl_{k}_N"] = fxl + SIGMA_CELL * e[0] + (0.5 * t if drift and k == 2 else 0.0)
        cols[f"fxr_{k}_N"] = fxr + SIGMA_CELL * e[1]
        cols[f"fzl_{k}_N"] = fzl + SIGMA_CELL * e[2]
        cols[f"fzr_{k}_N"] = fzr + SIGMA_CELL * e[3] + (0.4 * t if drift and k == 1 else 0.0)
        omega = v * (1.0 - slip) / r + noise * 0.002 * v / r * rng.standard_normal(n)
        cols[f"omega_{k}_rad_s"] = np.where(zero, v / r, omega)
        if chain:
            cols[f"fcu_{k}_N"] = fcu + noise * rng.standard_normal(n)
            cols[f"fcd_{k}_N"] = fcd + noise * rng.standard_normal(n)
            cols[f"theta_{k}_deg"] = np.full(n, 4.0 + k)
        truth["mu"].append(mu)
        truth["slip"].append(slip)
    return cols, truth


def write_csv(path, cols, fmt="%.6f"):
    names = list(cols)
    np.savetxt(path, np.column_stack([cols[c] for c in names]), delimiter=",", header=",".join(names),
               comments="", fmt=fmt)
    return path


@pytest.fixture(scope="module")
def dry_run(tmp_path_factory):
    cols, truth = forward_run(40.0, wet=False, seed=1)
    path = write_csv(tmp_path_factory.mktemp("rig") / "dry.csv", cols)
    raw = rigs.read_trailer(path, RIG)
    return cols, truth, raw


# ---- the reduction: Eqs. 8-10, zero offsets, slip (Eq. 1), running position -----------------------------------
def test_synthetic_run_reduces_back_to_its_friction_within_the_noise(dry_run):
    cols, truth, raw = dry_run
    rows = rigs.reduce(raw, RIG, align=False)
    assert rows.balance.ok, rows.balance.summary()
    measured = cols["zero"] == 0
    for k in (1, 2, 3):
        tire = rows.for_tire(k)
        assert tire.n == int(measured.sum())
        mu_true = truth["mu"][k - 1][measured]
        r = tire.mu - mu_true
        # noise of one sample: the cells' noise through Eqs. 8-10
        t = RIG["tires"][k - 1]
        a, b = 1 + t["l_left_m"] / t["l_span_m"], 1 - t["l_right_m"] / t["l_span_m"]
        sigma = SIGMA_CELL * math.hypot(a, b) * np.sqrt(1.0 + mu_true ** 2) / 500.0
        assert np.std(r) == pytest.approx(np.sqrt(np.mean(sigma ** 2)), rel=0.06)
        assert rows.noise[k - 1] == pytest.approx(np.sqrt(np.mean(sigma ** 2)), rel=0.08)
        # what the zero offsets leave: two block medians of 100 samples (efficiency 2/pi), shared by every row
        offset = math.sqrt(math.pi / 2) * np.sqrt(np.mean(sigma ** 2)) / math.sqrt(2 * 100)
        assert rows.offset_std[k - 1] == pytest.approx(offset, rel=0.2)
        # the drifting offsets are gone: the mean error is within what the noise and the zero offsets leave
        assert abs(np.mean(r)) < 4 * math.hypot(np.std(r) / math.sqrt(r.size), rows.offset_std[k - 1])
        np.testing.assert_allclose(tire.slip.mean(), SLIPS[k - 1], atol=3e-4)
    # the running position is the integral of the speed (exact here), to 1 mm over 480 m
    np.testing.assert_allclose(rows.for_tire(1).position, truth["x"][measured], atol=1e-3)


def test_without_zero_rows_the_drift_goes_into_mu(dry_run):
    cols, truth, _ = dry_run
    keep = cols["zero"] == 0
    raw = rigs.TrailerRun.from_columns({c: a[keep] for c, a in cols.items() if c != "zero"}, RIG)
    rows = rigs.reduce(raw, RIG, align=False)
    assert any("no zero rows" in n for n in rows.notes)
    r = rows.for_tire(2).mu - truth["mu"][1][keep]
    assert abs(np.mean(r)) > 20 * np.std(r) / math.sqrt(r.size)        # the same check as above fails


# ---- alignment of the tires' offsets ---------------------------------------------------------------------------
def _step_position(x, y):
    """Where a single step in y(x) lies: the split minimising the squared error of two constant levels."""
    order = np.argsort(x)
    x, y = x[order], y[order]
    c1, c2 = np.cumsum(y), np.cumsum(y * y)
    i = np.arange(1, x.size)
    left = c2[i - 1] - c1[i - 1] ** 2 / i
    right = (c2[-1] - c2[i - 1]) - (c1[-1] - c1[i - 1]) ** 2 / (x.size - i)
    j = int(np.argmin(left + right)) + 1
    return 0.5 * (x[j - 1] + x[j])


@pytest.mark.parametrize("v0, step_m", [(12.0, STEP_M), (5 / 3.6, 30.0), (65 / 3.6, STEP_M)])
def test_alignment_recovers_a_step_in_friction_at_its_road_position(dry_run, v0, step_m):
    raw = dry_run[2] if v0 == 12.0 else rigs.TrailerRun.from_columns(forward_run(40.0, v0=v0, step_m=step_m)[0], RIG)
    spacing = v0 / HZ
    aligned = rigs.reduce(raw, RIG, align=True)
    plain = rigs.reduce(raw, RIG, align=False)
    for k, tire in enumerate(RIG["tires"], start=1):
        a, p = aligned.for_tire(k), plain.for_tire(k)
        assert _step_position(a.position, a.mu) == pytest.approx(step_m, abs=1.5 * spacing)
        assert _step_position(p.position, p.mu) == pytest.approx(step_m + tire["offset_m"], abs=1.5 * spacing)
    # aligned rows share the road positions of tire 1 where every tire has been
    np.testing.assert_array_equal(aligned.for_tire(3).position, aligned.for_tire(1).position)
    # the notes give the offsets in samples (13.9 for tire 3 at 12 m/s and 100 Hz)
    shift = [float(m) for n in aligned.notes for m in re.findall(r"tire 3: ([0-9.]+)", n)]
    assert shift == [pytest.approx(1.67 / (v0 / HZ), rel=0.01)]


def test_peak_and_locked_mu_along_the_road_with_and_without_alignment(dry_run):
    _, _, raw = dry_run
    step = 2.0
    prof = rigs.peak_lock_along_road(rigs.reduce(raw, RIG, align=True), step_m=step, start_m=0.0)
    plain = rigs.peak_lock_along_road(rigs.reduce(raw, RIG, align=False), step_m=step, start_m=0.0)
    assert prof.identified.all()
    for pave, sel in (("A", prof.position + step / 2 <= STEP_M), ("B", prof.position - step / 2 >= STEP_M)):
        peak, lock = true_peak_lock(pave, False)
        assert np.all(np.abs(prof.peak_mu[sel] - peak) < 4.5 * prof.peak_mu_std[sel])
        assert np.all(np.abs(prof.locked_mu[sel] - lock) < 4.5 * prof.locked_mu_std[sel])
    # without the offsets corrected, the bin just behind the step mixes both pavements (tire 3 still on A for
    # 1.67 of its 2 m): its locked mu is far off even for its own, widened, uncertainty; the aligned one is right
    first_b = int(np.argmin(np.abs(plain.position - (STEP_M + step / 2))))
    lock_b = true_peak_lock("B", False)[1]
    assert abs(plain.locked_mu[first_b] - lock_b) > 4 * plain.locked_mu_std[first_b]
    assert abs(plain.locked_mu[first_b] - lock_b) > 10 * prof.locked_mu_std[first_b]
    assert abs(prof.locked_mu[first_b] - lock_b) < 4.5 * prof.locked_mu_std[first_b]


def test_uncertainties_cover_the_scatter_of_repeated_runs():
    z_peak, z_lock, profiles = [], [], []
    peak, lock = true_peak_lock("A", False)
    for seed in range(12):
        cols, _ = forward_run(24.0, seed=100 + seed, drift=False, chain=False)
        raw = rigs.TrailerRun.from_columns(cols, RIG)
        prof = rigs.peak_lock_along_road(rigs.reduce(raw, RIG, check=False), step_m=3.0, start_m=0.0)
        sel = prof.position + 1.5 <= STEP_M
        z_peak.append((prof.peak_mu[sel] - peak) / prof.peak_mu_std[sel])
        z_lock.append((prof.locked_mu[sel] - lock) / prof.locked_mu_std[sel])
        profiles.append(prof)
    for z in (np.concatenate(z_peak), np.concatenate(z_lock)):
        assert z.size > 500
        assert 0.85 < np.std(z) < 1.15
        assert abs(np.mean(z)) < 0.2
        assert 0.91 < np.mean(np.abs(z) < 1.96) < 0.985
    # two runs over the same pavement: the peak reduction is 0; its standard error keeps the zero offsets' share,
    # which averaging the positions does not reduce (without it, sum z^2 = 22 here)
    z = [r.reduction / r.reduction_std for a, b in zip(profiles[0::2], profiles[1::2])
         for r in rigs.peak_reduction_by_pavement(a, b, {"A": (15.0, STEP_M)})]
    assert np.sum(np.square(z)) < 16.8      # chi-square, 6 degrees of freedom, 99th percentile


# ---- the force balance --------------------------------------------------------------------------------------------
def test_force_balance_flags_a_broken_channel_and_reduce_leaves_it_out(dry_run):
    cols, _, raw = dry_run
    assert rigs.check_balance(raw, RIG).ok                 # no false alarm on 3 x 2 x 4000 residuals
    bad = {c: a.copy() for c, a in cols.items()}
    bad["fxr_3_N"][2000:2600] += 60.0                      # a loose connector: a step of 60 N
    bad["fzl_2_N"][3000:3200] = bad["fzl_2_N"][3000]       # a stalled channel
    broken = rigs.TrailerRun.from_columns(bad, RIG, source="broken.csv")
    check = rigs.check_balance(broken, RIG)
    by_kind = {(f.tire, f.kind): f for f in check.flags}
    assert set(by_kind) == {(3, "moment_x"), (2, "frozen"), (2, "moment_z")}
    step = by_kind[(3, "moment_x")]
    assert step.channels == ("fxr_3_N",) and abs(step.start - 2000) <= 2 and abs(step.stop - 2600) <= 2
    assert "tire 3" in step.message and "'fxr_3_N'" in step.message and "rows 2001-2600" in step.message
    frozen = by_kind[(2, "frozen")]
    assert (frozen.start, frozen.stop, frozen.channels) == (3000, 3200, ("fzl_2_N",))
    assert by_kind[(2, "moment_z")].channels == ("fzl_2_N",)
    with pytest.warns(ChannelWarning, match="fxr_3_N"):
        rows = rigs.reduce(broken, RIG, align=False)
    t3 = rows.for_tire(3).time
    assert not np.any((t3 >= broken.time[2001]) & (t3 <= broken.time[2598]))
    assert rows.for_tire(1).n == int((cols["zero"] == 0).sum())        # the other tires keep every sample


# ---- rows as measurements -------------------------------------------------------------------------------------------
def test_reduced_rows_go_through_compare_as_they_are(dry_run, tmp_path):
    _, _, raw = dry_run
    rows = rigs.reduce(raw, RIG)
    contact = Contact(length=0.1, width=0.1, stiffness=3e9)
    model = persson.Model(surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e5, hrms=1e-4),
                          materials.ConstantModulus(E_storage=5e6, E_loss=2e6))
    binned = rows.binned(40.0)
    meas = binned.to_measurements(temperature=20.0, pressure=2e5, contact=contact, series="dry")
    assert meas.n == binned.n and meas.series_labels == ("dry, tire 1", "dry, tire 2", "dry, tire 3")
    np.testing.assert_array_equal(meas.position, binned.position)
    np.testing.assert_array_equal(meas.mu_std, binned.mu_std)
    cmp = validation.compare(model, meas)
    np.testing.assert_allclose(cmp.residual, meas.mu - cmp.predicted)
    # single samples too, with the position written to and read from the measurement format
    few = rows.subset(np.arange(rows.n) % 400 == 0).to_measurements(temperature=20.0, pressure=2e5, contact=contact)
    assert validation.compare(model, few).n == few.n
    back = validation.read_measurements(few.to_csv(tmp_path / "rows.csv"))
    np.testing.assert_allclose(back.position, few.position)


# ---- the three-point identification ---------------------------------------------------------------------------------
@pytest.mark.parametrize("B, C, D", [
    (12.0, 1.65, 1.2),      # dry road: peak near s = 0.1
    (25.0, 1.9, 0.3),       # wet low-friction road, steep rise, locked mu far below the peak
    (3.0, 1.3, 0.9),        # soft tire: peak near s = 0.5
    (2.0, 0.9, 0.8),        # no peak: the curve still rises at s = 1
])
def test_batched_identification_matches_the_project_one(B, C, D):
    s = np.array([0.05, 0.14, 0.35])
    rng = np.random.default_rng(3)
    levels = 1.0 + 0.1 * rng.standard_normal(3)
    m = D * levels[:, None] * np.sin(C * np.arctan(B * s))[None, :]
    n = len(levels)
    rows = rigs.TrailerRows(position=np.repeat(np.arange(n) + 0.5, 3 * 2), tire=np.tile(np.repeat([1, 2, 3], 2), n),
                            slip=np.tile(np.repeat(s, 2), n), speed=np.full(6 * n, 12.0),
                            mu=np.repeat(m, 2, axis=1).ravel(), time=np.zeros(6 * n), noise=(1e-3,) * 3,
                            slip_noise=(1e-4,) * 3)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        prof = rigs.peak_lock_along_road(rows, step_m=1.0, start_m=0.0)
    for i in range(n):
        ref = magic_formula_from_points(s, m[i])
        np.testing.assert_allclose([prof.B[i], prof.C[i], prof.D[i]], [ref.B, ref.C, ref.D], rtol=1e-7)
        assert prof.peak_mu[i] == pytest.approx(ref.peak_mu, rel=1e-9)
        assert prof.slip_at_peak[i] == pytest.approx(ref.slip_at_peak, abs=1e-6)
        assert prof.locked_mu[i] == pytest.approx(ref.locked_mu, rel=1e-12)
    assert (C < 1) == any("still rises at s = 1" in note for note in prof.notes)


def test_positions_without_three_points_are_reported():
    rows = rigs.TrailerRows(position=np.array([0.5, 0.6, 0.5, 0.6, 1.5, 1.6]), tire=np.array([1, 1, 2, 2, 3, 3]),
                            slip=np.repeat([0.05, 0.14, 0.35], 2), speed=np.full(6, 12.0),
                            mu=np.repeat([0.8, 1.0, 0.9], 2), time=np.zeros(6), noise=(1e-3,) * 3,
                            slip_noise=(1e-4,) * 3)
    with pytest.warns(IdentificationWarning, match="fewer than 2 samples"):
        prof = rigs.peak_lock_along_road(rows, step_m=1.0, start_m=0.0)
    assert not prof.identified.any() and np.isnan(prof.peak_mu).all()
    with pytest.raises(InputError, match="three tires"):
        rigs.peak_lock_along_road(rows.subset(rows.tire < 3), step_m=1.0)


def test_dry_against_wet_gives_the_peak_reduction_per_pavement(dry_run):
    _, _, raw = dry_run
    wet_cols, _ = forward_run(40.0, wet=True, seed=2)
    wet_raw = rigs.TrailerRun.from_columns(wet_cols, RIG, source="wet")
    dry = rigs.peak_lock_along_road(rigs.reduce(raw, RIG), step_m=4.0, start_m=0.0)
    wet = rigs.peak_lock_along_road(rigs.reduce(wet_raw, RIG), step_m=4.0, start_m=0.0)
    out = rigs.peak_reduction_by_pavement(dry, wet, {"A": (20.0, STEP_M), "B": (STEP_M, 440.0)})
    for r in out:
        expected = true_peak_lock(r.name, False)[0] - true_peak_lock(r.name, True)[0]
        assert r.reduction == pytest.approx(expected, abs=4 * r.reduction_std)
        assert r.reduction_std < 0.01
    assert out[1].relative == pytest.approx(0.5 / 1.1, abs=0.02)     # the low-friction pavement loses half
    with pytest.raises(InputError, match="start_m"):
        rigs.peak_reduction_by_pavement(dry, rigs.peak_lock_along_road(rigs.reduce(wet_raw, RIG), step_m=4.0,
                                                                        start_m=1.0), {"A": (20.0, 100.0)})


# ---- bad input --------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def small_csv(tmp_path_factory):
    cols, _ = forward_run(4.0, seed=5, chain=False)
    return write_csv(tmp_path_factory.mktemp("bad") / "run.csv", cols).read_text().splitlines()


def _edit(lines, row, column, value):
    header = lines[0].split(",")
    cells = lines[row].split(",")
    cells[header.index(column)] = value
    return lines[:row] + [",".join(cells)] + lines[row + 1:]


@pytest.mark.parametrize("edit, words", [
    (lambda L: [",".join(c for c in L[0].split(",") if c != "omega_2_rad_s")] + L[1:],
     ["line 1", "'omega_2_rad_s'", "missing"]),
    (lambda L: L[:150] + [L[151], L[150]] + L[152:], ["line 152", "data row 151", "'t_s'", "increase"]),
    (lambda L: _edit(L, 160, "v_m_s", "0"), ["line 161", "data row 160", "'v_m_s'", "moving"]),
    (lambda L: _edit(_edit(L, 170, "fzl_1_N", "-300"), 170, "fzr_1_N", "-250"),
     ["line 171", "'fzl_1_N'", "'fzr_1_N'", "normal load of tire 1", "> 0"]),
    (lambda L: _edit(L, 180, "fxl_3_N", "n/a"), ["line 181", "'fxl_3_N'", "'n/a'"]),
    (lambda L: _edit(L, 190, "zero", "2"), ["line 191", "'zero'", "0 (measured row) or 1"]),
    (lambda L: [L[0]] + [_kmh(x) for x in L[1:]], ["'v_m_s'", "km/h"]),
])
def test_bad_channels_name_the_file_line_and_column(tmp_path, small_csv, edit, words):
    path = tmp_path / "bad.csv"
    path.write_text("\n".join(edit(list(small_csv))) + "\n")
    with pytest.raises(InputError) as err:
        rigs.read_trailer(path, RIG)
    for w in ["bad.csv"] + words:
        assert w in str(err.value)


def _kmh(line):
    cells = line.split(",")
    cells[1] = f"{float(cells[1]) * 3.6 * 3:.4f}"
    return ",".join(cells)


def test_wheel_speed_in_rpm_is_caught(tmp_path, small_csv):
    header = small_csv[0].split(",")
    j = header.index("omega_1_rad_s")
    lines = [small_csv[0]] + [",".join(c if i != j else f"{float(c) * 60 / (2 * np.pi):.4f}"
                                       for i, c in enumerate(x.split(","))) for x in small_csv[1:]]
    path = tmp_path / "rpm.csv"
    path.write_text("\n".join(lines))
    with pytest.raises(InputError, match="'omega_1_rad_s'.*rpm"):
        rigs.read_trailer(path, RIG)


@pytest.mark.parametrize("change, words", [
    ({"wheel_radus_m": 0.3}, ["unknown key 'wheel_radus_m'", "did you mean 'wheel_radius_m'"]),
    ({"wheel_radius_m": 300.0}, ["tire 2", "wheel_radius_m = 300", "mm"]),
    ({"mass_kg": 220.0 * G}, ["mass_kg", "weight in N"]),
    ({"l_span_m": 0.0}, ["l_span_m = 0", "> 0"]),
    ({"offset_m": "0.78"}, ["offset_m", "expected a number"]),
])
def test_bad_rig_keys_are_named(change, words):
    tires = [dict(t) for t in RIG["tires"]]
    if "wheel_radus_m" in change:
        del tires[1]["wheel_radius_m"]
    tires[1].update(change)
    with pytest.raises(InputError) as err:
        rigs.rig_from_dict({"tires": tires}, source="case.toml: [rig]")
    for w in ["case.toml: [rig]"] + words:
        assert w in str(err.value)


def test_rig_from_a_case_file(tmp_path):
    text = "name = \"trailer\"\n" + "".join(
        "[[rig.tires]]\n" + "".join(f"{k} = {v}\n" for k, v in t.items()) for t in RIG["tires"])
    path = tmp_path / "case.toml"
    path.write_text(text)
    rig = rigs.load_rig(path)
    assert rig.n_tires == 3 and rig.tire(2).offset_m == 0.78 and rig.tire(2).chain_arm_m == 0.40
    path.write_text("name = \"x\"\n")
    with pytest.raises(InputError, match=r"no \[rig\] table"):
        rigs.load_rig(path)


def test_fixed_slips_columns_and_citations(dry_run):
    cols, _, _ = dry_run
    rig = {"tires": [dict(t, slip=s) for t, s in zip(RIG["tires"], SLIPS)]}
    no_omega = {c: a for c, a in cols.items() if not c.startswith("omega_")}
    rows = rigs.reduce(rigs.TrailerRun.from_columns(no_omega, rig), rig, align=False)
    for k, s in enumerate(SLIPS, start=1):
        np.testing.assert_array_equal(rows.for_tire(k).slip, s)          # the sprockets' slip, as given
    np.testing.assert_array_equal(rows["position_m"], rows.position)
    assert list(rows.as_table())[:5] == ["position_m", "tire", "slip", "speed_m_s", "mu"]
    with pytest.raises(InputError, match=r"row 1 \(tire 1, position .*slip = -0.01"):
        rigs.TrailerRows(position=[0.0], tire=[1], slip=[-0.01], speed=[12.0], mu=[0.1],
                         time=[0.0]).to_measurements(temperature=20.0, pressure=2e5)
    import frictioncite
    refs = frictioncite.references(rigs.reduce, rigs.peak_lock_along_road, rigs.check_balance)
    assert any("Lubricants 11(7), 277 (2023)" in r for r in refs)
    assert any("Magic Formula" in r for r in refs) and any("uncertainty in measurement" in r for r in refs)


def test_a_rig_table_in_a_case_file_is_checked_and_built_by_load_case(tmp_path):
    import shutil
    from pathlib import Path

    from validation.rigs import Rig

    src = Path(validation.__file__).parent / "cases" / "example"
    case = tmp_path / "example"
    shutil.copytree(src, case)
    tires = "".join(f"""
[[rig.tires]]
wheel_radius_m = 0.30
offset_m = {off}
l_left_m = 0.12
l_right_m = 0.10
l_span_m = 0.45
mass_kg = 20.0
""" for off in (0.0, 0.78))
    (case / "case.toml").write_text((case / "case.toml").read_text() + tires)
    loaded = validation.load_case(case / "case.toml")
    assert isinstance(loaded.rig, Rig) and loaded.rig.n_tires == 2
    (case / "case.toml").write_text((case / "case.toml").read_text().replace("mass_kg = 20.0", "mas_kg = 20.0", 1))
    with pytest.raises(validation.InputError, match=r"rig.*tires\[0\].*mas_kg.*mass_kg"):
        validation.load_case(case / "case.toml")
