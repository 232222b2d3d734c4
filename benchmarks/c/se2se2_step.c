/* Hand-unrolled scalar C baseline of the SE(2)xSE(2) LG-EKF step with a position measurement.
 *
 * The same filter as generated/se2se2.py predict + update_position (same Q, same safeguards):
 *   predict: mu <- mu exp(Omega(mu)) (eq:pred_mu), P <- F P F^T + Phi(Omega) G diag(sigma^2) G^T Phi(Omega)^T
 *            (eq:pred_cov), then the angle-variance cap (std of theta and omega at most pi);
 *   update:  K = P H^T S^-1, nu = alpha K (z - (x, y)) (eq:K) with the gain damping alpha = min(1, pi/max|nu_theta,omega|),
 *            mu <- mu exp(nu) (eq:up_mu), P <- Phi(nu) P_J Phi(nu)^T (eq:up_P).
 * The covariance uses P_J = P - beta K (H P), beta = alpha (2 - alpha): in exact arithmetic this IS the Joseph form
 * (I - aKH) P (I - aKH)^T + a^2 K R K^T for the damped gain aK, because K S K^T = K H P; only the upper triangle is
 * computed (symmetric by construction).  omega is carried as omega + nu_omega wrapped to (-pi, pi] (exact: the angle
 * of R_omega R_nu), no atan2 in the step.  The Taylor branches of sinc, cosc, sinc2, cosc2 are those of
 * generated/special.py.  After the update the LDL^T positive-definiteness test of generated covariance_is_pd runs,
 * as in the generated step; on failure the C adds the diagonal jitter of repair_pd (the generated step first redoes
 * the update in Joseph form): never triggered in the benchmark.
 *
 * State s: [x, y, cos th, sin th, vx, vy, omega, cos omega, sin omega]; p: packed upper triangle (21), row-major.
 * Compiled at benchmark time: cc -O3 -march=native -fopenmp -shared -fPIC.
 */
#include <math.h>
#include <stddef.h>

static inline double sinc_(double x, double s) {
    if (fabs(x) < 1e-4) { double x2 = x * x; return 1.0 + x2 * (-0.16666666666666666 + x2 * (0.008333333333333333 + x2 * (-0.0001984126984126984))); }
    return s / x;
}
static inline double cosc_(double x, double s, double c) {
    if (fabs(x) < 1e-4) { double x2 = x * x; return x * (0.5 + x2 * (-0.041666666666666664 + x2 * (0.001388888888888889 + x2 * (-2.48015873015873e-05)))); }
    return c > 0.0 ? (s * s / (1.0 + c)) / x : (1.0 - c) / x;
}
static inline double sinc2_(double x, double s) {
    if (fabs(x) < 0.75) { double x2 = x * x; return x * (0.16666666666666666 + x2 * (-0.008333333333333333 + x2 * (0.0001984126984126984 + x2 * (-2.7557319223985893e-06 + x2 * (2.505210838544172e-08 + x2 * (-1.6059043836821613e-10 + x2 * (7.647163731819816e-13 + x2 * (-2.8114572543455206e-15)))))))); }
    return (x - s) / (x * x);
}
static inline double cosc2_(double x, double s, double c) {
    if (fabs(x) < 1e-4) { double x2 = x * x; return 0.5 + x2 * (-0.041666666666666664 + x2 * (0.001388888888888889 + x2 * (-2.48015873015873e-05))); }
    return c > 0.0 ? (s / x) * (s / x) / (1.0 + c) : (1.0 - c) / (x * x);
}
static inline double wrap_(double a) {
    if (a > M_PI) a -= 2.0 * M_PI;
    else if (a <= -M_PI) a += 2.0 * M_PI;
    return a;
}

