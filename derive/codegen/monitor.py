"""The divergence monitor of ``lgekf track``, compiled (``lgekf.apps.divergence``): templates of the emitter.

``MONITOR_HELPERS`` is the body of ``generated/monitor.py``: the model-independent parts (the two-point estimate and
the initial covariance of ``lgekf.core.initiation``, the earlier row of a re-initialisation, the finite check, the
NIS-window scan, the speed's std). ``MODEL_TEMPLATE`` (once per model) and ``RECOVER_TEMPLATE`` (once per model and
measurement) call the model's own kernels: the re-initialisation of one row, the speed's std, the first alarm of a
range of rows, and the whole monitor-and-recover loop of
``lgekf.apps.divergence.recover``, segment after segment, so that an alarm costs no round of Python (the noise
search's low-noise candidates on one long object raise an alarm every few hundred rows: 0.15 ms of Python each).
"""

import re

MONITOR_HELPERS = '''import math

import numba as nb
import numpy as np


@nb.njit(cache=True, nogil=True, error_model="numpy")
def maximum(a, b):
    """``np.maximum`` of two floats: nan if either is nan (unlike Python's ``max``)."""
    if a != a or b != b:
        return a + b
    return a if a >= b else b


@nb.njit(cache=True, nogil=True, error_model="numpy")
def minimum(a, b):
    """``np.minimum`` of two floats: nan if either is nan (unlike Python's ``min``)."""
    if a != a or b != b:
        return a + b
    return a if a <= b else b


@nb.njit(cache=True, nogil=True, error_model="numpy")
def two_point_into(t, z, heading, i0, i1, meas_std, omega_std, heading_std, heading_cap, sideslip, c, var):
    """The two-point estimate at row i1 from the measurements i0 and i1 (``lgekf.core.initiation.two_point``, one row):
    common coordinates c (6,) = (x, y, θ, v_x, v_y, ω) and their variances var (6,). ``heading`` (N,) or empty (no
    heading column)."""
    dt = t[i1] - t[i0]
    v0 = (z[i1, 0] - z[i0, 0]) / dt
    v1 = (z[i1, 1] - z[i0, 1]) / dt
    speed = math.hypot(v0, v1)
    r2 = meas_std ** 2
    var_v = 2.0 * r2 / dt ** 2
    floor_vy = (sideslip ** 2) * var_v
    for k in range(6):
        c[k] = 0.0
    c[0] = z[i1, 0]
    c[1] = z[i1, 1]
    var[0] = r2
    var[1] = r2
    var[3] = var_v
    var[5] = omega_std ** 2
    if heading.shape[0] == 0:
        c[2] = math.atan2(v1, v0) if speed > 0 else 0.0
        c[3] = speed
        var_th = var_v / speed ** 2 if speed > 0 else np.inf
        cap = heading_cap ** 2
        var[2] = var_th if var_th <= cap or var_th != var_th else cap  # np.minimum: nan stays nan
        var[4] = maximum(var_v - speed ** 2 * var[2], floor_vy)
    else:
        h = heading[i1]
        c[2] = math.atan2(math.sin(h), math.cos(h))
        c[3] = v0 * math.cos(h) + v1 * math.sin(h)
        var[2] = heading_std ** 2
        var[4] = floor_vy


@nb.njit(cache=True, nogil=True, error_model="numpy")
def two_points(t, z, heading, i0, i1, meas_std, omega_std, heading_std, heading_cap, sideslip, c, var):
    """``two_point_into`` of every row: rows i1 (R,) from i0 (R,), measurement std per row (R,); c, var (R, 6)."""
    for k in range(i1.shape[0]):
        two_point_into(t, z, heading, i0[k], i1[k], meas_std[k], omega_std, heading_std, heading_cap, sideslip, c[k], var[k])


@nb.njit(cache=True, nogil=True, error_model="numpy")
def jacobian_point(c, var, out):
    """The common coordinates at which the initial covariance's Jacobian is taken: c with its speed c[3] moved
    just off zero (at least 1e-9 of its std, keeping its sign) where a heading-of-motion coordinate is singular."""
    for k in range(6):
        out[k] = c[k]
    tiny = 1e-9 * math.sqrt(var[3])
    if abs(c[3]) < tiny:
        out[3] = -tiny if c[3] < 0 else tiny


@nb.njit(cache=True, nogil=True, error_model="numpy")
def initial_covariance_into(J, var, angles, P):
    """P = J diag(var) Jᵀ, symmetrised, each angle's variance capped at π² (its row and column scaled):
    the initial covariance in filter coordinates from the common-coordinate variances (J (n, 6))."""
    n = J.shape[0]
    for i in range(n):
        for k in range(n):
            acc = 0.0
            for j in range(J.shape[1]):
                acc = acc + (J[i, j] * var[j]) * J[k, j]
            P[i, k] = acc
    for i in range(n):
        for k in range(i + 1, n):
            v = 0.5 * (P[i, k] + P[k, i])
            P[i, k] = v
            P[k, i] = v
    s = np.empty(n)
    for a in angles:
        if P[a, a] > math.pi ** 2:
            for i in range(n):
                s[i] = 1.0
            s[a] = math.pi / math.sqrt(P[a, a])
            for i in range(n):
                for k in range(n):
                    P[i, k] *= s[i] * s[k]


@nb.njit(cache=True, nogil=True, error_model="numpy")
def copy_row(src, i, dst, j):
    """dst[j, :] = src[i, :] (a loop: a slice assignment would compile numba's shape-mismatch error message)."""
    for k in range(src.shape[1]):
        dst[j, k] = src[i, k]


@nb.njit(cache=True, nogil=True, error_model="numpy")
def pack_into(P, out):
    """The upper triangle of P (n, n), row-major, into out (n(n+1)/2,)."""
    idx = 0
    for i in range(P.shape[0]):
        for k in range(i, P.shape[0]):
            out[idx] = P[i, k]
            idx += 1


@nb.njit(cache=True, nogil=True, error_model="numpy")
def reinit_earlier_row(t, g, a, baseline):
    """The earlier row of a re-initialisation at row g of an object starting at row a: the latest j in [a, g) with
    t[j] <= t[g] - baseline (by bisection, t increasing), a if none, at most g - 1."""
    target = t[g] - baseline
    lo, hi = a, g
    while lo < hi:
        mid = (lo + hi) // 2
        if t[mid] <= target:
            lo = mid + 1
        else:
            hi = mid
    return min(max(a, lo - 1), g - 1)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def finite_row(x, p, r):
    """Every entry of x[r] and p[r] is finite."""
    for j in range(x.shape[1]):
        if not np.isfinite(x[r, j]):
            return False
    for j in range(p.shape[1]):
        if not np.isfinite(p[r, j]):
            return False
    return True


@nb.njit(cache=True, nogil=True, error_model="numpy")
def largest_eigenvalue(S, k):
    """The largest eigenvalue of the symmetric S[:k, :k] (overwritten; nan if an entry is not finite) by cyclic
    Jacobi rotations on S scaled by a power of two: quadratic convergence, to the rounding of S's entries (k is at most the state dimension here; no LAPACK, whose numba
    wrappers would triple the monitor's compiled code and start a second OpenBLAS)."""
    top = 0.0
    for a in range(k):
        for b in range(k):
            top = max(top, abs(S[a, b]))
    if top == 0.0 or not math.isfinite(top):
        return top if top == 0.0 else np.nan
    e = math.frexp(top)[1]  # S scaled by 2^-e (exactly) so that the sums of squares below neither overflow nor underflow
    for a in range(k):
        for b in range(k):
            S[a, b] = math.ldexp(S[a, b], -e)
    for sweep in range(64):
        off = 0.0
        diag = 0.0
        for a in range(k):
            diag += S[a, a] * S[a, a]
            for b in range(a + 1, k):
                off += S[a, b] * S[a, b]
        if off <= 1e-34 * diag or off == 0.0:
            break
        for a in range(k):
            for b in range(a + 1, k):
                if S[a, b] == 0.0:
                    continue
                theta = (S[b, b] - S[a, a]) / (2.0 * S[a, b])
                if abs(theta) > 1e150:
                    t = 0.5 / theta
                else:
                    t = 1.0 / (abs(theta) + math.sqrt(theta * theta + 1.0))
                    if theta < 0.0:
                        t = -t
                c = 1.0 / math.sqrt(t * t + 1.0)
                sn = t * c
                for r in range(k):  # S <- S G, then G^T S (G the rotation in the plane (a, b))
                    sa = S[r, a]
                    sb = S[r, b]
                    S[r, a] = c * sa - sn * sb
                    S[r, b] = sn * sa + c * sb
                for r in range(k):
                    sa = S[a, r]
                    sb = S[b, r]
                    S[a, r] = c * sa - sn * sb
                    S[b, r] = sn * sa + c * sb
    lam = S[0, 0]
    for a in range(1, k):
        lam = max(lam, S[a, a])
    return math.ldexp(lam, e)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def speed_std_from(grad, p, n):
    """|grad| √λ_max(P restricted to the coordinates the speed depends on) (``divergence.speed_std``), from the
    speed's gradient (n,) and the packed covariance p."""
    top = 1.0
    for i in range(n):
        top = max(top, abs(grad[i]))
    sel = np.empty(n, np.int64)
    k = 0
    for i in range(n):
        if abs(grad[i]) > 1e-9 * top:
            sel[k] = i
            k += 1
    if k == 0:
        return 0.0
    P = np.empty((n, n))
    idx = 0
    for i in range(n):
        for j in range(i, n):
            P[i, j] = p[idx]
            P[j, i] = p[idx]
            idx += 1
    S = np.empty((k, k))
    g2 = 0.0
    for a in range(k):
        g2 += grad[sel[a]] * grad[sel[a]]
        for b in range(k):
            S[a, b] = P[sel[a], sel[b]]
    lam = largest_eigenvalue(S, k)
    return math.sqrt(max(lam, 0.0)) * math.sqrt(g2)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def scan_segment(nis, absurd, over, bad, a, e, window, short, clip, thr, thr_short):
    """The first alarm of rows [a, e) from their NIS and the per-row tests ``bad`` (non-finite), ``over`` (speed over
    the limit) and ``absurd`` (confidently so): (row or -1, kind (1 NIS, 2 speed, 3 non-finite), value (the window's
    mean clipped NIS; 0 for speed, nan for non-finite), first flagged row (the NIS window's first update; for speed
    the first of the run of rows over the limit, at most ``window`` back)). NIS tests need ``short`` / ``window``
    updates since row a. Every row carries a NIS (no missed detections in ``lgekf track``). Each window's sum is
    added up afresh from its own rows (not a running sum), so that it does not depend on where the scan began: a
    scan from any row gives the same sums from there on (``lgekf.apps.windows``, the reruns' windows). A NaN NIS
    (possible through the library, not ``lgekf track``) silences only the windows that hold it."""
    count = 0
    run = 0
    for k in range(a, e):
        if bad[k]:
            return k, 3, np.nan, k
        run = run + 1 if over[k] else 0
        if absurd[k]:
            return k, 2, 0.0, k - min(run, window) + 1
        count += 1
        total_s = 0.0
        if count >= short:
            for j in range(k - short + 1, k + 1):
                total_s += min(nis[j], clip)
        total = 0.0
        if count >= window:
            for j in range(k - window + 1, k + 1):
                total += min(nis[j], clip)
        if count >= short and total_s > thr_short:
            return k, 1, total_s / short, k - short + 1
        if count >= window and total > thr:
            return k, 1, total / window, k - window + 1
    return -1, 0, 0.0, 0


@nb.njit(cache=True, nogil=True, error_model="numpy")
def initial_covariances(J, var, angles, out):
    """``initial_covariance_into`` of every row: J (B, n, 6), var (B, 6) into out (B, n, n)."""
    for b in range(J.shape[0]):
        initial_covariance_into(J[b], var[b], angles, out[b])


@nb.njit(cache=True, nogil=True, error_model="numpy")
def jacobian_points(c, var, out):
    """``jacobian_point`` of every row of c, var (B, 6) into out (B, 6)."""
    for b in range(c.shape[0]):
        jacobian_point(c[b], var[b], out[b])


@nb.njit(cache=True, nogil=True, error_model="numpy")
def reinit_earlier_rows(t, rows, obj_first, baseline, out):
    """``reinit_earlier_row`` of every re-initialisation row: rows (R,), obj_first (R,) into out (R,)."""
    for i in range(rows.shape[0]):
        out[i] = reinit_earlier_row(t, rows[i], obj_first[i], baseline)
'''

