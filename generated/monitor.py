"""The divergence monitor's model-independent kernels (two-point start, scan, speed std).

GENERATED FILE: DO NOT EDIT.
Source: derive/codegen/monitor.py
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
import math

import numba as nb
import numpy as np

__all__ = ['maximum', 'minimum', 'two_point_into', 'two_point3_into', 'two_points', 'jacobian_point', 'initial_covariance_into', 'copy_row', 'pack_into', 'reinit_earlier_row', 'finite_row', 'largest_eigenvalue', 'speed_std_from', 'scan_segment', 'initial_covariances', 'jacobian_points', 'reinit_earlier_rows']


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
    common coordinates c and their variances var of the space of the positions z (N, d): in the plane (d = 2) c (6,) =
    (x, y, θ, v_x, v_y, ω) and ``heading`` (N,) or empty (no heading column); in 3-D space (d = 3, ``two_point3_into``)
    c (12,) = (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z) and ``heading`` the (roll, pitch, yaw) of
    every row flattened (3N,) or empty."""
    if z.shape[1] == 3:
        two_point3_into(t, z, heading, i0, i1, meas_std, omega_std, heading_std, heading_cap, sideslip, c, var)
        return
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
def two_point3_into(t, z, attitude, i0, i1, meas_std, omega_std, attitude_std, angle_cap, sideslip, c, var):
    """The two-point estimate of 3-D space (``two_point_into`` for z (N, 3)): c (12,) = (x, y, z, roll, pitch, yaw,
    v_x, v_y, v_z, ω_x, ω_y, ω_z) (Z-Y-X Euler angles, R = R_z(yaw) R_y(pitch) R_x(roll); body-frame velocity and rate,
    ``derive/space.py``) and their variances var (12,), from the world velocity w = (z_i1 − z_i0)/Δt, var σ_v² = 2r²/Δt²
    per axis.

    Without an attitude column (``attitude`` empty) the body's x axis is put along w: yaw = atan2(w_y, w_x) (the
    course), pitch = −atan2(w_z, |w_h|) (nose up for a climb), roll = 0, body velocity (|w|, 0, 0); var yaw =
    min(σ_v²/|w_h|², cap²), var pitch = min(σ_v²/|w|², cap²), var roll = cap² (the positions say nothing of it),
    var v_y = max(σ_v² − |w_h|² var yaw, (f σ_v)²), var v_z = max(σ_v² − |w|² var pitch, (f σ_v)²) (the velocity
    error across the motion the angles cannot take; f = ``sideslip``), as the plane's rule does for θ and v_y.
    With ``attitude`` (3N,) = the (roll, pitch, yaw) of every row: those angles (var ``attitude_std``² each), body
    velocity (w·R e_x, 0, 0), var v_y = var v_z = (f σ_v)². The rates are 0 with var ``omega_std``²."""
    dt = t[i1] - t[i0]
    w0 = (z[i1, 0] - z[i0, 0]) / dt
    w1 = (z[i1, 1] - z[i0, 1]) / dt
    w2 = (z[i1, 2] - z[i0, 2]) / dt
    hs = math.hypot(w0, w1)
    speed = math.hypot(hs, w2)
    r2 = meas_std ** 2
    var_v = 2.0 * r2 / dt ** 2
    floor = (sideslip ** 2) * var_v
    for k in range(12):
        c[k] = 0.0
    for k in range(3):
        c[k] = z[i1, k]
        var[k] = r2
        var[9 + k] = omega_std ** 2
    var[6] = var_v
    cap = angle_cap ** 2
    if attitude.shape[0] == 0:
        c[5] = math.atan2(w1, w0) if hs > 0 else 0.0
        c[4] = -math.atan2(w2, hs) if speed > 0 else 0.0
        c[6] = speed
        var_yaw = var_v / hs ** 2 if hs > 0 else np.inf
        var_pitch = var_v / speed ** 2 if speed > 0 else np.inf
        var[3] = cap
        var[4] = var_pitch if var_pitch <= cap or var_pitch != var_pitch else cap
        var[5] = var_yaw if var_yaw <= cap or var_yaw != var_yaw else cap
        var[7] = maximum(var_v - hs ** 2 * var[5], floor)
        var[8] = maximum(var_v - speed ** 2 * var[4], floor)
    else:
        for k in range(3):
            a = attitude[3 * i1 + k]
            c[3 + k] = math.atan2(math.sin(a), math.cos(a))
            var[3 + k] = attitude_std ** 2
        cp, sp_, cy, sy = math.cos(c[4]), math.sin(c[4]), math.cos(c[5]), math.sin(c[5])
        c[6] = w0 * cy * cp + w1 * sy * cp - w2 * sp_  # w · R e_x, R e_x = (cos yaw cos pitch, sin yaw cos pitch, −sin pitch)
        var[7] = floor
        var[8] = floor


@nb.njit(cache=True, nogil=True, error_model="numpy")
def two_points(t, z, heading, i0, i1, meas_std, omega_std, heading_std, heading_cap, sideslip, c, var):
    """``two_point_into`` of every row: rows i1 (R,) from i0 (R,), measurement std per row (R,); c, var (R, n_c)."""
    for k in range(i1.shape[0]):
        two_point_into(t, z, heading, i0[k], i1[k], meas_std[k], omega_std, heading_std, heading_cap, sideslip, c[k], var[k])


@nb.njit(cache=True, nogil=True, error_model="numpy")
def jacobian_point(c, var, out):
    """The common coordinates at which the initial covariance's Jacobian is taken: c with its forward speed v_x moved
    just off zero (at least 1e-9 of its std, keeping its sign) where a heading-of-motion coordinate is singular. v_x is
    the first coordinate of c's second half (position, attitude | velocity, rate): c[3] in the plane, c[6] in 3-D."""
    nc = c.shape[0]
    for k in range(nc):
        out[k] = c[k]
    s = nc // 2
    tiny = 1e-9 * math.sqrt(var[s])
    if abs(c[s]) < tiny:
        out[s] = -tiny if c[s] < 0 else tiny


@nb.njit(cache=True, nogil=True, error_model="numpy")
def initial_covariance_into(J, var, angles, P):
    """P = J diag(var) Jᵀ, symmetrised, each angle's variance capped at π² (its row and column scaled):
    the initial covariance in filter coordinates from the common-coordinate variances (J (n, n_c))."""
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
    """``initial_covariance_into`` of every row: J (B, n, n_c), var (B, n_c) into out (B, n, n)."""
    for b in range(J.shape[0]):
        initial_covariance_into(J[b], var[b], angles, out[b])


@nb.njit(cache=True, nogil=True, error_model="numpy")
def jacobian_points(c, var, out):
    """``jacobian_point`` of every row of c, var (B, n_c) into out (B, n_c)."""
    for b in range(c.shape[0]):
        jacobian_point(c[b], var[b], out[b])


@nb.njit(cache=True, nogil=True, error_model="numpy")
def reinit_earlier_rows(t, rows, obj_first, baseline, out):
    """``reinit_earlier_row`` of every re-initialisation row: rows (R,), obj_first (R,) into out (R,)."""
    for i in range(rows.shape[0]):
        out[i] = reinit_earlier_row(t, rows[i], obj_first[i], baseline)