/* LDL^T test of generated covariance_is_pd: every pivot > 1e-13 max_i P_ii (NaN fails) */
static inline int covariance_is_pd(const double *p) {
    const double p00 = p[0], p01 = p[1], p02 = p[2], p03 = p[3], p04 = p[4], p05 = p[5], p11 = p[6], p12 = p[7],
                 p13 = p[8], p14 = p[9], p15 = p[10], p22 = p[11], p23 = p[12], p24 = p[13], p25 = p[14], p33 = p[15],
                 p34 = p[16], p35 = p[17], p44 = p[18], p45 = p[19], p55 = p[20];
    const double tol = 1e-13 * fmax(fmax(fmax(p00, p11), fmax(p22, p33)), fmax(p44, p55));
    const double d0 = p00;
    if (!(d0 > tol)) return 0;
    const double r0 = 1.0 / d0;
    const double l10 = p01 * r0, l20 = p02 * r0, l30 = p03 * r0, l40 = p04 * r0, l50 = p05 * r0;
    const double d1 = p11 - l10 * l10 * d0;
    if (!(d1 > tol)) return 0;
    const double r1 = 1.0 / d1;
    const double l21 = (p12 - l20 * l10 * d0) * r1, l31 = (p13 - l30 * l10 * d0) * r1, l41 = (p14 - l40 * l10 * d0) * r1,
                 l51 = (p15 - l50 * l10 * d0) * r1;
    const double d2 = p22 - l20 * l20 * d0 - l21 * l21 * d1;
    if (!(d2 > tol)) return 0;
    const double r2 = 1.0 / d2;
    const double l32 = (p23 - l30 * l20 * d0 - l31 * l21 * d1) * r2, l42 = (p24 - l40 * l20 * d0 - l41 * l21 * d1) * r2,
                 l52 = (p25 - l50 * l20 * d0 - l51 * l21 * d1) * r2;
    const double d3 = p33 - l30 * l30 * d0 - l31 * l31 * d1 - l32 * l32 * d2;
    if (!(d3 > tol)) return 0;
    const double r3 = 1.0 / d3;
    const double l43 = (p34 - l40 * l30 * d0 - l41 * l31 * d1 - l42 * l32 * d2) * r3,
                 l53 = (p35 - l50 * l30 * d0 - l51 * l31 * d1 - l52 * l32 * d2) * r3;
    const double d4 = p44 - l40 * l40 * d0 - l41 * l41 * d1 - l42 * l42 * d2 - l43 * l43 * d3;
    if (!(d4 > tol)) return 0;
    const double r4 = 1.0 / d4;
    const double l54 = (p45 - l50 * l40 * d0 - l51 * l41 * d1 - l52 * l42 * d2 - l53 * l43 * d3) * r4;
    const double d5 = p55 - l50 * l50 * d0 - l51 * l51 * d1 - l52 * l52 * d2 - l53 * l53 * d3 - l54 * l54 * d4;
    return d5 > tol;
}

static void repair_pd(double *p) {
    static const int diag[6] = {0, 6, 11, 15, 18, 20};
    double scale = 0.0;
    for (int i = 0; i < 6; i++) scale = fmax(scale, fabs(p[diag[i]]));
    double delta = 1e-13 * scale;
    for (int it = 0; it < 60 && !covariance_is_pd(p); it++) {
        for (int i = 0; i < 6; i++) p[diag[i]] += delta;
        delta *= 4.0;
    }
}