MONITOR_NAMES = re.findall(r"^def (\w+)\(", MONITOR_HELPERS, flags=re.M)  # what generated/monitor.py exports

MODEL_TEMPLATE = '''
@nb.njit(cache=True, nogil=True, error_model="numpy")
def reinit_into(
        t_all, z_all, heading_all, g, a, scale, meas_std, omega_std, heading_std, heading_cap, sideslip, baseline, angles, c, var,
        cj, J, P, x_out, p_out):
    """The re-initialisation at (global) row g of an object starting at row a: the two-point estimate from g and the
    latest row at least ``baseline`` s earlier, the measurement std times ``scale``: physical x_out (1, n) and packed
    p_out (n(n+1)/2,); c, cj (1, 6), var (6,), J (1, n, 6), P (n, n) scratch."""
    two_point_into(t_all, z_all, heading_all, reinit_earlier_row(t_all, g, a, baseline), g, meas_std * scale, omega_std, heading_std,
                   heading_cap, sideslip, c[0], var)
    jacobian_point(c[0], var, cj[0])
    common_to_states(c, x_out)
    common_jacobians(cj, J)
    initial_covariance_into(J[0], var, angles, P)
    pack_into(P, p_out)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def speed_std_at(x, p, k, xh, grad):
    """The std of the speed |world_velocity| of row k of physical states x (N, n) with packed covariances p: its
    gradient by central differences (steps 1e-6 max(1, |x_i|)) through ``speed_std_from``; xh (1, n), grad (n,) scratch."""
    n = x.shape[1]
    one = np.zeros(1, np.int64)
    spd = np.empty(1)
    for i in range(n):
        h = 1e-6 * max(1.0, abs(x[k, i]))
        for j in range(n):
            xh[0, j] = x[k, j]
        xh[0, i] = x[k, i] + h
        row_speeds(xh, one, spd)
        up = spd[0]
        xh[0, i] = x[k, i] - h
        row_speeds(xh, one, spd)
        grad[i] = (up - spd[0]) / (2 * h)
    return speed_std_from(grad, p[k], n)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def speed_stds(x, p, out):
    """``speed_std_at`` of every row of x (N, n), p (N, n(n+1)/2) into out (N,)."""
    xh = np.empty((1, x.shape[1]))
    grad = np.empty(x.shape[1])
    for k in range(x.shape[0]):
        out[k] = speed_std_at(x, p, k, xh, grad)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def first_alarm(
        x, p, nis, a, e, limit, window, short, clip, thr, thr_short, n_sigma, over, absurd, bad, sp, rows, xh, grad):
    """The first alarm of rows [a, e) of one object: (row or -1, kind (1 NIS, 2 speed, 3 non-finite), value (the
    window's mean NIS, the speed), first flagged row, limit (of the mean NIS, of the speed)); ``limit`` the object's
    speed limit. over, absurd, bad (N,) bool, sp (N,), rows (N,) int64, xh (1, n), grad (n,): scratch."""
    if e <= a:  # no row
        return -1, 0, 0.0, 0, limit
    R = e - a
    for k in range(R):
        rows[k] = a + k
    row_speeds(x, rows[:R], sp[:R])
    for k in range(a, e):
        fin = finite_row(x, p, k)
        bad[k] = not fin
        ov = fin and sp[k - a] > limit
        over[k] = ov
        absurd[k] = ov and sp[k - a] - n_sigma * speed_std_at(x, p, k, xh, grad) > limit
    g, kind, val, start = scan_segment(nis, absurd, over, bad, a, e, window, short, clip, thr, thr_short)
    if kind == 2:
        val = sp[g - a]
    if kind == 1:
        lim = thr_short / short if g - start + 1 == short else thr / window
    else:
        lim = limit
    return g, kind, val, start, lim

'''