static inline void predict(double *restrict s, double *restrict p, double dt, double sx2, double sy2, double sw2) {
    const double x = s[0], y = s[1], ct = s[2], st = s[3], vx = s[4], vy = s[5], w = s[6], cw = s[7], sw = s[8];
    const double p00 = p[0], p01 = p[1], p02 = p[2], p03 = p[3], p04 = p[4], p05 = p[5], p11 = p[6], p12 = p[7],
                 p13 = p[8], p14 = p[9], p15 = p[10], p22 = p[11], p23 = p[12], p24 = p[13], p25 = p[14], p33 = p[15],
                 p34 = p[16], p35 = p[17], p44 = p[18], p45 = p[19], p55 = p[20];
    const double a = dt * w, sa = sin(a), ca = cos(a);
    const double sc = sinc_(a, sa), co = cosc_(a, sa, ca), sc2 = sinc2_(a, sa), co2 = cosc2_(a, sa, ca);
    const double t2 = dt * vx, t4 = dt * vy, h = 0.5 * dt * dt;
    const double t3 = co * t2, t5 = sc * t4, t7 = co * t4;
    const double t6 = sc2 * t2 - co2 * t4, t8 = co2 * t2 + sc2 * t4;
    const double t12 = sc * t2 - t7, t13 = t3 + t5;
    /* calC columns 3, 4 of rows 0, 1: dt R_omega-like entries */
    const double c03 = cw * dt, c04 = -dt * sw, c13 = dt * sw, c14 = cw * dt;
    /* F rows 0, 1 (row 2 = e2 + dt e5, rows 3..5 identity) */
    const double f00 = ca, f01 = sa, f02 = t3 - t5, f03 = co * c13 + sc * c03, f04 = co * c14 + sc * c04, f05 = t6 * dt;
    const double f10 = -sa, f11 = ca, f12 = sc * t2 + t7, f13 = sc * c13 - co * c03, f14 = sc * c14 - co * c04, f15 = t8 * dt;
    /* Phi(Omega) G rows 0..2 (rows 3..5 = dt I) */
    const double g00 = sc * h, g01 = co * h, g02 = t6 * h, g10 = -g01, g11 = g00, g12 = t8 * h, g22 = h;
    /* mean */
    s[0] = t12 * ct - t13 * st + x;
    s[1] = t12 * st + t13 * ct + y;
    s[2] = ca * ct - sa * st;
    s[3] = ca * st + sa * ct;
    /* M = F P, rows 0 and 1 */
    const double m00 = f00 * p00 + f01 * p01 + f02 * p02 + f03 * p03 + f04 * p04 + f05 * p05;
    const double m01 = f00 * p01 + f01 * p11 + f02 * p12 + f03 * p13 + f04 * p14 + f05 * p15;
    const double m02 = f00 * p02 + f01 * p12 + f02 * p22 + f03 * p23 + f04 * p24 + f05 * p25;
    const double m03 = f00 * p03 + f01 * p13 + f02 * p23 + f03 * p33 + f04 * p34 + f05 * p35;
    const double m04 = f00 * p04 + f01 * p14 + f02 * p24 + f03 * p34 + f04 * p44 + f05 * p45;
    const double m05 = f00 * p05 + f01 * p15 + f02 * p25 + f03 * p35 + f04 * p45 + f05 * p55;
    const double m10 = f10 * p00 + f11 * p01 + f12 * p02 + f13 * p03 + f14 * p04 + f15 * p05;
    const double m11 = f10 * p01 + f11 * p11 + f12 * p12 + f13 * p13 + f14 * p14 + f15 * p15;
    const double m12 = f10 * p02 + f11 * p12 + f12 * p22 + f13 * p23 + f14 * p24 + f15 * p25;
    const double m13 = f10 * p03 + f11 * p13 + f12 * p23 + f13 * p33 + f14 * p34 + f15 * p35;
    const double m14 = f10 * p04 + f11 * p14 + f12 * p24 + f13 * p34 + f14 * p44 + f15 * p45;
    const double m15 = f10 * p05 + f11 * p15 + f12 * p25 + f13 * p35 + f14 * p45 + f15 * p55;
    const double m22 = p22 + dt * p25, m23 = p23 + dt * p35, m24 = p24 + dt * p45, m25 = p25 + dt * p55;
    const double qx0 = sx2 * g00, qy0 = sy2 * g01, qw0 = sw2 * g02, qw1 = sw2 * g12;
    double n[21];
    n[0] = qx0 * g00 + qy0 * g01 + qw0 * g02 + f00 * m00 + f01 * m01 + f02 * m02 + f03 * m03 + f04 * m04 + f05 * m05;
    n[1] = qx0 * g10 + qy0 * g11 + qw0 * g12 + f10 * m00 + f11 * m01 + f12 * m02 + f13 * m03 + f14 * m04 + f15 * m05;
    n[2] = qw0 * g22 + dt * m05 + m02;
    n[3] = qx0 * dt + m03;
    n[4] = qy0 * dt + m04;
    n[5] = qw0 * dt + m05;
    n[6] = sx2 * g10 * g10 + sy2 * g11 * g11 + qw1 * g12 + f10 * m10 + f11 * m11 + f12 * m12 + f13 * m13 + f14 * m14 + f15 * m15;
    n[7] = qw1 * g22 + dt * m15 + m12;
    n[8] = sx2 * dt * g10 + m13;
    n[9] = sy2 * dt * g11 + m14;
    n[10] = qw1 * dt + m15;
    n[11] = sw2 * g22 * g22 + dt * m25 + m22;
    n[12] = m23;
    n[13] = m24;
    n[14] = sw2 * dt * g22 + m25;
    n[15] = sx2 * dt * dt + p33;
    n[16] = p34;
    n[17] = p35;
    n[18] = sy2 * dt * dt + p44;
    n[19] = p45;
    n[20] = sw2 * dt * dt + p55;
    /* angle-variance cap (inactive while the std is at most pi) */
    if (n[11] > M_PI * M_PI) {
        const double f = M_PI / sqrt(n[11]);
        n[2] *= f; n[7] *= f; n[12] *= f; n[13] *= f; n[14] *= f; n[11] = M_PI * M_PI;
    }
    if (n[20] > M_PI * M_PI) {
        const double f = M_PI / sqrt(n[20]);
        n[5] *= f; n[10] *= f; n[14] *= f; n[17] *= f; n[19] *= f; n[20] = M_PI * M_PI;
    }
    for (int i = 0; i < 21; i++) p[i] = n[i];
}

static inline double update_position(double *restrict s, double *restrict p, double zx, double zy, double r2) {
    const double x = s[0], y = s[1], ct = s[2], st = s[3], vx = s[4], vy = s[5], w = s[6], cw = s[7], sw = s[8];
    const double p00 = p[0], p01 = p[1], p02 = p[2], p03 = p[3], p04 = p[4], p05 = p[5], p11 = p[6], p12 = p[7],
                 p13 = p[8], p14 = p[9], p15 = p[10], p22 = p[11], p23 = p[12], p24 = p[13], p25 = p[14], p33 = p[15],
                 p34 = p[16], p35 = p[17], p44 = p[18], p45 = p[19], p55 = p[20];
    /* H P (H = [R_theta^T-rotated rows: [c -s; s c] on (x, y)]) */
    const double h00 = ct * p00 - st * p01, h01 = ct * p01 - st * p11, h02 = ct * p02 - st * p12,
                 h03 = ct * p03 - st * p13, h04 = ct * p04 - st * p14, h05 = ct * p05 - st * p15;
    const double h10 = st * p00 + ct * p01, h11 = st * p01 + ct * p11, h12 = st * p02 + ct * p12,
                 h13 = st * p03 + ct * p13, h14 = st * p04 + ct * p14, h15 = st * p05 + ct * p15;
    const double S00 = r2 + ct * h00 - st * h01, S01 = ct * h01 + st * h00, S11 = r2 + st * h10 + ct * h11;
    const double rd = 1.0 / (S00 * S11 - S01 * S01);
    const double i00 = S11 * rd, i01 = -S01 * rd, i11 = S00 * rd;
    const double e0 = zx - x, e1 = zy - y;
    const double nis = i00 * e0 * e0 + 2.0 * i01 * e0 * e1 + i11 * e1 * e1;
    /* K = (H P)^T S^-1 */
    const double k00 = i00 * h00 + i01 * h10, k01 = i01 * h00 + i11 * h10;
    const double k10 = i00 * h01 + i01 * h11, k11 = i01 * h01 + i11 * h11;
    const double k20 = i00 * h02 + i01 * h12, k21 = i01 * h02 + i11 * h12;
    const double k30 = i00 * h03 + i01 * h13, k31 = i01 * h03 + i11 * h13;
    const double k40 = i00 * h04 + i01 * h14, k41 = i01 * h04 + i11 * h14;
    const double k50 = i00 * h05 + i01 * h15, k51 = i01 * h05 + i11 * h15;
    const double n0 = k00 * e0 + k01 * e1, n1 = k10 * e0 + k11 * e1, n2 = k20 * e0 + k21 * e1;
    const double n3 = k30 * e0 + k31 * e1, n4 = k40 * e0 + k41 * e1, n5 = k50 * e0 + k51 * e1;
    const double mx = fmax(fabs(n2), fabs(n5));
    const double al = mx <= M_PI ? 1.0 : M_PI / mx;
    const double be = al * (2.0 - al);
    const double u0 = al * n0, u1 = al * n1, u2 = al * n2, u3 = al * n3, u4 = al * n4, u5 = al * n5;
    /* P_J = P - beta K (H P), upper triangle */
    const double b00 = be * k00, b01 = be * k01, b10 = be * k10, b11 = be * k11, b20 = be * k20, b21 = be * k21,
                 b30 = be * k30, b31 = be * k31, b40 = be * k40, b41 = be * k41, b50 = be * k50, b51 = be * k51;
    const double j00 = p00 - b00 * h00 - b01 * h10, j01 = p01 - b00 * h01 - b01 * h11, j02 = p02 - b00 * h02 - b01 * h12,
                 j03 = p03 - b00 * h03 - b01 * h13, j04 = p04 - b00 * h04 - b01 * h14, j05 = p05 - b00 * h05 - b01 * h15;
    const double j11 = p11 - b10 * h01 - b11 * h11, j12 = p12 - b10 * h02 - b11 * h12, j13 = p13 - b10 * h03 - b11 * h13,
                 j14 = p14 - b10 * h04 - b11 * h14, j15 = p15 - b10 * h05 - b11 * h15;
    const double j22 = p22 - b20 * h02 - b21 * h12, j23 = p23 - b20 * h03 - b21 * h13, j24 = p24 - b20 * h04 - b21 * h14,
                 j25 = p25 - b20 * h05 - b21 * h15;
    const double j33 = p33 - b30 * h03 - b31 * h13, j34 = p34 - b30 * h04 - b31 * h14, j35 = p35 - b30 * h05 - b31 * h15;
    const double j44 = p44 - b40 * h04 - b41 * h14, j45 = p45 - b40 * h05 - b41 * h15;
    const double j55 = p55 - b50 * h05 - b51 * h15;
    /* Phi(nu): two SE(2) blocks [[sinc, cosc, a02], [-cosc, sinc, a12], [0, 0, 1]] */
    const double s2 = sin(u2), c2 = cos(u2), s5 = sin(u5), c5 = cos(u5);
    const double sa = sinc_(u2, s2), ca = cosc_(u2, s2, c2), sa2 = sinc2_(u2, s2), ca2 = cosc2_(u2, s2, c2);
    const double sb = sinc_(u5, s5), cb = cosc_(u5, s5, c5), sb2 = sinc2_(u5, s5), cb2 = cosc2_(u5, s5, c5);
    const double a02 = sa2 * u0 - ca2 * u1, a12 = ca2 * u0 + sa2 * u1;
    const double d02 = sb2 * u3 - cb2 * u4, d12 = cb2 * u3 + sb2 * u4;
    /* mean: mu exp(nu) */
    const double tx = sa * u0 - ca * u1, ty = ca * u0 + sa * u1;
    const double tv = sb * u3 - cb * u4, tw = cb * u3 + sb * u4;
    s[0] = x + tx * ct - ty * st;
    s[1] = y + tx * st + ty * ct;
    s[2] = c2 * ct - s2 * st;
    s[3] = c2 * st + s2 * ct;
    s[4] = vx + tv * cw - tw * sw;
    s[5] = vy + tv * sw + tw * cw;
    s[6] = wrap_(w + u5);
    s[7] = c5 * cw - s5 * sw;
    s[8] = c5 * sw + s5 * cw;
    /* C = Phi P_J: rows 0, 1 (cols 0..5) and rows 3, 4 (cols 3..5) */
    const double q00 = sa * j00 + ca * j01 + a02 * j02, q01 = sa * j01 + ca * j11 + a02 * j12, q02 = sa * j02 + ca * j12 + a02 * j22,
                 q03 = sa * j03 + ca * j13 + a02 * j23, q04 = sa * j04 + ca * j14 + a02 * j24, q05 = sa * j05 + ca * j15 + a02 * j25;
    const double q10 = sa * j01 - ca * j00 + a12 * j02, q11 = sa * j11 - ca * j01 + a12 * j12, q12 = sa * j12 - ca * j02 + a12 * j22,
                 q13 = sa * j13 - ca * j03 + a12 * j23, q14 = sa * j14 - ca * j04 + a12 * j24, q15 = sa * j15 - ca * j05 + a12 * j25;
    const double q33 = sb * j33 + cb * j34 + d02 * j35, q34 = sb * j34 + cb * j44 + d02 * j45, q35 = sb * j35 + cb * j45 + d02 * j55;
    const double q43 = sb * j34 - cb * j33 + d12 * j35, q44 = sb * j44 - cb * j34 + d12 * j45, q45 = sb * j45 - cb * j35 + d12 * j55;
    /* P = C Phi^T (upper triangle) */
    p[0] = q00 * sa + q01 * ca + q02 * a02;
    p[1] = q01 * sa - q00 * ca + q02 * a12;
    p[2] = q02;
    p[3] = q03 * sb + q04 * cb + q05 * d02;
    p[4] = q04 * sb - q03 * cb + q05 * d12;
    p[5] = q05;
    p[6] = q11 * sa - q10 * ca + q12 * a12;
    p[7] = q12;
    p[8] = q13 * sb + q14 * cb + q15 * d02;
    p[9] = q14 * sb - q13 * cb + q15 * d12;
    p[10] = q15;
    p[11] = j22;
    p[12] = sb * j23 + cb * j24 + d02 * j25;
    p[13] = sb * j24 - cb * j23 + d12 * j25;
    p[14] = j25;
    p[15] = q33 * sb + q34 * cb + q35 * d02;
    p[16] = q34 * sb - q33 * cb + q35 * d12;
    p[17] = q35;
    p[18] = q44 * sb - q43 * cb + q45 * d12;
    p[19] = q45;
    p[20] = j55;
    if (!covariance_is_pd(p)) repair_pd(p);
    return nis;
}