RECOVER_TEMPLATE = '''
@nb.njit(cache=True, nogil=True, error_model="numpy")
def rerun_{meas}(zm, t, a, b, s1, p1, q, r, scale, q1, r1, x, p, nis):
    """Filter rows a .. b - 1 from the internal state s1 (1, ni) and packed covariance p1 (1, n(n+1)/2) of row a - 1, every
    noise std times ``scale`` (q1, r1 (1, nq), (1, nr) scratch), into x, p, nis; s1, p1 are left at row b - 1."""
    for j in range(q.shape[0]):
        q1[0, j] = q[j] * scale
    for j in range(r.shape[0]):
        r1[0, j] = r[j] * scale
    run_segments_noise_from_{meas}(zm, t, np.full(1, a, np.int64), np.full(1, b - a, np.int64), s1, p1, q1, r1, x, p, nis)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def recover_{meas}(
        x, p, nis, flag, seg_obj, seg_first, seg_end, run_first, run_s, run_p, run_scale0, limits, m, window, short, clip, thr,
        thr_short, n_sigma, max_reinit, repeat, max_inflation, rerun_rows, count, scale, last, zm, t, q, r, t_all, z_all,
        heading_all, offset, obj_first, meas_std, omega_std, heading_std, heading_cap, sideslip, baseline, angles, carry_s,
        carry_p, carry_scale, carry_reached):
    """The divergence monitor and recovery of ``lgekf.apps.divergence.recover``, segment after segment, compiled.

    Segment i is rows seg_first[i] .. seg_end[i] - 1 of object seg_obj[i]. Where run_first[i] >= 0 its rows run_first[i]
    .. seg_end[i] - 1 are filtered first, from the internal state run_s[i] and covariance run_p[i] of the row before, the
    noise stds times run_scale0[i] (the first pass of ``lgekf.apps.track.track_monitored``: one library with the
    filter's step per model instead of two); else they are in x, p, nis already. Each
    round scans rows for the first alarm (``first_alarm``); at an alarm the row is re-initialised (``reinit_into``, the
    measurements of global row + ``offset`` of t_all, z_all, heading_all; obj_first (B,) global) and the filter is
    run again over a window of ``rerun_rows`` rows that doubles until the next alarm or the segment's end, each window
    going on from the previous one's last state and scanned from max(window, short) rows before it. count, scale,
    last (B,): the objects' memory, updated in place; flag (N,) int8 set on the alarms' rows. carry_s, carry_p,
    carry_scale, carry_reached (B,): the filter's state, covariance and noise inflation after the segment's last row
    where a re-initialisation or a rerun reached it (carry_reached True). Returns the alarms (A, 8): obj, row, kind,
    value, limit, updates, reinitialised (1.0 / 0.0), scale, object after object, each object's in order."""
    N = x.shape[0]
    n = x.shape[1]
    over = np.zeros(N, np.bool_)
    absurd = np.zeros(N, np.bool_)
    bad = np.zeros(N, np.bool_)
    sp = np.empty(N)
    rows = np.empty(N, np.int64)
    xh = np.empty((1, n))
    grad = np.empty(n)
    reach = max(window, short)
    found = np.empty((16, 8))  # the alarms: obj, row, kind, value, limit, updates, reinitialised, scale (rows grow)
    na = 0
    s1 = np.empty((1, carry_s.shape[1]))
    p1 = np.empty((1, p.shape[1]))
    q1 = np.empty((1, q.shape[0]))
    r1 = np.empty((1, r.shape[0]))
    x0 = np.empty((1, n))
    p0 = np.empty(p.shape[1])
    c6 = np.empty((1, 6))
    var6 = np.empty(6)
    cj6 = np.empty((1, 6))
    J6 = np.empty((1, n, 6))
    P6 = np.empty((n, n))
    for si in range(seg_obj.shape[0]):
        o = seg_obj[si]
        first = seg_first[si]
        end = seg_end[si]
        scan_from = first
        scan_end = end
        run_scale = scale[o]  # the noise inflation of the run being scanned
        reached = False  # a run or a re-initialisation reached the segment's last row
        if run_first[si] >= 0:  # the first pass
            copy_row(run_s, si, s1, 0)
            copy_row(run_p, si, p1, 0)
            run_scale = run_scale0[si]
            rerun_{meas}(zm, t, run_first[si], end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
            reached = True
        while True:
            g, kind, val, start, lim = first_alarm(x, p, nis, scan_from, scan_end, limits[o], window, short, clip, thr, thr_short,
                                                   n_sigma, over, absurd, bad, sp, rows, xh, grad)
            if g < 0:
                if scan_end >= end:
                    break
                # no alarm in this window: the next, twice as wide, goes on from where the run stopped
                new_end = min(end, first + 2 * (scan_end - first))
                rerun_{meas}(zm, t, scan_end, new_end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
                scan_from = max(first, scan_end - reach)
                scan_end = new_end
                reached = scan_end == end
                continue
            count[o] += 1
            if kind == 1 and g - last[o] <= repeat * window:  # soon after the last re-initialisation: the noise is too small
                scale[o] *= minimum(math.sqrt(maximum(val / m, 1.0)), max_inflation)
            ok = count[o] <= max_reinit
            if na == found.shape[0]:
                more = np.empty((2 * na, 8))
                for i in range(na):
                    for j in range(8):
                        more[i, j] = found[i, j]
                found = more
            found[na, 0] = o
            found[na, 1] = g
            found[na, 2] = kind
            found[na, 3] = val
            found[na, 4] = lim
            found[na, 5] = g - start + 1 if kind == 1 else 0
            found[na, 6] = 1.0 if ok else 0.0
            found[na, 7] = scale[o]
            na += 1
            # the NIS of an update tests the estimate before it: flag from the row before the alarm's first update (not
            # before the segment's first row) through the alarm row
            for k in range(max(max(start, first) - 1, 0), g + 1):
                flag[k] = 1
            if not ok:  # max_reinit used up: no more monitoring; the run goes on to the segment's end
                if scan_end < end:
                    rerun_{meas}(zm, t, scan_end, end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
                    reached = True
                break
            last[o] = g
            reinit_into(t_all, z_all, heading_all, g + offset, obj_first[o], scale[o], meas_std, omega_std, heading_std, heading_cap,
                        sideslip, baseline, angles, c6, var6, cj6, J6, P6, x0, p0)
            copy_row(x0, 0, x, g)
            for j in range(p0.shape[0]):
                p[g, j] = p0[j]
            nis[g] = np.nan
            states_from_physical(x0, s1)
            for j in range(p0.shape[0]):
                p1[0, j] = p0[j]
            run_scale = scale[o]
            if g + 1 >= end:  # the re-initialised row is the segment's last
                reached = True
                break
            first = g + 1
            scan_from = first
            scan_end = min(end, first + rerun_rows)
            rerun_{meas}(zm, t, first, scan_end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
            reached = scan_end == end
        if reached:
            copy_row(s1, 0, carry_s, o)
            copy_row(p1, 0, carry_p, o)
            carry_scale[o] = run_scale
            carry_reached[o] = True
    return found[:na]
'''


# the helpers of generated/monitor.py that the templates call: imported into every generated model module
TEMPLATE_HELPERS = [name for name in MONITOR_NAMES if re.search(rf"\b{name}\(", MODEL_TEMPLATE + RECOVER_TEMPLATE)]


def model_monitor_kernels() -> list:
    """(label, source) of the monitor's kernels of one model (``MODEL_TEMPLATE``), for ``render_module``."""
    return [("monitor", MODEL_TEMPLATE)]


def measurement_monitor_kernels(meas: str) -> list:
    """(label, source) of the monitor's kernels of one model and measurement (``RECOVER_TEMPLATE``)."""
    return [(f"monitor_{meas}", RECOVER_TEMPLATE.replace("{meas}", meas))]