static void run_one(const double *z, const double *dts, const double *x0, const double *p0, const double *q, double r,
                    long K, double *out_x, double *out_p, double *out_nis) {
    double s[9], p[21];
    s[0] = x0[0]; s[1] = x0[1]; s[2] = cos(x0[2]); s[3] = sin(x0[2]); s[4] = x0[3]; s[5] = x0[4];
    s[7] = cos(x0[5]); s[8] = sin(x0[5]); s[6] = atan2(s[8], s[7]);
    for (int i = 0; i < 21; i++) p[i] = p0[i];
    const double sx2 = q[0] * q[0], sy2 = q[1] * q[1], sw2 = q[2] * q[2], r2 = r * r;
    for (long k = 0; k < K; k++) {
        predict(s, p, dts[k], sx2, sy2, sw2);
        const double zx = z[2 * k], zy = z[2 * k + 1];
        out_nis[k] = (isnan(zx) || isnan(zy)) ? NAN : update_position(s, p, zx, zy, r2);
        double *o = out_x + 6 * k;
        o[0] = s[0]; o[1] = s[1]; o[2] = atan2(s[3], s[2]); o[3] = s[4]; o[4] = s[5]; o[5] = s[6];
        if (out_p) for (int i = 0; i < 21; i++) out_p[21 * k + i] = p[i];
    }
}

/* one trajectory: z (K, 2), dts (K,), x0 (6,), p0 (21,), q (3,) stds, r std; out_x (K, 6), out_p (K, 21) or NULL, out_nis (K,) */
void se2se2_run_one_position(const double *z, const double *dts, const double *x0, const double *p0, const double *q,
                             double r, long K, double *out_x, double *out_p, double *out_nis) {
    run_one(z, dts, x0, p0, q, r, K, out_x, out_p, out_nis);
}

/* B trajectories, OpenMP over trajectories (static schedule, like numba's prange): z (B, K, 2), dts (B, K), x0 (B, 6),
   p0 (B, 21); out_x (B, K, 6), out_p (B, K, 21) or NULL, out_nis (B, K) */
void se2se2_run_batch_position(const double *z, const double *dts, const double *x0, const double *p0, const double *q,
                               double r, long B, long K, double *out_x, double *out_p, double *out_nis) {
    #pragma omp parallel for schedule(static)
    for (long b = 0; b < B; b++)
        run_one(z + 2 * K * b, dts + K * b, x0 + 6 * b, p0 + 21 * b, q, r, K, out_x + 6 * K * b,
                out_p ? out_p + 21 * K * b : NULL, out_nis + K * b);
}
